//! The two algorithms bound to a loaded project: its users, its phrases, and Algorithm 2 on
//! the intention stack an action of the reasoning cycle ran in.
//!
//! `explain --scenario`, the catalogue and the explanation properties of `verify` all go
//! through [`Explainer`], so that what the robot would say and what is verified are one
//! computation.

use super::content::{
    content, Content, ContextLiteral, Effects, FrameSnapshot, PlanStep, Semantic, Syntactic,
};
use super::demand::{ExpectedSuccessors, Pair};
use super::render::{sentence, Phrases};
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::plans::BodyStep;
use crate::model::project::Project;
use crate::model::{unify, Converter, Substitution, Term};
use crate::semantics::{FrameView, Semantics};
use crate::syntax::ast::StepKind;
use crate::syntax::manifest::Modifies;
use crate::syntax::{Diagnostic, Span};

/// A user of the manifest (`[explanation.users.NAME]`) and their initial `N`.
#[derive(Clone, Debug)]
pub struct User {
    /// The user's name.
    pub name: String,
    /// `N_0`: the user's `expected` patterns.
    pub expected: ExpectedSuccessors,
    /// Where the manifest names the user.
    pub span: Span,
}

/// The manifest's users (only `only`, when given). Fails when the manifest has no
/// `[explanation]` section, a pair is not an action or a request, or `only` names nobody.
pub fn users(p: &Project, only: Option<&str>) -> Result<Vec<User>, Vec<Diagnostic>> {
    let Some(ex) = &p.manifest.explanation else {
        return Err(vec![Diagnostic::error(
            "input",
            "the manifest has no `[explanation]` section",
        )
        .in_file(p.manifest.path.display().to_string())
        .with_help(
            "add `[explanation.users.NAME]` with the user's `expected` pairs",
        )]);
    };
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for u in &ex.users {
        if only.is_some_and(|o| o != u.name.value) {
            continue;
        }
        let mut pairs = Vec::new();
        for pair in &u.expected {
            match Pair::from_steps(&pair.before.step, &pair.after.step) {
                Ok(p) => pairs.push(p),
                Err(e) => errors.push(Diagnostic::error("input", e).with_label(pair.span, "here")),
            }
        }
        out.push(User {
            name: u.name.value.clone(),
            expected: ExpectedSuccessors::new(pairs),
            span: u.name.span,
        });
    }
    if let Some(o) = only {
        if out.is_empty() {
            errors.push(
                Diagnostic::error("input", format!("the manifest has no user `{o}`"))
                    .in_file(p.manifest.path.display().to_string()),
            );
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

/// The phrases of `[explanation.phrases]`.
pub fn phrases(p: &Project) -> Phrases {
    let mut ph = Phrases::new(Vec::new());
    for entry in p.manifest.explanation.iter().flat_map(|e| &e.phrases) {
        let mut c = Converter::new();
        match &entry.pattern.step.kind {
            StepKind::Achieve(e) => {
                if let Ok(t) = c.term(e) {
                    ph.push_goal(t, &entry.template.value);
                }
            }
            StepKind::Action(e) => {
                if let Ok(t) = c.term(e) {
                    ph.push(t, &entry.template.value);
                }
            }
            _ => {}
        }
    }
    ph
}

/// An explanation as Algorithm 2 builds it for an action of a run.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Explanation {
    /// `(Γ, (a_i, …, a_k))`, shared with the explanations given from it: a user's search
    /// gives it at every transition that explains the action on these beliefs.
    pub content: std::sync::Arc<Content>,
    /// The block of the top frame's body that the action belongs to.
    pub block: u16,
    /// The position in that block of each step of `content.actions`.
    pub positions: Vec<u16>,
    /// The position of the block's last action or subgoal: where the content ends when no
    /// step modifies `Γ`.
    pub last: u16,
}

/// Algorithm 2 (and the sentence) for the actions of one project's runs.
pub struct Explainer<'p> {
    project: &'p Project,
    sem: &'p Semantics<'p>,
    semantic: bool,
    /// The project's phrases.
    pub phrases: Phrases,
}

impl<'p> Explainer<'p> {
    /// For `project`, with the manifest's `modifies`.
    pub fn new(project: &'p Project, sem: &'p Semantics<'p>) -> Explainer<'p> {
        let semantic = project
            .manifest
            .explanation
            .as_ref()
            .is_some_and(|e| e.modifies == Modifies::Semantic);
        Explainer {
            project,
            sem,
            semantic,
            phrases: phrases(project),
        }
    }

    /// The stack an action ran in (bottom first, as [`crate::semantics::Note::Action`]
    /// carries it), as Algorithm 2 reads it, with the top frame's block and the positions of
    /// its steps.
    pub fn snapshot(&self, stack: &[FrameView]) -> (Vec<FrameSnapshot>, u16, Vec<u16>) {
        let top = stack.len().saturating_sub(1);
        let mut positions = Vec::new();
        let mut at_block = 0;
        let frames = stack
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let plan = self.sem.plan(f.plan);
                let mut body = Vec::new();
                if i == top {
                    let (block, pos) = f.at;
                    at_block = block;
                    for (k, s) in self.sem.block(f.plan, block).iter().enumerate() {
                        let step = match &s.kind {
                            // The agent's own explanations are not steps the user watches.
                            BodyStep::Action(t) if self.sem.is_emission(t) => continue,
                            BodyStep::Action(t) => PlanStep::Action(t.clone()),
                            BodyStep::Achieve { goal, .. } => PlanStep::Subgoal(goal.clone()),
                            _ => continue,
                        };
                        if k >= pos as usize {
                            body.push(step);
                            positions.push(k as u16);
                        }
                    }
                }
                FrameSnapshot {
                    context: ContextLiteral::of_formula(&plan.context),
                    bindings: f.subst.clone(),
                    body,
                }
            })
            .collect();
        (frames, at_block, positions)
    }

    /// Whether Algorithm 2 reads the beliefs (`modifies = "semantic"`): with "syntactic",
    /// [`Explainer::explain`] depends on the stack alone.
    pub fn is_semantic(&self) -> bool {
        self.semantic
    }

    /// Algorithm 2 for the action that ran on `stack` in a state with `beliefs` (before the
    /// action), with `modifies` as the manifest says.
    pub fn explain(&self, beliefs: &AtomSet, stack: &[FrameView]) -> Option<Explanation> {
        let (frames, block, positions) = self.snapshot(stack);
        let content = if self.semantic {
            let m = Semantic::new(
                beliefs,
                |s: &AtomSet, a: &Term| self.holds(s, a),
                |s: &AtomSet, a: &Term| self.apply(s, a),
            );
            content(&frames, &m)?
        } else {
            content(&frames, &Syntactic::new(|a: &Term| self.effects(a)))?
        };
        let last = *positions.last()?;
        let positions = positions[..content.actions.len()].to_vec();
        Some(Explanation {
            content: std::sync::Arc::new(content),
            block,
            positions,
            last,
        })
    }

    /// The sentence for `content`, explaining `action`.
    pub fn sentence(&self, action: &Term, content: &Content) -> String {
        sentence(action, content, &self.phrases)
    }

    /// `Eff+` and `Eff-` of a ground action: every atom any of its effects may add or delete.
    pub fn effects(&self, action: &Term) -> Effects {
        let p = self.project;
        let Some(ga) = p.actions.of_term(action, &p.universe) else {
            return Effects::none();
        };
        let term = |a: &crate::model::atoms::AtomId| p.atoms.term(*a, &p.universe);
        Effects::new(
            ga.effects
                .iter()
                .flat_map(|e| e.add.iter().map(term))
                .collect(),
            ga.effects
                .iter()
                .flat_map(|e| e.del.iter().map(term))
                .collect(),
        )
    }

    /// Whether an atom (possibly with variables: some instance) is believed in `s`.
    pub fn holds(&self, s: &AtomSet, atom: &Term) -> bool {
        let p = self.project;
        let Some(pred) = p.atoms.pred_of_literal(atom) else {
            return false;
        };
        let atom = atom.without_annots();
        p.atoms.atoms_of(pred).any(|a| {
            s.contains(a)
                && unify(
                    &atom,
                    &p.atoms.term(a, &p.universe),
                    &mut Substitution::new(),
                )
        })
    }

    /// The atoms `atom` unifies with: [`Explainer::holds`] is whether `s` has one of them.
    pub fn instances(&self, atom: &Term) -> Vec<AtomId> {
        let p = self.project;
        let Some(pred) = p.atoms.pred_of_literal(atom) else {
            return Vec::new();
        };
        let atom = atom.without_annots();
        p.atoms
            .atoms_of(pred)
            .filter(|&a| {
                unify(
                    &atom,
                    &p.atoms.term(a, &p.universe),
                    &mut Substitution::new(),
                )
            })
            .collect()
    }

    /// Whether a context literal is believed in `s`: `not p(X)` when no instance of `p(X)` is.
    pub fn literal_holds(&self, s: &AtomSet, l: &ContextLiteral) -> bool {
        self.holds(s, &l.atom) == l.positive
    }

    /// The state after a ground action (unchanged when the term is not one).
    pub fn apply(&self, s: &AtomSet, action: &Term) -> AtomSet {
        let p = self.project;
        match p.actions.of_term(action, &p.universe) {
            Some(ga) => ga.apply(s),
            None => s.clone(),
        }
    }
}
