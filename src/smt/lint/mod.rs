//! The static checks of `bdi-check lint` (SPEC §3), each decided with z3 on the grounded
//! model, and their findings.
//!
//! | check | question (states: every assignment of the atoms satisfying the invariants) | severity |
//! |---|---|---|
//! | `dead-plan` | no state and no event of the trigger's types makes the plan applicable | error |
//! | `shadowed-plan` | in every state and event where the plan is applicable, an earlier plan for the same trigger is too (one earlier plan, or several between them: the unsat core names them; `plan_selection = "first"` only) | error |
//! | `coverage-gap` | some state and some instance of an achievement goal leave no plan applicable | warning |
//! | `plan-overlap` | some state and event make two plans for the same trigger applicable | warning |
//! | `precondition` | along the plan body, executed symbolically from its context, an action's precondition may not hold | warning |
//! | `effect-conflict` | some binding of an action adds and deletes one atom, in a state where it can run | warning |
//! | `action-breaks-invariant` | from some state satisfying the invariants and the precondition, the action leaves a state that does not (the invariant is not inductive; `verify` settles whether a run breaks it) | warning |
//! | `undefined-action` | a plan calls an action that nothing defines | error |
//! | `undefined-predicate` | a test goal asks a predicate nothing defines (Jason just fails it) | warning |
//! | `unused-action` | no plan calls a PDDL action | note |
//! | `no-plan-for-goal` | a goal is posted (subgoal, initial goal, request) but no plan handles it | error |
//!
//! SPEC fixes the warnings: lint cannot know which states are reachable. The others:
//! a dead or shadowed plan can never run whichever states are reachable (the invariants hold
//! in every reachable state): nobody writes a plan meaning it never to run, so it is a
//! mistake (a contradictory context, plans in the wrong order) and an error; with
//! `plan_selection = "any"` an earlier applicable plan does not hide a later one, so
//! `shadowed-plan` is not checked. An action that breaks an invariant is
//! an error because every other check (and the user) relies on the invariants describing the
//! possible states: either the action's precondition or the invariant is wrong.
//! `effect-conflict` is a warning: PDDL defines the outcome (deletions first, so the atom ends
//! true) and some domains rely on it, though it usually means a missing inequality.
//! `unused-action` is a note: a domain may describe more than one plan library uses. A
//! posted goal without plans and an undefined action make the intention fail whenever they
//! are reached: errors (SPEC §2: exit 1).
//!
//! Every failing finding carries the state the solver found (`counterexample.initial`,
//! preferring an initial state of the manifest when there is one) and the literals at fault:
//! for a satisfiable question, a minimal set of the atoms' values in that state that forces
//! the answer (deletion over an unsat core); for an unsatisfiable one, the minimal set of
//! conjuncts and invariants in the unsat core. A dead plan has no state to show. An answer the
//! solver could not give within the budget, or a construct the encoding does not cover, is a
//! finding with status `unknown`. The findings that are not about states (`undefined-action`,
//! `unused-action`, `no-plan-for-goal`) point at the call, the action or the goal instead.

use super::encode::{and, Encoder, Val};
use super::solve::{int, truth, Outcome, Session, DEFAULT_RLIMIT};
use super::summary::Summaries;
use crate::findings::{Counterexample, Finding, Status};
use crate::model::atoms::AtomId;
use crate::model::from_ast::Converter;
use crate::model::plans::{BodyStep, Plan, Step};
use crate::model::project::Project;
use crate::model::subst::unifier;
use crate::model::term::Term;
use crate::model::universe::{ObjectId, TypeId};
use crate::syntax::ast::{ExprKind, TriggerKind, TriggerOp};
use crate::syntax::{Severity, Span};
use std::collections::BTreeSet;
use z3::ast::{Bool, Int};
use z3::Model;

mod actions;
mod names;
mod plans;

