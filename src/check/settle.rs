//! Settling lint's findings by the runs (SPEC §3): a static warning some run reaches
//! becomes an error with that run, one no run reaches (a complete search) a note, and
//! plan checks lint left undecided are decided by the plans the runs adopt.

use super::checker::Checker;
use super::failures::Failure;
use crate::findings::{Counterexample, Finding, Status};
use crate::model::project::Project;
use crate::semantics::Note;
use crate::syntax::{Severity, Span};
use std::collections::BTreeMap;

/// Decides with the runs the plan checks lint could not decide (z3's budget, arithmetic
/// it does not model): a plan some run adopts is not dead, nor hidden by an earlier one
/// (with Jason's first-applicable selection); a goal for which no run meets a state where
/// no plan applies, in a complete search, has no gap any run reaches.
pub(super) fn settle_undecided(
    findings: &mut [Finding],
    project: &Project,
    applied: impl Fn(u32) -> bool,
    no_plan: &BTreeMap<(String, usize), Failure>,
    complete: bool,
) {
    let first =
        project.manifest.bounds.plan_selection == crate::syntax::manifest::PlanSelection::First;
    for f in findings.iter_mut() {
        if f.status != Status::Unknown {
            continue;
        }
        let Some(i) = project
            .plans
            .plans
            .iter()
            .position(|p| Some(p.span) == f.span)
        else {
            continue;
        };
        let plan = &project.plans.plans[i];
        match f.check.as_str() {
            "dead-plan" if applied(i as u32) => {
                f.status = Status::Pass;
                f.message = format!("{} is applicable: a run adopts it", plan.name());
            }
            "shadowed-plan" if first && applied(i as u32) => {
                f.status = Status::Pass;
                f.message = format!("no earlier plan hides {}: a run adopts it", plan.name());
            }
            // Decided for the model, not for every state: no run adopts the plan. True and
            // worth saying, but a warning (a bound such as `[requests] max` may be why).
            "dead-plan" | "shadowed-plan" if complete && !applied(i as u32) => {
                f.status = Status::Fail;
                f.severity = Severity::Warning;
                f.message = format!(
                    "no run adopts {} (lint could not decide whether some state makes it applicable, but every reachable state was explored)",
                    plan.name()
                );
            }
            "coverage-gap" if complete => {
                let t = &plan.trigger.literal;
                let key = (t.functor().unwrap_or("").to_string(), t.arity());
                if !no_plan.contains_key(&key) {
                    f.status = Status::Pass;
                    f.message = format!(
                        "no run meets a state where no plan for {} applies",
                        plan.trigger
                    );
                }
            }
            _ => {}
        }
    }
}

/// Settles lint's `action-breaks-invariant` warnings with the invariants the search
/// checked: an action that can break an invariant from some state only matters when a
/// run breaks it. Reached, the warning is an error with the run that breaks the
/// invariant; never reached (a complete search), a note: the invariant is not inductive,
/// but holds in every reachable state.
pub(super) fn settle_non_inductive(findings: &mut [Finding], project: &Project, complete: bool) {
    let broken: Vec<(String, Option<Counterexample>)> = project
        .invariants
        .iter()
        .filter_map(|(name, _)| {
            let f = findings.iter().find(|f| {
                f.check == "invariant"
                    && f.status == Status::Fail
                    && f.message.starts_with(&format!("invariant `{name}` "))
            })?;
            Some((name.clone(), f.counterexample.clone()))
        })
        .collect();
    for f in findings.iter_mut() {
        if f.check != "action-breaks-invariant"
            || f.status != Status::Fail
            || f.severity != Severity::Warning
        {
            continue;
        }
        let hit = broken
            .iter()
            .find(|(name, _)| f.message.contains(&format!("`{name}` (after")));
        match hit {
            Some((name, cx)) => {
                f.severity = Severity::Error;
                f.message = format!("{} — and a run breaks `{name}`", f.message);
                f.counterexample = cx.clone();
            }
            None if complete => {
                f.severity = Severity::Note;
                f.message = format!(
                    "{} — but no run breaks it: the invariant is not inductive, yet it holds in every reachable state",
                    f.message
                );
            }
            None => {}
        }
    }
}

