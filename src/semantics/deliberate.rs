//! The deliberation phase: the selected event's relevant plans, the applicable ones, the
//! option chosen, and the intention it goes in (with Jason's tail-recursion optimisation).
//! Mirrors `TransitionSystem.applySelEv`, `applyRelPl` (`relevantPlans`), `applyApplPl`
//! (`applicablePlans`), `applySelAppl`, `applyAddIM`, and `applyRelApplPlRule2` for an
//! event with no relevant or applicable plan.

use super::cycle::{kind_key, op_key, Note, Semantics, MAX_STACK};
use super::query::{take_trouble, trouble_reason, Beliefs};
use super::state::{Cursor, CursorKind, Event, EventTrigger, Frame, Intention, State};
use crate::model::{unify, Substitution};
use crate::syntax::ast::{TriggerKind, TriggerOp};

impl Semantics<'_> {
    /// Every plan that may be relevant for `t`, in any library a run can reach (for the
    /// library of a state, `Semantics::relevant_in`).
    pub fn relevant_plans(&self, t: &EventTrigger) -> &[u32] {
        self.relevant
            .get(&(
                op_key(t.op),
                kind_key(t.kind),
                t.literal.functor().unwrap_or("").to_string(),
                t.literal.arity(),
            ))
            .map_or(&[], |v| v.as_slice())
    }

    /// Handles one event (already out of the queue): every option the plan selection
    /// allows, as its own state. An external belief event with no applicable plan is
    /// discarded and the next event handled in the same cycle, as Jason's
    /// `applyRelApplPlRule2` goes back to `SelEv`.
    pub(super) fn deliberate(&self, s: State, ev: Event) -> Vec<(State, Vec<Note>)> {
        let (mut options, goes_on) = self.deliberate_event(s, ev);
        if goes_on {
            let (mut s, notes) = options.pop().expect("the discarded event's outcome");
            if s.events.is_empty() {
                return vec![(s, notes)];
            }
            let next = s.events.remove(0);
            let mut more = self.deliberate(s, next);
            for (_, n) in &mut more {
                n.splice(0..0, notes.iter().cloned());
            }
            return more;
        }
        options
    }

    /// [`Semantics::deliberate`] on one event, and whether the deliberation goes on to
    /// the next event (then the one outcome is the state without the event).
    pub(super) fn deliberate_event(&self, s: State, ev: Event) -> (Vec<(State, Vec<Note>)>, bool) {
        let mut notes = vec![Note::Event(ev.trigger.clone())];
        take_trouble();
        let applicable = self.applicable_for(&s, &ev, !self.select_any);
        if let Some(e) = take_trouble() {
            // A context's arithmetic that Jason throws on (the deliberation's exception
            // resets the circumstance) or goes on past with a non-number: refused.
            // The plan whose context met it (asked again, one plan at a time: rare path).
            let relevant = self.relevant_in(s.library.as_deref(), &ev.trigger);
            let plan = relevant
                .iter()
                .copied()
                .find(|&pi| {
                    let plan = self.plan(pi);
                    let mut u = Substitution::new();
                    if unify(&plan.trigger.literal, &ev.trigger.literal, &mut u) {
                        let mut b = self.beliefs(&s);
                        b.selected = Some(&ev);
                        b.answers(&plan.context, &u);
                    }
                    take_trouble().is_some()
                })
                .or(relevant.first().copied())
                .unwrap_or(0);
            let span = self.plan(plan).span;
            notes.push(Note::Beyond {
                text: format!("the contexts of the plans for {}", ev.trigger),
                plan,
                span,
                reason: trouble_reason(e),
            });
            return (vec![(s, notes)], false);
        }
        if applicable.is_empty() {
            let mut s = s;
            if ev.trigger.kind != TriggerKind::Belief {
                notes.push(Note::NoApplicablePlan(ev.trigger.clone()));
            }
            if ev.trigger.op == TriggerOp::Add && ev.trigger.kind != TriggerKind::Belief {
                let reason = if self
                    .relevant_in(s.library.as_deref(), &ev.trigger)
                    .is_empty()
                {
                    "no relevant plan"
                } else {
                    "no applicable plan"
                };
                self.goal_failed_from_event(&mut s, ev, reason, &mut notes);
            } else if ev.trigger.op == TriggerOp::Del && ev.trigger.kind != TriggerKind::Belief {
                // A failure event nothing can handle: Jason's "Could not finish
                // intention"; the intention is gone.
                let goal = ev
                    .intention
                    .as_ref()
                    .and_then(|i| i.frames.first())
                    .map_or_else(|| ev.trigger.clone(), |f| f.trigger.clone());
                notes.push(Note::GoalFailed {
                    goal,
                    cause: ev.trigger.clone(),
                    plan: ev.posted_at.map(|(p, _)| p),
                    span: ev.posted_at.map(|(_, sp)| sp),
                    reason: "no applicable failure plan".into(),
                    origin: ev.origin,
                });
            } else if let Some(int) = ev.intention {
                // A belief event an intention waits in: it goes on after its belief update
                // (TransitionSystem.applyRelApplPlRule2, an internal event:
                // removeActionReQueue).
                self.add_running(&mut s, int);
            } else {
                // An external one is discarded, and another event selected.
                return (vec![(s, notes)], true);
            }
            return (vec![(s, notes)], false);
        }
        let options = applicable
            .into_iter()
            .map(|(pi, answer)| {
                let mut s = s.clone();
                let mut notes = notes.clone();
                let plan = self.plan(pi);
                let mut frame = Frame {
                    plan: pi,
                    subst: answer,
                    cursors: if plan.body.is_empty() {
                        Vec::new()
                    } else {
                        vec![Cursor {
                            block: 0,
                            pos: 0,
                            kind: CursorKind::Seq,
                        }]
                    },
                    trigger: ev.trigger.clone(),
                    calling: None,
                };
                self.normalize(&mut frame);
                let origin = match &ev.intention {
                    Some(i) => i.origin,
                    None => ev.origin,
                };
                let subst = frame.subst.clone();
                let depth = match ev.intention.clone() {
                    // `C.addRunningIntention`: an atomic plan's new intention is `C.AI`.
                    None => {
                        let int = Intention {
                            frames: vec![frame],
                            origin,
                        };
                        self.add_running(&mut s, int);
                        0
                    }
                    Some(int) if int.frames.len() >= MAX_STACK => {
                        let goal = int.frames.first().map(|f| f.trigger.clone());
                        notes.push(Note::GoalFailed {
                            goal: goal.unwrap_or_else(|| ev.trigger.clone()),
                            cause: ev.trigger.clone(),
                            plan: Some(pi),
                            span: Some(plan.span),
                            reason: format!(
                                "its intention would hold more than {MAX_STACK} plans (Jason grows it without bound)"
                            ),
                            origin,
                        });
                        return (s, notes);
                    }
                    Some(mut int) => {
                        // Trigger.isGoal: an achievement or a test goal.
                        let is_goal_add = |t: &EventTrigger| {
                            t.op == TriggerOp::Add
                                && matches!(t.kind, TriggerKind::Achieve | TriggerKind::Test)
                        };
                        if let Some(top) = int.frames.last() {
                            // Jason's TRO (TransitionSystem.applyAddIM, under `isTROon()`): the
                            // plan on top finished with `!g` or `?g`, both triggers goal
                            // additions of one predicate indicator.
                            if is_goal_add(&ev.trigger)
                                && top.cursors.is_empty()
                                && top.calling.is_some()
                                && is_goal_add(&top.trigger)
                                && top.trigger.literal.functor() == ev.trigger.literal.functor()
                                && top.trigger.literal.arity() == ev.trigger.literal.arity()
                            {
                                int.frames.pop();
                            }
                        }
                        int.frames.push(frame);
                        let depth = int.frames.len() - 1;
                        self.add_running(&mut s, int);
                        depth
                    }
                };
                notes.push(Note::Plan {
                    plan: pi,
                    origin,
                    subst,
                    depth: depth as u16,
                });
                (s, notes)
            })
            .collect();
        (options, false)
    }

    /// The applicable plans for an event in `s`, in source order, each with the first
    /// answer of its context; only the first one when `first_only`.
    pub fn applicable(
        &self,
        s: &State,
        trigger: &EventTrigger,
        first_only: bool,
    ) -> Vec<(u32, Substitution)> {
        self.applicable_in(self.beliefs(s), trigger, first_only)
    }

    /// As [`Semantics::applicable`], for the event just taken out of the queue of `s`.
    fn applicable_for(&self, s: &State, ev: &Event, first_only: bool) -> Vec<(u32, Substitution)> {
        let mut b = self.beliefs(s);
        b.selected = Some(ev);
        self.applicable_in(b, &ev.trigger, first_only)
    }

    fn applicable_in(
        &self,
        b: Beliefs,
        trigger: &EventTrigger,
        first_only: bool,
    ) -> Vec<(u32, Substitution)> {
        let mut out = Vec::new();
        for &pi in self.relevant_in(b.state.library.as_deref(), trigger).iter() {
            let plan = self.plan(pi);
            let mut u = Substitution::new();
            if !unify(&plan.trigger.literal, &trigger.literal, &mut u) {
                continue;
            }
            if let Some(answer) = b.answers(&plan.context, &u).into_iter().next() {
                out.push((pi, answer));
                if first_only {
                    break;
                }
            }
        }
        out
    }
}