/// Options of a lint run.
#[derive(Clone, Debug)]
pub struct LintOptions {
    /// The z3 resource budget of each check (see [`DEFAULT_RLIMIT`]).
    pub rlimit: u32,
    /// No check is begun after this moment: the rest say `unknown` (`verify --timeout`).
    pub deadline: Option<std::time::Instant>,
}

impl Default for LintOptions {
    fn default() -> LintOptions {
        LintOptions {
            rlimit: DEFAULT_RLIMIT,
            deadline: None,
        }
    }
}

/// Every check of lint, in the order SPEC lists them.
pub const CHECKS: &[&str] = &[
    "dead-plan",
    "shadowed-plan",
    "coverage-gap",
    "plan-overlap",
    "precondition",
    "effect-conflict",
    "action-breaks-invariant",
    "undefined-action",
    "undefined-predicate",
    "unused-action",
    "no-plan-for-goal",
];

/// The severity of a lint check (see the module documentation).
pub fn severity(check: &str) -> Severity {
    match check {
        "coverage-gap"
        | "plan-overlap"
        | "precondition"
        | "effect-conflict"
        | "undefined-predicate"
        | "action-breaks-invariant" => Severity::Warning,
        "unused-action" => Severity::Note,
        _ => Severity::Error,
    }
}

/// A finding with what the human report needs to show its source.
#[derive(Clone, Debug, PartialEq)]
pub struct LintFinding {
    /// The finding of SPEC §3 (its `id` is made unique by [`lint`]; its `span` is the place
    /// it is about: a plan, a step, an action, a goal's mention).
    pub finding: Finding,
    /// Text under the caret.
    pub label: String,
    /// Other places (an earlier plan that shadows this one).
    pub secondary: Vec<(Span, String)>,
}

/// Lint encodes every ground atom as a z3 constant (about 4 KB each with its uses); past
/// this many, the solver checks are left undecided rather than run out of memory.
pub const MAX_LINT_ATOMS: usize = 100_000;

/// Runs every lint check on a loaded project, in a fresh z3 context of its own (so the
/// answers do not depend on what ran before). Findings come sorted by place.
pub fn lint(project: &Project, opts: &LintOptions) -> Vec<LintFinding> {
    let cfg = z3::Config::new();
    let mut out = z3::with_z3_config(&cfg, || Linter::new(project, opts).run());
    let map = &project.map;
    let key = |f: &LintFinding| {
        let loc = f.finding.location.clone();
        let check = CHECKS.iter().position(|c| *c == f.finding.check);
        (loc.map(|l| (l.file, l.line, l.column)), check)
    };
    out.sort_by_key(key);
    // Ids are `check:file:line`; two findings on one line get the column, then a number.
    let mut seen: BTreeSet<String> = BTreeSet::new();
    for f in &mut out {
        let mut id = f.finding.id.clone();
        if seen.contains(&id) {
            if let Some(span) = f.finding.span {
                id = format!("{id}:{}", map.location(span).column);
            }
            let base = id.clone();
            let mut n = 2;
            while seen.contains(&id) {
                id = format!("{base}-{n}");
                n += 1;
            }
        }
        seen.insert(id.clone());
        f.finding.id = id;
    }
    out
}

/// A static counterexample: a state (and the request that posts the goal, if users may
/// request it), no run.
fn state_cx(initial: Vec<String>, requests: Vec<String>) -> Counterexample {
    Counterexample {
        initial,
        requests,
        ..Counterexample::default()
    }
}

/// Plans for one trigger signature, in source order.
#[derive(Clone, Debug)]
pub(super) struct Group {
    pub op: TriggerOp,
    pub kind: TriggerKind,
    pub name: String,
    pub arity: usize,
    pub plans: Vec<usize>,
    /// The type of each argument of the events.
    pub types: Vec<TypeId>,
}

