//! What a goal may change: the atoms the plans for it may make true or false, transitively
//! through their subgoals, as the `precondition` check applies them at a subgoal step.
//!
//! A summary is directional: an atom that the plans may only add can only become true (if it
//! was true it stays true), one they may only delete can only become false, one they may do
//! both to may end either way, and every other atom keeps its value. The atoms of an action
//! step are those of every ground action its term can be (a variable argument matches every
//! object), so the summary over-approximates what really happens: sound for "may fail".

use crate::model::atoms::AtomId;
use crate::model::ground::GroundAction;
use crate::model::plans::{BodyStep, Step};
use crate::model::project::Project;
use crate::model::term::Term;
use crate::syntax::ast::{TriggerKind, TriggerOp};
use std::collections::{BTreeMap, BTreeSet};

/// Atoms that may become true and atoms that may become false.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Effects {
    /// May be added.
    pub add: BTreeSet<AtomId>,
    /// May be deleted.
    pub del: BTreeSet<AtomId>,
}

impl Effects {
    /// Adds everything `other` may do; returns whether anything was new.
    pub fn absorb(&mut self, other: &Effects) -> bool {
        let before = (self.add.len(), self.del.len());
        self.add.extend(other.add.iter().copied());
        self.del.extend(other.del.iter().copied());
        before != (self.add.len(), self.del.len())
    }

    /// Every atom that may change, in order.
    pub fn touched(&self) -> BTreeSet<AtomId> {
        self.add.union(&self.del).copied().collect()
    }

    /// Whether nothing may change.
    pub fn is_empty(&self) -> bool {
        self.add.is_empty() && self.del.is_empty()
    }
}

/// The summary of every achievement goal `name/arity` that has plans.
#[derive(Clone, Debug, Default)]
pub struct Summaries {
    goals: BTreeMap<(String, usize), Effects>,
}

impl Summaries {
    /// Summaries of every goal of the project, to a fixed point (goals may be recursive).
    /// Both `+!g` and `-!g` plans count: a handled failure continues the caller.
    pub fn compute(project: &Project) -> Summaries {
        let mut s = Summaries::default();
        for p in &project.plans.plans {
            if p.trigger.kind == TriggerKind::Achieve && p.trigger.op != TriggerOp::GoalState {
                if let Some(f) = p.trigger.literal.functor() {
                    s.goals
                        .entry((f.to_string(), p.trigger.literal.arity()))
                        .or_default();
                }
            }
        }
        loop {
            let mut changed = false;
            for p in &project.plans.plans {
                if p.trigger.kind != TriggerKind::Achieve || p.trigger.op == TriggerOp::GoalState {
                    continue;
                }
                let Some(f) = p.trigger.literal.functor() else {
                    continue;
                };
                let key = (f.to_string(), p.trigger.literal.arity());
                let eff = s.steps(project, &p.body);
                if let Some(e) = s.goals.get_mut(&key) {
                    changed |= e.absorb(&eff);
                }
            }
            if !changed {
                return s;
            }
        }
    }

    /// What the goal `name/arity` may change (`None`: it has no plan).
    pub fn goal(&self, name: &str, arity: usize) -> Option<&Effects> {
        self.goals.get(&(name.to_string(), arity))
    }

    /// What a list of body steps may change, with the current goal summaries.
    pub fn steps(&self, project: &Project, steps: &[Step]) -> Effects {
        let mut out = Effects::default();
        for s in steps {
            match &s.kind {
                BodyStep::Action(t) => {
                    for g in matching_actions(project, t) {
                        for e in &g.effects {
                            out.add.extend(e.add.iter().copied());
                            out.del.extend(e.del.iter().copied());
                        }
                    }
                }
                BodyStep::Achieve { goal, .. } => {
                    if let Some(e) = goal
                        .functor()
                        .and_then(|f| self.goals.get(&(f.to_string(), goal.arity())))
                    {
                        out.absorb(e);
                    }
                }
                BodyStep::AddBel(t) => out.add.extend(matching_atoms(project, t)),
                BodyStep::DelBel(t) => out.del.extend(matching_atoms(project, t)),
                BodyStep::DelAddBel(t) => {
                    out.add.extend(matching_atoms(project, t));
                    out.del.extend(same_predicate_atoms(project, t));
                }
                BodyStep::If {
                    branches,
                    else_body,
                } => {
                    for (_, b) in branches {
                        out.absorb(&self.steps(project, b));
                    }
                    out.absorb(&self.steps(project, else_body));
                }
                BodyStep::While(_, b) | BodyStep::For(_, b) => {
                    out.absorb(&self.steps(project, b));
                }
                BodyStep::Internal(_)
                | BodyStep::Test(_)
                | BodyStep::Constraint(..)
                | BodyStep::Wait { .. }
                | BodyStep::Library { .. } => {}
            }
        }
        out
    }
}

/// Whether a term argument can be the object `o` (variables match anything).
fn arg_matches(project: &Project, t: &Term, o: crate::model::ObjectId) -> bool {
    match t {
        Term::Var(_) => true,
        Term::Atom(name) => project.universe.object(name) == Some(o),
        _ => false,
    }
}

/// The ground actions an action term of a plan body can be.
pub fn matching_actions<'p>(
    project: &'p Project,
    t: &'p Term,
) -> impl Iterator<Item = &'p GroundAction> + 'p {
    let name = t.functor().unwrap_or("");
    project.actions.all().iter().filter(move |g| {
        &*g.name == name
            && g.args.len() == t.arity()
            && t.args()
                .iter()
                .zip(&g.args)
                .all(|(a, o)| arg_matches(project, a, *o))
    })
}

/// The atoms a belief term of a plan body can be.
pub fn matching_atoms(project: &Project, t: &Term) -> Vec<AtomId> {
    let atoms = &project.atoms;
    let Some(p) = atoms.pred_of_literal(t) else {
        return Vec::new();
    };
    atoms
        .atoms_of(p)
        .filter(|a| {
            let (_, args) = atoms.decode(*a);
            args.len() == t.arity()
                && t.args()
                    .iter()
                    .zip(args.iter())
                    .all(|(x, o)| arg_matches(project, x, *o))
        })
        .collect()
}

/// Every atom of the predicate of `t` (what `-+t` may remove).
pub fn same_predicate_atoms(project: &Project, t: &Term) -> Vec<AtomId> {
    let atoms = &project.atoms;
    match atoms.pred_of_literal(t) {
        Some(p) if atoms.pred_params(p).len() == t.arity() => atoms.atoms_of(p).collect(),
        _ => Vec::new(),
    }
}
