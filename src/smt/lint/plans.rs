//! The checks on the plans for one trigger, by z3 on the base state: `dead-plan`,
//! `shadowed-plan`, `plan-overlap` and `coverage-gap`, with the literals at fault that
//! explain a satisfiable answer. They share one event per trigger signature (a [`Group`]),
//! and the later checks skip the plans the dead-plan check found dead.
//!
//! Where steps add or remove plans (`.add_plan`, `.remove_plan`), which plans are in the
//! library, and in which order, depends on the run: a context is what it is in every
//! library (dead-plan, plan-overlap), but a plan is found shadowed only by earlier plans
//! that are always there and before it, and coverage is
//! decided from the plans always there (covered) or from every plan that may be there (a
//! gap); in between it is left undecided, for `verify` to settle by its runs.

use super::{state_cx, Base, Group, Linter};
use crate::findings::{Counterexample, Status};
use crate::smt::encode::{and, or, Enc, Env, Unsupported, Val};
use crate::smt::solve::{truth, Outcome};
use crate::smt::text;
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::manifest::PlanSelection;
use std::collections::{BTreeMap, BTreeSet};
use z3::ast::Bool;
use z3::Model;

/// How a plan fared in the dead-plan check.
enum Alive {
    /// Applicable in this state (the counterexample of later findings).
    Yes(Counterexample),
    Dead,
    Unknown,
}

impl Linter<'_> {
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

    pub(super) fn group_checks(&mut self, g: &Group, base: &Base) {
        let mut alive: BTreeMap<usize, Alive> = BTreeMap::new();
        for &i in &g.plans {
            let a = self.dead_plan(g, i, base);
            alive.insert(i, a);
        }
        let mut shadowed = BTreeSet::new();
        let lib = &self.p.plans;
        if self.p.manifest.bounds.plan_selection == PlanSelection::First {
            // Each plan that may hide a later one is encoded once for the group, as an
            // assumption literal `l => not applicable`: asking whether plan j is shadowed then
            // assumes the earlier plans' literals instead of encoding them again, so the
            // group costs linearly in encoding, not quadratically (issue 18).
            base.sess.solver.push();
            let (_, event, _) = self.event(g);
            let mut hiders: Vec<(usize, Result<Bool, String>)> = Vec::new();
            for (k, &j) in g.plans.iter().enumerate() {
                if k > 0 && !lib.added_at_begin(j) {
                    if let Some(Alive::Yes(cx)) = alive.get(&j) {
                        if self.shadowed(g, &hiders, j, cx.clone(), base) {
                            shadowed.insert(j);
                        }
                    }
                }
                // Only plans that are always there, always before it, hide a plan: the
                // agent's own that no step removes, unless it may be added before them. A
                // shadowed plan hides nothing its own hiders do not, so it is left out: the
                // plans named "chosen instead" are then ones that are chosen.
                let hides = !lib.may_change(j)
                    && !shadowed.contains(&j)
                    && !matches!(alive.get(&j), Some(Alive::Dead));
                if hides {
                    let lit = self.applicable(j, &event).map(|app| {
                        let l = self.enc.fresh_bool("not earlier");
                        base.sess.solver.assert(l.implies(app.not()));
                        l
                    });
                    hiders.push((j, lit.map_err(|Unsupported(why)| why)));
                }
            }
            base.sess.solver.pop(1);
        }
        for (k, &i) in g.plans.iter().enumerate() {
            for &j in &g.plans[k + 1..] {
                let both = matches!(alive.get(&i), Some(Alive::Yes(_)))
                    && matches!(alive.get(&j), Some(Alive::Yes(_)));
                if both && !shadowed.contains(&j) && !lib.never_together(i, j) {
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

    /// Whether the earlier plans `hiders` (each with its literal `l => not applicable`, or
    /// why it could not be encoded) are applicable whenever plan `j` is.
    fn shadowed(
        &mut self,
        g: &Group,
        hiders: &[(usize, Result<Bool, String>)],
        j: usize,
        witness: Counterexample,
        base: &Base,
    ) -> bool {
        let plan = self.plan(j);
        if hiders.is_empty() {
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
            let lits = hiders
                .iter()
                .map(|(_, l)| l.clone().map_err(Unsupported))
                .collect::<Enc<Vec<Bool>>>()?;
            Ok((and(vec![dom.clone(), rel, ctx]), lits))
        })();
        let (this, lits) = match built {
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
        let earlier: Vec<usize> = hiders.iter().map(|&(i, _)| i).collect();
        base.sess.solver.push();
        base.sess.solver.assert(&this);
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
        let lib = &self.p.plans;
        let always: Vec<usize> = g
            .plans
            .iter()
            .copied()
            .filter(|&i| !lib.may_change(i))
            .collect();
        if always.len() < g.plans.len() && self.covered(g, &always, base, alive) == Some(true) {
            let msg = format!(
                "some plan for {} that is always in the library is applicable in every state",
                g.event_text(None)
            );
            self.push("coverage-gap", Status::Pass, msg, span, "", None, vec![]);
            return;
        }
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
            Outcome::Unsat(_) if always.len() < g.plans.len() => {
                self.undecided(
                    "coverage-gap",
                    &format!(
                        "whether every {} has an applicable plan",
                        g.event_text(None)
                    ),
                    ": the plans that cover every state are added or removed at run time",
                    span,
                    "the first plan for this goal",
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

    /// Whether some of `plans` (the live ones) is applicable for every event of the group in
    /// every state: `None` when z3 cannot say.
    fn covered(
        &self,
        g: &Group,
        plans: &[usize],
        base: &Base,
        alive: &BTreeMap<usize, Alive>,
    ) -> Option<bool> {
        let (_, event, dom) = self.event(g);
        let mut parts = vec![dom];
        for &i in plans {
            if !matches!(alive.get(&i), Some(Alive::Dead)) {
                parts.push(self.applicable(i, &event).ok()?.not());
            }
        }
        match base.witness(&and(parts), &[]).0 {
            Outcome::Unsat(_) => Some(true),
            Outcome::Sat(_) => Some(false),
            Outcome::Unknown(_) => None,
        }
    }
}
