//! The checks on actions: `precondition` (along each live plan body, executed symbolically),
//! and, per PDDL action over all its bindings, `effect-conflict` and
//! `action-breaks-invariant`.

use super::{state_cx, Base, Group, Linter};
use crate::findings::{Counterexample, Status};
use crate::model::atoms::AtomId;
use crate::model::cond::Cond;
use crate::smt::encode::{and, or, State, Unsupported};
use crate::smt::exec::{self, PreResult};
use crate::smt::solve::{truth, Outcome};
use crate::smt::text;
use crate::syntax::Span;
use std::collections::BTreeSet;
use z3::ast::{Bool, Int};
use z3::Model;

/// One conjunct of an invariant, with the atoms it reads.
type Conjunct = (Cond, BTreeSet<AtomId>);

impl Linter<'_> {
    // ----- precondition -------------------------------------------------------------------

    pub(super) fn preconditions(&mut self, g: &Group, i: usize) {
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

    pub(super) fn effect_conflicts(&mut self, base: &Base) {
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

    pub(super) fn invariant_breaks(&mut self, base: &Base) {
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
}
