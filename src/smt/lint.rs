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

use super::encode::{and, or, Enc, Encoder, Env, State, Unsupported, Val};
use super::exec::{self, PreResult};
use super::solve::{int, truth, Outcome, Session, DEFAULT_RLIMIT};
use super::summary::Summaries;
use super::text;
use crate::findings::{Counterexample, Finding, Status};
use crate::model::atoms::AtomId;
use crate::model::cond::Cond;
use crate::model::from_ast::Converter;
use crate::model::plans::{BodyStep, Plan, Step};
use crate::model::project::Project;
use crate::model::subst::unifier;
use crate::model::term::Term;
use crate::model::universe::{ObjectId, TypeId};
use crate::syntax::ast::{ExprKind, TriggerKind, TriggerOp};
use crate::syntax::manifest::PlanSelection;
use crate::syntax::{Severity, Span};
use std::collections::{BTreeMap, BTreeSet};
use z3::ast::{Bool, Int};
use z3::Model;

/// Options of a lint run.
#[derive(Clone, Debug)]
pub struct LintOptions {
    /// The z3 resource budget of each check (see [`DEFAULT_RLIMIT`]).
    pub rlimit: u32,
}

impl Default for LintOptions {
    fn default() -> LintOptions {
        LintOptions {
            rlimit: DEFAULT_RLIMIT,
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

/// One conjunct of an invariant, with the atoms it reads.
type Conjunct = (Cond, BTreeSet<AtomId>);

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

/// How a plan fared in the dead-plan check.
enum Alive {
    /// Applicable in this state (the counterexample of later findings).
    Yes(Counterexample),
    Dead,
    Unknown,
}

impl<'p> Linter<'p> {
    fn new(p: &'p Project, opts: &'p LintOptions) -> Linter<'p> {
        Linter {
            p,
            opts,
            enc: Encoder::new(p),
            sum: Summaries::compute(p),
            out: Vec::new(),
        }
    }

    /// A new solver with the invariants and the initial-state guard.
    pub fn base(&self) -> Base {
        let sess = Session::new(self.opts.rlimit);
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
        let base = self.base();
        for g in &groups {
            self.group_checks(g, &base);
        }
        self.effect_conflicts(&base);
        self.invariant_breaks(&base);
        self.undefined_actions();
        self.undefined_tests();
        self.unused_actions();
        self.goals_without_plans();
        self.out
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

    /// Closed applicability of plan `i` for the event `event`, on the base state.
    fn applicable(&self, i: usize, event: &[Val]) -> Enc<Bool> {
        let plan = self.plan(i);
        let mut env = Env::new();
        let rel = self.enc.relevant(&plan.trigger.literal, event, &mut env)?;
        let ctx = self
            .enc
            .closed_formula(&plan.context, &env, &self.enc.base)?;
        Ok(and(vec![rel, ctx]))
    }

    fn group_checks(&mut self, g: &Group, base: &Base) {
        let mut alive: BTreeMap<usize, Alive> = BTreeMap::new();
        for &i in &g.plans {
            let a = self.dead_plan(g, i, base);
            alive.insert(i, a);
        }
        let mut shadowed = BTreeSet::new();
        if self.p.manifest.bounds.plan_selection == PlanSelection::First {
            for (k, &j) in g.plans.iter().enumerate() {
                if k == 0 {
                    continue;
                }
                if let Some(Alive::Yes(cx)) = alive.get(&j) {
                    if self.shadowed(g, &g.plans[..k], j, cx.clone(), base, &alive) {
                        shadowed.insert(j);
                    }
                }
            }
        }
        for (k, &i) in g.plans.iter().enumerate() {
            for &j in &g.plans[k + 1..] {
                let both = matches!(alive.get(&i), Some(Alive::Yes(_)))
                    && matches!(alive.get(&j), Some(Alive::Yes(_)));
                if both && !shadowed.contains(&j) {
                    self.overlap(g, i, j, base);
                }
            }
        }
        if g.op == TriggerOp::Add && g.kind == TriggerKind::Achieve {
            self.coverage(g, base, &alive);
        }
        for &i in &g.plans {
            if let Some(Alive::Yes(_)) = alive.get(&i) {
                self.preconditions(g, i);
            }
        }
    }

    // ----- dead-plan ----------------------------------------------------------------------

    fn dead_plan(&mut self, g: &Group, i: usize, base: &Base) -> Alive {
        let plan = self.plan(i);
        let (_, event, dom) = self.event(g);
        let mut env = Env::new();
        let mut frame = self.enc.frame();
        let items = self
            .enc
            .relevant(&plan.trigger.literal, &event, &mut env)
            .and_then(|rel| {
                let mut items = vec![("trigger".to_string(), rel)];
                items.extend(self.enc.assert_conjuncts(
                    &plan.context,
                    &mut env,
                    &mut frame,
                    &self.enc.base,
                )?);
                Ok(items)
            });
        let items = match items {
            Ok(items) => items,
            Err(Unsupported(why)) => {
                self.undecided(
                    "dead-plan",
                    &format!("whether {} can be applicable", plan.name()),
                    &format!(": {why}"),
                    plan.span,
                    "this plan",
                );
                return Alive::Unknown;
            }
        };
        base.sess.solver.push();
        base.sess.solver.assert(&dom);
        let lits: Vec<Bool> = items
            .iter()
            .map(|(_, b)| {
                let l = self.enc.fresh_bool("conjunct");
                base.sess.solver.assert(l.implies(b));
                l
            })
            .collect();
        let (outcome, _) = base.witness(&Bool::from_bool(true), &lits);
        let result = match outcome {
            Outcome::Sat(m) => Alive::Yes(state_cx(self.state_of(&m), Vec::new())),
            Outcome::Unsat(_) => {
                let keep = base.sess.minimize(&[], &{
                    let mut all = base.inv_lits();
                    all.extend(lits.iter().cloned());
                    all
                });
                let n_inv = base.invs.len();
                let mut parts = Vec::new();
                let mut invs = Vec::new();
                let mut trigger = false;
                for k in keep.unwrap_or_default() {
                    if k < n_inv {
                        invs.push(format!("`{}`", base.invs[k].0));
                    } else if k == n_inv {
                        trigger = true;
                    } else {
                        parts.push(format!("`{}`", items[k - n_inv].0));
                    }
                }
                let mut why = Vec::new();
                if trigger {
                    why.push(format!(
                        "its trigger `{}` matches no {} of the declared types",
                        plan.trigger,
                        if g.kind == TriggerKind::Belief {
                            "belief"
                        } else {
                            "goal"
                        }
                    ));
                }
                if !parts.is_empty() {
                    why.push(format!("{} cannot all hold", parts.join(" and ")));
                }
                if !invs.is_empty() {
                    why.push(format!(
                        "given invariant{} {}",
                        if invs.len() == 1 { "" } else { "s" },
                        invs.join(", ")
                    ));
                }
                if why.is_empty() {
                    why.push("its context is unsatisfiable".into());
                }
                let msg = format!("{} is never applicable: {}", plan.name(), why.join(", "));
                let span = plan.context_span.unwrap_or(plan.span);
                self.push(
                    "dead-plan",
                    Status::Fail,
                    msg,
                    plan.span,
                    "this plan can never run",
                    None,
                    vec![(span, "this context".into())],
                );
                Alive::Dead
            }
            Outcome::Unknown(r) => {
                self.undecided(
                    "dead-plan",
                    &format!("whether {} can be applicable", plan.name()),
                    &format!(" (z3: {r})"),
                    plan.span,
                    "this plan",
                );
                Alive::Unknown
            }
        };
        base.sess.solver.pop(1);
        if let Alive::Yes(_) = result {
            let msg = format!("{} is applicable in some state", plan.name());
            self.push("dead-plan", Status::Pass, msg, plan.span, "", None, vec![]);
        }
        result
    }

    // ----- shadowed-plan ------------------------------------------------------------------

    fn shadowed(
        &mut self,
        g: &Group,
        earlier: &[usize],
        j: usize,
        witness: Counterexample,
        base: &Base,
        alive: &BTreeMap<usize, Alive>,
    ) -> bool {
        let plan = self.plan(j);
        let earlier: Vec<usize> = earlier
            .iter()
            .copied()
            .filter(|i| !matches!(alive.get(i), Some(Alive::Dead)))
            .collect();
        if earlier.is_empty() {
            return false;
        }
        let (_, event, dom) = self.event(g);
        let built = (|| -> Enc<(Bool, Vec<Bool>)> {
            let mut env = Env::new();
            let mut frame = self.enc.frame();
            let rel = self.enc.relevant(&plan.trigger.literal, &event, &mut env)?;
            let ctx =
                self.enc
                    .assert_formula(&plan.context, &mut env, &mut frame, &self.enc.base)?;
            let mut nots = Vec::new();
            for &i in &earlier {
                nots.push(self.applicable(i, &event)?.not());
            }
            Ok((and(vec![dom.clone(), rel, ctx]), nots))
        })();
        let (this, nots) = match built {
            Ok(x) => x,
            Err(Unsupported(why)) => {
                self.undecided(
                    "shadowed-plan",
                    &format!("whether an earlier plan hides {}", plan.name()),
                    &format!(": {why}"),
                    plan.span,
                    "this plan",
                );
                return false;
            }
        };
        base.sess.solver.push();
        base.sess.solver.assert(&this);
        let lits: Vec<Bool> = nots
            .iter()
            .map(|b| {
                let l = self.enc.fresh_bool("not earlier");
                base.sess.solver.assert(l.implies(b));
                l
            })
            .collect();
        let mut all = base.inv_lits();
        all.extend(lits.iter().cloned());
        let outcome = base.sess.check(&all);
        let result = match outcome {
            Outcome::Unsat(_) => {
                let keep = base
                    .sess
                    .minimize(&base.inv_lits(), &lits)
                    .unwrap_or_else(|| (0..lits.len()).collect());
                let hiders: Vec<usize> = keep.iter().map(|&k| earlier[k]).collect();
                let names: Vec<String> = hiders.iter().map(|&i| self.plan_place(i)).collect();
                let msg = if names.len() == 1 {
                    format!(
                        "{} is never chosen: the earlier plan {} is applicable whenever it is",
                        plan.name(),
                        names[0]
                    )
                } else {
                    format!(
                        "{} is never chosen: whenever it is applicable, one of the earlier plans {} is too",
                        plan.name(),
                        names.join(", ")
                    )
                };
                let secondary = hiders
                    .iter()
                    .map(|&i| (self.plan(i).span, "chosen instead".to_string()))
                    .collect();
                self.push(
                    "shadowed-plan",
                    Status::Fail,
                    msg,
                    plan.span,
                    "never chosen",
                    Some(witness),
                    secondary,
                );
                true
            }
            Outcome::Sat(_) => {
                let msg = format!("{} is the first applicable plan in some state", plan.name());
                self.push(
                    "shadowed-plan",
                    Status::Pass,
                    msg,
                    plan.span,
                    "",
                    None,
                    vec![],
                );
                false
            }
            Outcome::Unknown(r) => {
                self.undecided(
                    "shadowed-plan",
                    &format!("whether an earlier plan hides {}", plan.name()),
                    &format!(" (z3: {r})"),
                    plan.span,
                    "this plan",
                );
                false
            }
        };
        base.sess.solver.pop(1);
        result
    }

    // ----- the literals at fault of a satisfiable question ---------------------------------

    /// The values in `m` of the base atoms that `contra` reads, minimised so that they still
    /// contradict `contra` (under the invariants): the state's part that forces the answer.
    fn fault_literals(
        &self,
        base: &Base,
        m: &Model,
        contra: &dyn Fn() -> Enc<Bool>,
    ) -> Vec<String> {
        self.enc.record_reads();
        let f = contra();
        // Every fact `contra` reads: the atoms, and the agent's goals it asks about.
        let mut facts: Vec<(String, Bool)> = self
            .enc
            .take_reads()
            .into_iter()
            .map(|a| {
                let name = self.p.atoms.display(a, &self.p.universe);
                (name, self.enc.base[a.0 as usize].clone())
            })
            .collect();
        facts.extend(self.enc.take_call_reads());
        let values: Vec<bool> = facts.iter().map(|(_, b)| truth(m, b)).collect();
        let show = |k: usize| {
            if values[k] {
                facts[k].0.clone()
            } else {
                format!("not {}", facts[k].0)
            }
        };
        let Ok(f) = f else {
            return (0..facts.len()).map(show).collect();
        };
        base.sess.solver.push();
        base.sess.solver.assert(&f);
        let lits: Vec<Bool> = facts
            .iter()
            .zip(&values)
            .map(|((_, b), v)| {
                let l = self.enc.fresh_bool("fact");
                base.sess
                    .solver
                    .assert(l.implies(if *v { b.clone() } else { b.not() }));
                l
            })
            .collect();
        let keep = base.sess.minimize(&base.inv_lits(), &lits);
        base.sess.solver.pop(1);
        match keep {
            Some(k) => k.into_iter().map(show).collect(),
            None => (0..facts.len()).map(show).collect(),
        }
    }

    // ----- plan-overlap -------------------------------------------------------------------

    fn overlap(&mut self, g: &Group, i: usize, j: usize, base: &Base) {
        let (pi, pj) = (self.plan(i), self.plan(j));
        let (ints, event, dom) = self.event(g);
        let built = (|| -> Enc<Bool> {
            let mut parts = vec![dom.clone()];
            for plan in [pi, pj] {
                let mut env = Env::new();
                let mut frame = self.enc.frame();
                parts.push(self.enc.relevant(&plan.trigger.literal, &event, &mut env)?);
                parts.push(self.enc.assert_formula(
                    &plan.context,
                    &mut env,
                    &mut frame,
                    &self.enc.base,
                )?);
            }
            Ok(and(parts))
        })();
        let q = match built {
            Ok(q) => q,
            Err(Unsupported(why)) => {
                self.undecided(
                    "plan-overlap",
                    &format!("whether {} and {} overlap", pi.name(), pj.name()),
                    &format!(": {why}"),
                    pj.span,
                    "this plan",
                );
                return;
            }
        };
        let (outcome, _) = base.witness(&q, &[]);
        match outcome {
            Outcome::Sat(m) => {
                let objs = self.event_objects(&m, &ints).unwrap_or_default();
                let fixed: Vec<Val> = objs.iter().map(|o| Val::Obj(*o)).collect();
                let lits = self.fault_literals(base, &m, &|| {
                    Ok(and(vec![
                        self.applicable(i, &fixed)?,
                        self.applicable(j, &fixed)?,
                    ])
                    .not())
                });
                let msg = format!(
                    "{} and {} are both applicable for {} when {}",
                    pi.name(),
                    self.plan_place(j),
                    g.event_text(Some(&self.names(&objs))),
                    text::conjunction(&lits)
                );
                let cx = state_cx(self.state_of(&m), self.requests(g, &objs));
                let secondary = vec![(pi.span, "also applicable".to_string())];
                self.push(
                    "plan-overlap",
                    Status::Fail,
                    msg,
                    pj.span,
                    "overlaps an earlier plan",
                    Some(cx),
                    secondary,
                );
            }
            Outcome::Unsat(_) => {
                let msg = format!(
                    "{} and {} are never applicable together",
                    pi.name(),
                    pj.name()
                );
                self.push("plan-overlap", Status::Pass, msg, pj.span, "", None, vec![]);
            }
            Outcome::Unknown(r) => {
                self.undecided(
                    "plan-overlap",
                    &format!("whether {} and {} overlap", pi.name(), pj.name()),
                    &format!(" (z3: {r})"),
                    pj.span,
                    "this plan",
                );
            }
        }
    }

    // ----- coverage-gap -------------------------------------------------------------------

    fn coverage(&mut self, g: &Group, base: &Base, alive: &BTreeMap<usize, Alive>) {
        let first = self.plan(g.plans[0]);
        let span = first.span;
        let (ints, event, dom) = self.event(g);
        let built = (|| -> Enc<Bool> {
            let mut parts = vec![dom.clone()];
            for &i in &g.plans {
                if matches!(alive.get(&i), Some(Alive::Dead)) {
                    continue;
                }
                parts.push(self.applicable(i, &event)?.not());
            }
            Ok(and(parts))
        })();
        let q = match built {
            Ok(q) => q,
            Err(Unsupported(why)) => {
                self.undecided(
                    "coverage-gap",
                    &format!(
                        "whether every {} has an applicable plan",
                        g.event_text(None)
                    ),
                    &format!(": {why}"),
                    span,
                    "the first plan for this goal",
                );
                return;
            }
        };
        let (outcome, initial) = base.witness(&q, &[]);
        match outcome {
            Outcome::Sat(m) => {
                let objs = self.event_objects(&m, &ints).unwrap_or_default();
                let fixed: Vec<Val> = objs.iter().map(|o| Val::Obj(*o)).collect();
                let plans = g.plans.clone();
                let lits = self.fault_literals(base, &m, &|| {
                    let mut any = Vec::new();
                    for &i in &plans {
                        any.push(self.applicable(i, &fixed)?);
                    }
                    Ok(or(any))
                });
                let msg = format!(
                    "no plan for {} is applicable when {}{}",
                    g.event_text(Some(&self.names(&objs))),
                    text::conjunction(&lits),
                    if initial {
                        " (this can be an initial state)"
                    } else {
                        ""
                    }
                );
                let cx = state_cx(self.state_of(&m), self.requests(g, &objs));
                self.push(
                    "coverage-gap",
                    Status::Fail,
                    msg,
                    span,
                    "the first plan for this goal",
                    Some(cx),
                    vec![],
                );
            }
            Outcome::Unsat(_) => {
                let msg = format!(
                    "some plan for {} is applicable in every state",
                    g.event_text(None)
                );
                self.push("coverage-gap", Status::Pass, msg, span, "", None, vec![]);
            }
            Outcome::Unknown(r) => {
                self.undecided(
                    "coverage-gap",
                    &format!(
                        "whether every {} has an applicable plan",
                        g.event_text(None)
                    ),
                    &format!(" (z3: {r})"),
                    span,
                    "the first plan for this goal",
                );
            }
        }
    }

    // ----- precondition -------------------------------------------------------------------

    fn preconditions(&mut self, g: &Group, i: usize) {
        let plan = self.plan(i);
        let (checks, stop) = exec::run(self, g, plan);
        for c in checks {
            match c.result {
                PreResult::Pass => {
                    let msg = format!(
                        "the precondition of `{}` holds whenever it is executed here",
                        c.action
                    );
                    self.push("precondition", Status::Pass, msg, c.span, "", None, vec![]);
                }
                PreResult::Fail {
                    instance,
                    lits,
                    initial,
                    requests,
                } => {
                    let msg = match instance {
                        Some(inst) => format!(
                            "the precondition of `{}` may not hold here in {}, e.g. {}when {}",
                            c.action,
                            plan.name(),
                            if inst == c.action { String::new() } else { format!("as `{inst}` ") },
                            text::conjunction(&lits)
                        ),
                        None => format!(
                            "`{}` in {} may name no action of the domain (its arguments do not fit the action's types)",
                            c.action,
                            plan.name()
                        ),
                    };
                    let cx = state_cx(initial, requests);
                    let secondary = vec![(self.head_span(plan), format!("in {}", plan.name()))];
                    self.push(
                        "precondition",
                        Status::Fail,
                        msg,
                        c.span,
                        "this action may fail",
                        Some(cx),
                        secondary,
                    );
                }
                PreResult::Unknown(r) => {
                    self.undecided(
                        "precondition",
                        &format!("whether the precondition of `{}` holds here", c.action),
                        &format!(" (z3: {r})"),
                        c.span,
                        "this action",
                    );
                }
            }
        }
        if let Some((span, Unsupported(why))) = stop {
            self.undecided(
                "precondition",
                &format!(
                    "whether the preconditions of {} hold from here on",
                    plan.name()
                ),
                &format!(": {why}"),
                span,
                "from here on",
            );
        }
    }

    /// The counterexample fields of a model for plan `plan` of group `g`.
    pub fn plan_counterexample(
        &self,
        m: &Model,
        g: &Group,
        ints: &[Int],
    ) -> (Vec<String>, Vec<String>) {
        let objs = self.event_objects(m, ints).unwrap_or_default();
        (self.state_of(m), self.requests(g, &objs))
    }

    // ----- effect-conflict ----------------------------------------------------------------

    fn action_span(&self, schema: usize) -> Span {
        let name = &self.p.domain.actions[schema].name;
        self.p
            .vocabulary
            .action(name)
            .map(|(_, a)| a.span)
            .unwrap_or(self.p.domain.actions[schema].span)
    }

    fn effect_conflicts(&mut self, base: &Base) {
        for schema in 0..self.p.domain.actions.len() {
            let name = self.p.domain.actions[schema].name.clone();
            let span = self.action_span(schema);
            let st = &self.enc.base;
            // Per ground action: when it runs, and each pair of effects that add and
            // delete one atom firing together. One query over all of them, so the state
            // shown is an initial state whenever some instance conflicts in one.
            let mut insts = Vec::new();
            for g in self.p.actions.all().iter().filter(|g| g.schema == schema) {
                let mut pairs = Vec::new();
                for e1 in &g.effects {
                    for a in &e1.add {
                        for e2 in &g.effects {
                            if e2.del.contains(a) {
                                let fire = and(vec![
                                    self.enc.cond(&e1.when, st),
                                    self.enc.cond(&e2.when, st),
                                ]);
                                pairs.push((
                                    *a,
                                    Cond::and(vec![e1.when.clone(), e2.when.clone()]),
                                    fire,
                                ));
                            }
                        }
                    }
                }
                if !pairs.is_empty() && g.pre != Cond::False {
                    let pre = self.enc.cond(&g.pre, st);
                    let any = or(pairs.iter().map(|(_, _, f)| f.clone()).collect());
                    insts.push((g, pairs, and(vec![pre, any])));
                }
            }
            let q = or(insts.iter().map(|(_, _, q)| q.clone()).collect());
            match base.witness(&q, &[]).0 {
                Outcome::Sat(m) => {
                    let Some((g, pairs, _)) = insts.iter().find(|(_, _, q)| truth(&m, q)) else {
                        continue;
                    };
                    let Some((a, when, _)) = pairs.iter().find(|(_, _, f)| truth(&m, f)) else {
                        continue;
                    };
                    let value = |x: AtomId| truth(&m, &st[x.0 as usize]);
                    let lits: Vec<String> = text::why(when, &value)
                        .into_iter()
                        .map(|(x, v)| text::literal(&self.p.atoms, &self.p.universe, x, v))
                        .collect();
                    let atom = self.p.atoms.display(*a, &self.p.universe);
                    let msg = format!(
                        "`{}` both adds and deletes {atom}{} (PDDL deletes first, so it stays true)",
                        g.display(&self.p.universe),
                        if lits.is_empty() { String::new() } else { format!(" when {}", text::conjunction(&lits)) }
                    );
                    let cx = state_cx(self.state_of(&m), Vec::new());
                    self.push(
                        "effect-conflict",
                        Status::Fail,
                        msg,
                        span,
                        "this action",
                        Some(cx),
                        vec![],
                    );
                }
                Outcome::Unsat(_) => {
                    let msg = format!("no binding of `{name}` adds and deletes one atom");
                    self.push("effect-conflict", Status::Pass, msg, span, "", None, vec![]);
                }
                Outcome::Unknown(r) => {
                    self.undecided(
                        "effect-conflict",
                        &format!("whether `{name}` adds and deletes one atom"),
                        &format!(" (z3: {r})"),
                        span,
                        "this action",
                    );
                }
            }
        }
    }

    // ----- action-breaks-invariant -------------------------------------------------------

    fn invariant_breaks(&mut self, base: &Base) {
        // Each invariant as its conjuncts, with the atoms each reads: an action can only
        // break a conjunct that reads an atom it changes.
        let invs: Vec<(String, Vec<Conjunct>)> = self
            .p
            .invariants
            .iter()
            .map(|(name, c)| {
                let parts = match c {
                    Cond::And(cs) => cs.clone(),
                    other => vec![other.clone()],
                };
                let parts = parts
                    .into_iter()
                    .map(|c| {
                        let atoms = c.atoms().into_iter().collect();
                        (c, atoms)
                    })
                    .collect();
                (name.clone(), parts)
            })
            .collect();
        for schema in 0..self.p.domain.actions.len() {
            let name = self.p.domain.actions[schema].name.clone();
            let span = self.action_span(schema);
            let st = &self.enc.base;
            // Every ground action's successor state, built once.
            let mut insts = Vec::new();
            for g in self.p.actions.all().iter().filter(|g| g.schema == schema) {
                if g.pre == Cond::False {
                    continue;
                }
                let touched: BTreeSet<AtomId> = g.touched().into_iter().collect();
                let mut next: State = st.clone();
                for a in &touched {
                    let when = |add: bool| {
                        or(g.effects
                            .iter()
                            .filter(|e| {
                                if add {
                                    e.add.contains(a)
                                } else {
                                    e.del.contains(a)
                                }
                            })
                            .map(|e| self.enc.cond(&e.when, st))
                            .collect())
                    };
                    let kept = and(vec![st[a.0 as usize].clone(), when(false).not()]);
                    next[a.0 as usize] = or(vec![when(true), kept]);
                }
                insts.push((g, touched, next, self.enc.cond(&g.pre, st)));
            }
            let mut broken: Vec<String> = Vec::new();
            let mut first_cx: Option<Counterexample> = None;
            let mut unknown: Option<String> = None;
            for (inv_name, parts) in &invs {
                // One query per invariant over every binding: some ground action runs from
                // a state satisfying the invariants and leaves one of them false.
                let mut cases = Vec::new();
                for (g, touched, next, pre) in &insts {
                    let relevant: Vec<&Cond> = parts
                        .iter()
                        .filter(|(_, atoms)| !atoms.is_disjoint(touched))
                        .map(|(c, _)| c)
                        .collect();
                    if relevant.is_empty() {
                        continue;
                    }
                    let after: Vec<Bool> =
                        relevant.iter().map(|c| self.enc.cond(c, next)).collect();
                    let q = and(vec![pre.clone(), and(after.clone()).not()]);
                    cases.push((g, next, relevant, after, q));
                }
                if cases.is_empty() {
                    continue;
                }
                let q = or(cases.iter().map(|c| c.4.clone()).collect());
                match base.witness(&q, &[]).0 {
                    Outcome::Sat(m) => {
                        let Some((g, next, relevant, after, _)) =
                            cases.iter().find(|c| truth(&m, &c.4))
                        else {
                            continue;
                        };
                        let k = after.iter().position(|b| !truth(&m, b)).unwrap_or(0);
                        let value = |x: AtomId| truth(&m, &next[x.0 as usize]);
                        let lits: Vec<String> = text::why(relevant[k], &value)
                            .into_iter()
                            .map(|(x, v)| text::literal(&self.p.atoms, &self.p.universe, x, v))
                            .collect();
                        broken.push(format!(
                            "`{inv_name}` (after `{}` {})",
                            g.display(&self.p.universe),
                            text::conjunction(&lits)
                        ));
                        if first_cx.is_none() {
                            first_cx = Some(state_cx(self.state_of(&m), Vec::new()));
                        }
                    }
                    Outcome::Unsat(_) => {}
                    Outcome::Unknown(r) => unknown = Some(r),
                }
            }
            if !broken.is_empty() {
                let msg = format!(
                    "`{name}` can break invariant{} {}, from a state that satisfies the invariants and its precondition",
                    if broken.len() == 1 { "" } else { "s" },
                    broken.join(", ")
                );
                self.push(
                    "action-breaks-invariant",
                    Status::Fail,
                    msg,
                    span,
                    "this action",
                    first_cx,
                    vec![],
                );
            } else if let Some(r) = unknown {
                self.undecided(
                    "action-breaks-invariant",
                    &format!("whether `{name}` preserves the invariants"),
                    &format!(" (z3: {r})"),
                    span,
                    "this action",
                );
            } else {
                let msg = format!("`{name}` preserves every invariant");
                self.push(
                    "action-breaks-invariant",
                    Status::Pass,
                    msg,
                    span,
                    "",
                    None,
                    vec![],
                );
            }
        }
    }

    // ----- undefined-action, unused-action, no-plan-for-goal -----------------------------

    fn undefined_tests(&mut self) {
        for u in self.p.vocabulary.undefined_tests.clone() {
            let msg = format!(
                "the test goal asks `{}/{}`, which no PDDL predicate, mental note, rule or `+?` plan defines: it always fails",
                u.name, u.arity
            );
            self.push(
                "undefined-predicate",
                Status::Fail,
                msg,
                u.span,
                "undefined predicate",
                None,
                vec![],
            );
        }
    }

    fn undefined_actions(&mut self) {
        let names: Vec<String> = self
            .p
            .vocabulary
            .actions
            .iter()
            .map(|a| a.name.clone())
            .collect();
        for u in self.p.vocabulary.undefined_actions.clone() {
            let near = nearest(&u.name, names.iter().map(String::as_str));
            let msg = format!(
                "`{}/{}` is neither an action of the PDDL domain nor an internal action bdi-check models{}",
                u.name,
                u.arity,
                match near {
                    Some(n) => format!(" (did you mean `{n}`?)"),
                    None => String::new(),
                }
            );
            self.push(
                "undefined-action",
                Status::Fail,
                msg,
                u.span,
                "undefined action",
                None,
                vec![],
            );
        }
    }

    fn unused_actions(&mut self) {
        let mut called: BTreeSet<(String, usize)> = BTreeSet::new();
        for p in &self.p.plans.plans {
            walk(&p.body, &mut |s| {
                if let BodyStep::Action(t) = &s.kind {
                    if let Some(f) = t.functor() {
                        called.insert((f.to_string(), t.arity()));
                    }
                }
            });
        }
        for a in self.p.vocabulary.actions.clone() {
            if called.contains(&(a.name.clone(), a.params.len())) {
                let msg = format!("`{}` is called by a plan", a.name);
                self.push("unused-action", Status::Pass, msg, a.span, "", None, vec![]);
            } else {
                let msg = format!("no plan calls the action `{}`", a.name);
                self.push(
                    "unused-action",
                    Status::Fail,
                    msg,
                    a.span,
                    "never called",
                    None,
                    vec![],
                );
            }
        }
    }

    fn goals_without_plans(&mut self) {
        // Where each goal is first posted: a subgoal step, an initial goal, a request.
        let mut posted: BTreeMap<(String, usize), Span> = BTreeMap::new();
        for p in &self.p.plans.plans {
            walk(&p.body, &mut |s| {
                if let BodyStep::Achieve { goal, .. } = &s.kind {
                    if let Some(f) = goal.functor() {
                        posted
                            .entry((f.to_string(), goal.arity()))
                            .or_insert(s.span);
                    }
                }
            });
        }
        for (g, span) in &self.p.plans.initial_goals {
            if let Some(f) = g.functor() {
                posted.entry((f.to_string(), g.arity())).or_insert(*span);
            }
        }
        for f in &self.p.manifest.requests.goals {
            if let ExprKind::Literal(l) = &f.expr.kind {
                posted
                    .entry((l.functor.clone(), l.args.len()))
                    .or_insert(f.span);
            }
        }
        for ((name, arity), span) in posted {
            let has_plan = self
                .p
                .vocabulary
                .goal(&name, arity)
                .map(|(_, g)| g.has_plan)
                .unwrap_or_else(|| {
                    self.p.plans.plans.iter().any(|p| {
                        p.trigger.op == TriggerOp::Add
                            && p.trigger.kind == TriggerKind::Achieve
                            && p.trigger.literal.functor() == Some(name.as_str())
                            && p.trigger.literal.arity() == arity
                    })
                });
            if has_plan {
                let msg = format!("`!{name}/{arity}` has a plan");
                self.push(
                    "no-plan-for-goal",
                    Status::Pass,
                    msg,
                    span,
                    "",
                    None,
                    vec![],
                );
            } else {
                let msg = format!(
                    "the goal `{name}/{arity}` is posted here but no plan has the trigger `+!{name}`{}",
                    if arity > 0 { format!(" with {arity} argument{}", if arity == 1 { "" } else { "s" }) } else { String::new() }
                );
                self.push(
                    "no-plan-for-goal",
                    Status::Fail,
                    msg,
                    span,
                    "no plan for this goal",
                    None,
                    vec![],
                );
            }
        }
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

/// The nearest candidate to `name`, if one is within a third of its length in edits.
fn nearest<'c>(name: &str, candidates: impl Iterator<Item = &'c str>) -> Option<&'c str> {
    let limit = (name.chars().count() / 3).max(1);
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let d = edit_distance(&name.to_lowercase(), &c.to_lowercase());
        if d <= limit && best.is_none_or(|(b, _)| d < b) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
        }
        prev = cur;
    }
    prev[b.len()]
}