impl Checker<'_> {
    /// A precondition lint could not decide from a step on (arithmetic it does not model):
    /// a run whose action of that plan, there or later, fails settles it as an error with
    /// that run; a complete search with none, as a pass.
    fn settle_undecided_precondition(
        &self,
        f: &Finding,
        action_failures: &BTreeMap<(u32, u32), Failure>,
    ) -> Finding {
        let mut g = f.clone();
        let Some(from) = f.span else { return g };
        let Some(i) = self.project.plans.plans.iter().position(|p| {
            p.span.file == from.file && p.span.start <= from.start && from.start < p.span.end
        }) else {
            return g;
        };
        let plan = &self.project.plans.plans[i];
        let failed = action_failures.values().find(|x| {
            matches!(&x.note, Note::ActionFailed { plan: p, span, .. }
                if *p as usize == i && span.file == from.file && span.start >= from.start)
        });
        match failed {
            Some(x) => {
                let Note::ActionFailed { text, reason, .. } = &x.note else {
                    return g;
                };
                g.status = Status::Fail;
                g.severity = Severity::Error;
                g.message = format!(
                    "`{text}` in {} fails in a run ({reason}), after a step lint could not decide",
                    plan.name()
                );
                g.counterexample =
                    Some(self.counterexample(&self.graph.path_to(x.src), Some(x), &[]));
            }
            None if self.graph.complete() => {
                g.status = Status::Pass;
                g.message = format!(
                    "no run of {} attempts an action from here on when its precondition does not hold",
                    plan.name()
                );
            }
            None => {}
        }
        g
    }
}

/// Whether a lint finding is one that exploration settles.
pub(super) fn settles(f: &Finding) -> bool {
    matches!(
        f.check.as_str(),
        "coverage-gap" | "plan-overlap" | "precondition"
    ) && f.status == Status::Fail
        && f.severity == Severity::Warning
}

/// A run reaching a state: the path to it, and the transition taken there, if any.
type Reach<'f> = (Vec<u32>, Option<&'f Failure>);

impl Checker<'_> {
    /// Settles one static finding against the explored graph.
    pub(super) fn settle(
        &self,
        f: &Finding,
        action_failures: &BTreeMap<(u32, u32), Failure>,
        no_plan: &BTreeMap<(String, usize), Failure>,
    ) -> Finding {
        let plan_at = |sp: Span| self.project.plans.plans.iter().position(|p| p.span == sp);
        if f.check == "coverage-gap" && f.status == Status::Unknown {
            // Undecided by lint, decided by a run that meets the gap (the pass, when none
            // does, is `settle_undecided`'s).
            let reached = f.span.and_then(plan_at).and_then(|i| {
                let t = &self.project.plans.plans[i].trigger.literal;
                no_plan.get(&(t.functor().unwrap_or("").to_string(), t.arity()))
            });
            let mut g = f.clone();
            if let Some(x) = reached {
                let Note::NoApplicablePlan(t) = &x.note else {
                    return g;
                };
                g.status = Status::Fail;
                g.severity = Severity::Error;
                g.message = format!("no plan for {t} is applicable in a state a run reaches");
                let path = self.graph.path_to(x.src);
                g.counterexample = Some(self.counterexample(&path, Some(x), &[]));
            }
            return g;
        }
        if f.check == "precondition" && f.status == Status::Unknown {
            return self.settle_undecided_precondition(f, action_failures);
        }
        if !settles(f) {
            return f.clone();
        }
        let Some(span) = f.span else { return f.clone() };
        let reached: Option<Reach> = match f.check.as_str() {
            "precondition" => action_failures
                .get(&(span.file.0, span.start))
                .map(|x| (self.graph.path_to(x.src), Some(x))),
            "coverage-gap" => plan_at(span).and_then(|i| {
                let t = &self.project.plans.plans[i].trigger.literal;
                no_plan
                    .get(&(t.functor().unwrap_or("").to_string(), t.arity()))
                    .map(|x| (self.graph.path_to(x.src), Some(x)))
            }),
            _ => {
                // plan-overlap: the later plan at the finding, the earlier one beside it.
                let later = plan_at(span);
                let earlier = f.secondary_plan_span().and_then(plan_at);
                match (earlier, later) {
                    (Some(a), Some(b)) => self
                        .overlap(a as u32, b as u32)
                        .map(|i| (self.graph.path_to(i), None)),
                    _ => None,
                }
            }
        };
        let mut g = f.clone();
        match reached {
            Some((path, extra)) => {
                g.severity = Severity::Error;
                g.message = format!("{} — and a run reaches it", f.message);
                g.counterexample = Some(self.counterexample(&path, extra, &[]));
            }
            None if self.graph.complete() => {
                g.severity = Severity::Note;
                g.message = format!("{} — but no run reaches it", f.message);
            }
            None => {}
        }
        g
    }

    /// The first explored state whose next event has both plans applicable.
    fn overlap(&self, a: u32, b: u32) -> Option<u32> {
        let c = self.conditions;
        let k = c.overlaps.iter().position(|&p| p == (a, b))?;
        self.facts.first_holds[c.invariants.len() + c.props.len() + k]
    }
}