impl Group {
    /// `+!g(_,_)` for messages, with the event's arguments when known.
    pub fn event_text(&self, args: Option<&[String]>) -> String {
        let op = match self.op {
            TriggerOp::Add => "+",
            TriggerOp::Del => "-",
            TriggerOp::GoalState => "^",
        };
        let kind = match self.kind {
            TriggerKind::Belief => "",
            TriggerKind::Achieve => "!",
            TriggerKind::Test => "?",
        };
        let args = match args {
            Some(a) if !a.is_empty() => format!("({})", a.join(",")),
            None if self.arity > 0 => format!("({})", vec!["_"; self.arity].join(",")),
            _ => String::new(),
        };
        format!("{op}{kind}{}{args}", self.name)
    }
}

/// A solver over the base state with the invariants as tracked assumptions and a guard
/// that, when assumed, makes the base state an initial state of the manifest.
pub(super) struct Base {
    pub sess: Session,
    pub invs: Vec<(String, Bool)>,
    pub init: Bool,
}

impl Base {
    /// The invariants' assumption literals.
    pub fn inv_lits(&self) -> Vec<Bool> {
        self.invs.iter().map(|(_, b)| b.clone()).collect()
    }

    /// Checks `extra` (forgotten afterwards) under the invariants and `assumptions`; when
    /// satisfiable, prefers a model whose base state is an initial state (`true` then).
    pub fn witness(&self, extra: &Bool, assumptions: &[Bool]) -> (Outcome, bool) {
        self.sess.solver.push();
        self.sess.solver.assert(extra);
        let mut lits = self.inv_lits();
        lits.extend_from_slice(assumptions);
        let first = self.sess.check(&lits);
        let out = match first {
            Outcome::Sat(m) => {
                lits.push(self.init.clone());
                match self.sess.check(&lits) {
                    Outcome::Sat(m2) => (Outcome::Sat(m2), true),
                    _ => (Outcome::Sat(m), false),
                }
            }
            other => (other, false),
        };
        self.sess.solver.pop(1);
        out
    }
}

pub(super) struct Linter<'p> {
    pub p: &'p Project,
    pub opts: &'p LintOptions,
    pub enc: Encoder<'p>,
    pub sum: Summaries,
    out: Vec<LintFinding>,
}

