//! The checks that need no solver, about names: `undefined-action`, `undefined-predicate`,
//! `unused-action` and `no-plan-for-goal`. They point at the call, the action or the goal's
//! first mention instead of a state.

use super::{walk, Linter};
use crate::findings::Status;
use crate::model::plans::BodyStep;
use crate::syntax::ast::{ExprKind, TriggerKind, TriggerOp};
use crate::syntax::Span;
use std::collections::{BTreeMap, BTreeSet};

impl Linter<'_> {
    // ----- undefined-action, unused-action, no-plan-for-goal -----------------------------

    pub(super) fn undefined_tests(&mut self) {
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

    pub(super) fn undefined_actions(&mut self) {
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

    pub(super) fn unused_actions(&mut self) {
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

    pub(super) fn goals_without_plans(&mut self) {
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
