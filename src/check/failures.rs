//! The checks one transition decides: `action-failure` and `goal-failure`. The search
//! records the first transition that shows each failure; the findings report it with the
//! run that takes it.

use super::checker::Checker;
use crate::findings::{Finding, Status};
use crate::semantics::{EventTrigger, Note, Origin};
use crate::syntax::ast::TriggerOp;
use crate::syntax::Span;
use std::collections::BTreeMap;

/// The first (hence shallowest-source) transition of each failure, keyed by place.
#[derive(Default)]
pub(super) struct Failures {
    pub(super) actions: BTreeMap<(u32, u32), Failure>,
    pub(super) goals: BTreeMap<String, Failure>,
    pub(super) no_plan: BTreeMap<(String, usize), Failure>,
    /// The plans some run adopts, a bit per plan ([`super::search::bit`]): the merging
    /// thread meets a plan's adoption at most transitions, and a tree's lookup each time
    /// cost more than the rest of this record.
    pub(super) applied: Vec<u64>,
}

impl Failures {
    /// Records the failures a transition shows.
    pub(super) fn record<'n>(
        &mut self,
        src: u32,
        k: u32,
        fp: u64,
        notes: impl Iterator<Item = &'n Note>,
    ) {
        for n in notes {
            let at = || Failure {
                src,
                k,
                fp,
                note: n.clone(),
            };
            match n {
                Note::ActionFailed { span, .. } => {
                    self.actions
                        .entry((span.file.0, span.start))
                        .or_insert_with(at);
                }
                Note::GoalFailed { goal, span, .. } => {
                    let key = match span {
                        Some(sp) => format!("{}:{}", sp.file.0, sp.start),
                        None => goal.to_string(),
                    };
                    self.goals.entry(key).or_insert_with(at);
                }
                Note::NoApplicablePlan(t) => {
                    let key = (
                        t.literal.functor().unwrap_or("").to_string(),
                        t.literal.arity(),
                    );
                    self.no_plan.entry(key).or_insert_with(at);
                }
                Note::Plan { plan, .. } => super::search::set_bit(&mut self.applied, *plan, true),
                _ => {}
            }
        }
    }
}

/// A transition that shows a failure: where it starts, its number there, the fingerprint
/// of its target, and the note.
pub(super) struct Failure {
    pub(super) src: u32,
    pub(super) k: u32,
    pub(super) fp: u64,
    pub(super) note: Note,
}

impl Checker<'_> {
    /// Where a goal that failed with no step to blame is at fault: its plans (none of
    /// which applied), or, when it has none, the request or initial goal that posted it.
    fn goal_place(&self, cause: &EventTrigger, origin: &Origin) -> Span {
        let sem = self.agent.sem;
        let goal_event = EventTrigger {
            op: TriggerOp::Add,
            ..cause.clone()
        };
        if let Some(&p) = sem.relevant_plans(&goal_event).first() {
            return sem.plan(p).span;
        }
        match *origin {
            Origin::Request(r) => {
                let t = &sem.requests[r as usize];
                let matches = |e: &crate::syntax::ast::Expr| match &e.kind {
                    crate::syntax::ast::ExprKind::Literal(l) => {
                        Some(l.functor.as_str()) == t.functor() && l.args.len() == t.arity()
                    }
                    _ => false,
                };
                if let Some(g) = self
                    .project
                    .manifest
                    .requests
                    .goals
                    .iter()
                    .find(|g| matches(&g.expr))
                {
                    return g.span;
                }
            }
            Origin::InitialGoal(k) => {
                if let Some((_, span)) = self.project.plans.initial_goals.get(k as usize) {
                    return *span;
                }
            }
            Origin::Spawned => {}
        }
        self.project.manifest.agent.plans.written.span
    }

    pub(super) fn failures(
        &self,
        out: &mut Vec<Finding>,
        actions: BTreeMap<(u32, u32), Failure>,
        goals: BTreeMap<String, Failure>,
    ) {
        let span = self.project.manifest.agent.plans.written.span;
        if actions.is_empty() {
            out.push(self.finding(
                "action-failure",
                "all",
                span,
                self.held(),
                "no action is ever attempted when its precondition does not hold".into(),
            ));
        }
        for x in actions.values() {
            if let Note::ActionFailed {
                text,
                plan,
                span,
                reason,
            } = &x.note
            {
                let loc = self.location(*span);
                let plan = &self.project.plans.plans[*plan as usize];
                let mut f = self.finding(
                    "action-failure",
                    &format!("{}:{}", loc.file, loc.line),
                    *span,
                    Status::Fail,
                    format!("`{text}` in plan {} fails: {reason}", plan.name()),
                );
                f.id = format!("action-failure:{}:{}", loc.file, loc.line);
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(x.src), Some(x), &[]));
                out.push(f);
            }
        }
        if goals.is_empty() {
            out.push(self.finding(
                "goal-failure",
                "all",
                span,
                self.held(),
                "no goal ever fails without a failure plan to handle it".into(),
            ));
        }
        for x in goals.values() {
            if let Note::GoalFailed {
                goal,
                cause,
                span: at,
                reason,
                origin,
                ..
            } = &x.note
            {
                let place = at.unwrap_or_else(|| self.goal_place(cause, origin));
                let loc = self.location(place);
                let what = if goal == cause {
                    format!("goal {goal} fails ({reason})")
                } else {
                    format!("{cause} fails ({reason}), so goal {goal} fails")
                };
                let mut f = self.finding(
                    "goal-failure",
                    "",
                    place,
                    Status::Fail,
                    format!("{what}, and no failure plan handles it: the intention is dropped"),
                );
                f.id = format!("goal-failure:{}:{}", loc.file, loc.line);
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(x.src), Some(x), &[]));
                out.push(f);
            }
        }
    }
}