impl<'p> Linter<'p> {
    fn new(p: &'p Project, opts: &'p LintOptions) -> Linter<'p> {
        Linter {
            p,
            opts,
            enc: if p.atoms.len() > MAX_LINT_ATOMS {
                Encoder::without_atoms(p)
            } else {
                Encoder::new(p)
            },
            sum: Summaries::compute(p),
            out: Vec::new(),
        }
    }

    /// A new solver with the invariants and the initial-state guard.
    pub fn base(&self) -> Base {
        let sess = Session::new(self.opts.rlimit, self.opts.deadline);
        let st = &self.enc.base;
        let invs = self
            .p
            .invariants
            .iter()
            .map(|(name, c)| {
                let lit = Bool::new_const(format!("invariant {name}"));
                sess.solver.assert(lit.implies(self.enc.cond(c, st)));
                (name.clone(), lit)
            })
            .collect();
        let init = Bool::new_const("initial state");
        let mut parts = Vec::new();
        let vary: BTreeSet<AtomId> = self.p.initial.vary.iter().copied().collect();
        for a in 0..self.p.atoms.len() as u32 {
            let a = AtomId(a);
            if self.p.initial.facts.contains(a) {
                parts.push(st[a.0 as usize].clone());
            } else if !vary.contains(&a) {
                parts.push(st[a.0 as usize].not());
            }
        }
        parts.extend(self.p.constraints.iter().map(|c| self.enc.cond(c, st)));
        sess.solver.assert(init.implies(and(parts)));
        Base { sess, invs, init }
    }

    /// Symbolic event arguments of a group, and their type constraints.
    pub fn event(&self, g: &Group) -> (Vec<Int>, Vec<Val>, Bool) {
        let ints: Vec<Int> = (0..g.arity)
            .map(|i| Int::new_const(format!("event argument {}", i + 1)))
            .collect();
        let dom = and(ints
            .iter()
            .zip(&g.types)
            .map(|(x, t)| self.enc.dom(x, *t))
            .collect());
        let vals = ints.iter().map(|x| Val::Sym(x.clone())).collect();
        (ints, vals, dom)
    }

    /// The objects the model gives the event arguments.
    fn event_objects(&self, m: &Model, ints: &[Int]) -> Option<Vec<ObjectId>> {
        ints.iter()
            .map(|x| {
                int(m, x)
                    .and_then(|v| u16::try_from(v).ok())
                    .map(ObjectId)
                    .filter(|o| (o.0 as usize) < self.p.universe.object_count())
            })
            .collect()
    }

    /// The true atoms of the base state in `m`, as Jason terms.
    pub fn state_of(&self, m: &Model) -> Vec<String> {
        self.enc
            .base
            .iter()
            .enumerate()
            .filter(|(_, b)| truth(m, b))
            .map(|(a, _)| self.p.atoms.display(AtomId(a as u32), &self.p.universe))
            .collect()
    }

    /// The requests that post this goal instance, when the manifest lets users request it.
    fn requests(&self, g: &Group, objs: &[ObjectId]) -> Vec<String> {
        if g.op != TriggerOp::Add || g.kind != TriggerKind::Achieve {
            return Vec::new();
        }
        let args: Vec<Term> = objs
            .iter()
            .map(|o| Term::atom(self.p.universe.object_name(*o)))
            .collect();
        let instance = Term::structure(&g.name, args);
        let requested = self
            .p
            .manifest
            .requests
            .goals
            .iter()
            .any(|f| match &f.expr.kind {
                ExprKind::Literal(l) => Converter::new()
                    .literal(l)
                    .is_ok_and(|pat| unifier(&pat, &instance).is_some()),
                _ => false,
            });
        if requested {
            vec![instance.to_string()]
        } else {
            Vec::new()
        }
    }

    fn names(&self, objs: &[ObjectId]) -> Vec<String> {
        objs.iter()
            .map(|o| self.p.universe.object_name(*o).to_string())
            .collect()
    }

    /// A finding at `span`.
    #[allow(clippy::too_many_arguments)]
    pub fn push(
        &mut self,
        check: &str,
        status: Status,
        message: String,
        span: Span,
        label: impl Into<String>,
        counterexample: Option<Counterexample>,
        secondary: Vec<(Span, String)>,
    ) {
        let location = self.p.map.location(span);
        self.out.push(LintFinding {
            finding: Finding {
                id: format!("{check}:{}:{}", location.file, location.line),
                check: check.into(),
                severity: severity(check),
                status,
                message,
                location: Some(location),
                counterexample,
                span: Some(span),
                related: secondary.iter().map(|(sp, _)| *sp).collect(),
                suppressed: None,
            },
            label: label.into(),
            secondary,
        });
    }

    fn plan(&self, i: usize) -> &'p Plan {
        &self.p.plans.plans[i]
    }

    /// A plan's trigger and context (its first line when it has no context): where a
    /// finding about one of its steps points back to.
    fn head_span(&self, plan: &Plan) -> Span {
        let end = match plan.context_span {
            Some(c) => c.end,
            None => match self.p.map.get(plan.span.file) {
                Some(f) => {
                    let start = (plan.span.start as usize).min(f.text.len());
                    let line_end = f.text[start..]
                        .find('\n')
                        .map_or(f.text.len(), |i| start + i);
                    (line_end as u32).min(plan.span.end)
                }
                None => plan.span.end,
            },
        };
        Span {
            end: end.max(plan.span.start),
            ..plan.span
        }
    }

    fn plan_place(&self, i: usize) -> String {
        let plan = self.plan(i);
        let loc = self.p.map.location(plan.span);
        format!("{} ({}:{})", plan.name(), loc.file, loc.line)
    }

    /// "cannot decide whether ...": the message of an undecided check; the reason follows.
    /// A check z3 could not decide (an unsupported construct, or its answer `unknown`):
    /// "cannot decide QUESTION" and why, status `unknown`, never a pass.
    fn undecided(&mut self, check: &str, question: &str, detail: &str, span: Span, label: &str) {
        let msg = format!("cannot decide {question}{detail}");
        self.push(check, Status::Unknown, msg, span, label, None, vec![]);
    }

    fn run(mut self) -> Vec<LintFinding> {
        let groups = self.groups();
        if self.p.atoms.len() > MAX_LINT_ATOMS {
            self.too_many_atoms(&groups);
        } else {
            let base = self.base();
            for g in &groups {
                self.group_checks(g, &base);
            }
            self.effect_conflicts(&base);
            self.invariant_breaks(&base);
        }
        self.undefined_actions();
        self.undefined_tests();
        self.unused_actions();
        self.goals_without_plans();
        self.out
    }

    /// The solver checks, undecided: the project has too many ground atoms to encode.
    /// `verify` settles dead plans, shadowed plans and coverage by its runs.
    fn too_many_atoms(&mut self, groups: &[Group]) {
        let why = format!(
            ": the project has {} ground atoms, more than lint encodes ({MAX_LINT_ATOMS})",
            self.p.atoms.len()
        );
        for g in groups {
            for &i in &g.plans {
                let (name, span) = (self.plan(i).name(), self.plan(i).span);
                let q = format!("whether {name} can be applicable");
                self.undecided("dead-plan", &q, &why, span, "this plan");
            }
            if g.op == TriggerOp::Add && g.kind == TriggerKind::Achieve {
                let q = format!(
                    "whether every {} has an applicable plan",
                    g.event_text(None)
                );
                let span = self.plan(g.plans[0]).span;
                self.undecided("coverage-gap", &q, &why, span, "plans for this goal");
            }
        }
        if let Some(first) = self.p.plans.plans.first() {
            let span = first.span;
            for (check, q) in [
                (
                    "shadowed-plan",
                    "whether a plan is shadowed by an earlier one",
                ),
                ("plan-overlap", "whether two plans overlap"),
                (
                    "precondition",
                    "whether every action's precondition holds where it is called",
                ),
                ("effect-conflict", "whether an action's effects conflict"),
                (
                    "action-breaks-invariant",
                    "whether an action breaks an invariant",
                ),
            ] {
                self.undecided(check, q, &why, span, "the plan library");
            }
        }
    }

    fn groups(&self) -> Vec<Group> {
        let mut groups: Vec<Group> = Vec::new();
        for (i, plan) in self.p.plans.plans.iter().enumerate() {
            let t = &plan.trigger;
            let name = t.literal.functor().unwrap_or("").to_string();
            let arity = t.literal.arity();
            match groups
                .iter_mut()
                .find(|g| g.op == t.op && g.kind == t.kind && g.name == name && g.arity == arity)
            {
                Some(g) => g.plans.push(i),
                None => {
                    let voc = &self.p.vocabulary;
                    let types = match t.kind {
                        TriggerKind::Achieve => {
                            voc.goal(&name, arity).map(|(_, g)| g.params.clone())
                        }
                        TriggerKind::Belief => self
                            .p
                            .atoms
                            .pred(&name)
                            .map(|p| self.p.atoms.pred_params(p).to_vec())
                            .filter(|ps| ps.len() == arity),
                        TriggerKind::Test => None,
                    }
                    .unwrap_or_else(|| vec![TypeId::OBJECT; arity]);
                    groups.push(Group {
                        op: t.op,
                        kind: t.kind,
                        name,
                        arity,
                        plans: vec![i],
                        types,
                    });
                }
            }
        }
        groups
    }
}

/// Calls `f` on every step of a body, nested ones included.
pub(super) fn walk(steps: &[Step], f: &mut dyn FnMut(&Step)) {
    for s in steps {
        f(s);
        match &s.kind {
            BodyStep::If {
                branches,
                else_body,
            } => {
                for (_, b) in branches {
                    walk(b, f);
                }
                walk(else_body, f);
            }
            BodyStep::While(_, b) | BodyStep::For(_, b) => walk(b, f),
            _ => {}
        }
    }
}
