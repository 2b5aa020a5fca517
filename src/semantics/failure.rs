//! Failure handling and the clearing of finished plans: the failure event of a failed step
//! or of a goal with no applicable plan, the goal down the stack that gets it, and the
//! popping of finished plans (a finished failure plan takes the plans above the goal it
//! handled). Mirrors `TransitionSystem.generateGoalDeletion`,
//! `generateGoalDeletionFromEvent`, `Intention.findEventForFailure` and
//! `TransitionSystem.applyClrInt`.

use super::cycle::{Note, Semantics};
use super::state::{Event, EventTrigger, Frame, InLibrary, Intention, State};
use crate::model::term::Term;
use crate::model::unify;
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::Span;

impl Semantics<'_> {
    /// The line of a step, for failure annotations.
    fn line_of(&self, at: Option<(u32, Span)>) -> Option<usize> {
        at.map(|(_, span)| self.project.map.location(span).line)
    }

    /// No applicable plan for the goal addition `ev` (`+!g` or `+?g`): Jason's
    /// `generateGoalDeletionFromEvent`. The failure event is looked for from the event's
    /// own goal down the intention that waits for it; with none, that intention is
    /// dropped (an external event just fails).
    pub(super) fn goal_failed_from_event(
        &self,
        s: &mut State,
        ev: Event,
        reason: &str,
        notes: &mut Vec<Note>,
    ) {
        let lib = s.library.as_deref();
        let fail = match &ev.intention {
            Some(int) => self.find_event_for_failure(lib, int, &ev.trigger),
            // `TransitionSystem.findEventForFailure` of an external goal (`EmptyInt`): `-!g`
            // when the library has a candidate plan for it.
            None => {
                let del = EventTrigger {
                    op: TriggerOp::Del,
                    kind: ev.trigger.kind,
                    literal: ev.trigger.literal.clone(),
                };
                (ev.trigger.kind != TriggerKind::Belief && !self.relevant_in(lib, &del).is_empty())
                    .then_some(del)
            }
        };
        let error = if self
            .relevant_in(s.library.as_deref(), &ev.trigger)
            .is_empty()
        {
            "no_relevant"
        } else {
            "no_applicable"
        };
        match (fail, ev.intention) {
            (Some(fail), int) => self.post_event(
                s,
                Event {
                    trigger: with_error(fail, (error, &[]), self.line_of(ev.posted_at)),
                    intention: int,
                    origin: ev.origin,
                    posted_at: ev.posted_at,
                },
            ),
            (_, int) => notes.push(Note::GoalFailed {
                goal: int
                    .as_ref()
                    .and_then(|i| i.frames.first())
                    .map_or_else(|| ev.trigger.clone(), |f| f.trigger.clone()),
                cause: ev.trigger,
                plan: ev.posted_at.map(|(p, _)| p),
                span: ev.posted_at.map(|(_, sp)| sp),
                reason: reason.into(),
                origin: ev.origin,
            }),
        }
    }

    /// Jason's `Intention.findEventForFailure`, in library `lib`: the failure event for
    /// `tevent`, the trigger that failed (the top plan's, or a subgoal event's that had no
    /// applicable plan). From the top of the stack down, the first goal with a relevant `-`
    /// plan gets it. When a failure plan itself failed (`tevent` is `-!g`), the search starts
    /// below the frames of `g`; if `g` is the bottom of the stack, `-!g` is posted again.
    pub(super) fn find_event_for_failure(
        &self,
        lib: Option<&[InLibrary]>,
        int: &Intention,
        tevent: &EventTrigger,
    ) -> Option<EventTrigger> {
        let frames = &int.frames;
        // Jason's iterator over the stack, top first: `next` frames remain.
        let mut next = frames.len();
        let mut tevent = tevent.clone();
        let unifies = |f: &Frame, t: &EventTrigger| {
            crate::model::unifier(&f.trigger.literal, &t.literal).is_some()
        };
        if tevent.kind != TriggerKind::Belief && tevent.op == TriggerOp::Del && next > 0 {
            next -= 1; // the failed failure plan
            let mut im = next;
            let mut found = false;
            while next > 0 && !found {
                next -= 1;
                im = next;
                while next > 0 && unifies(&frames[im], &tevent) {
                    next -= 1;
                    im = next;
                    found = true;
                }
            }
            tevent = frames[im].trigger.clone();
        }
        let del = |t: &EventTrigger| EventTrigger {
            op: TriggerOp::Del,
            kind: t.kind,
            literal: t.literal.clone(),
        };
        let mut fail = del(&tevent);
        while self.relevant_in(lib, &fail).is_empty() && next > 0 {
            next -= 1;
            tevent = frames[next].trigger.clone();
            fail = del(&tevent);
        }
        (tevent.kind != TriggerKind::Belief && !self.relevant_in(lib, &fail).is_empty())
            .then_some(fail)
    }

    /// A step of the top plan of `int` failed: Jason's `generateGoalDeletion`. The stack
    /// stays as it is (the failed plan marked failed, its step not done) and the failure
    /// event carries it; with no failure event, the intention is dropped.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fail_intention(
        &self,
        s: &mut State,
        mut int: Intention,
        failed: &EventTrigger,
        step: Option<(u32, Span)>,
        reason: &str,
        error: (&str, &[Term]),
        notes: &mut Vec<Note>,
    ) {
        if let Some(top) = int.frames.last_mut() {
            top.calling = None;
        }
        let tevent = int
            .frames
            .last()
            .map_or_else(|| failed.clone(), |f| f.trigger.clone());
        if let Some(fail) = self.find_event_for_failure(s.library.as_deref(), &int, &tevent) {
            let origin = int.origin;
            self.post_event(
                s,
                Event {
                    trigger: with_error(fail, error, self.line_of(step)),
                    intention: Some(int),
                    origin,
                    posted_at: step,
                },
            );
            return;
        }
        let goal = int
            .frames
            .first()
            .map(|f| f.trigger.clone())
            .unwrap_or_else(|| failed.clone());
        notes.push(Note::GoalFailed {
            goal,
            cause: failed.clone(),
            plan: step.map(|(p, _)| p),
            span: step.map(|(_, sp)| sp),
            reason: reason.into(),
            origin: int.origin,
        });
    }

    /// Pops finished plans, as Jason's `applyClrInt`; returns whether the intention is
    /// still alive. A finished subgoal's bindings flow back into the plan that posted it,
    /// which goes on after its `!g`. A finished failure plan `-!g` takes with it the
    /// plans above the one it handled, down to the plan of `g` itself or to the plan whose
    /// step posted `g`, and the plan below goes on after its current step (the `!g`, or
    /// the step that failed, when a failure plan failed at the bottom of the stack).
    pub(super) fn clear_finished(&self, int: &mut Intention, notes: &mut Vec<Note>) -> bool {
        loop {
            let Some(top) = int.frames.last() else {
                notes.push(Note::Finished(int.origin));
                return false;
            };
            if !top.cursors.is_empty() {
                return true;
            }
            let depth = int.frames.len() - 1;
            let done = int.frames.pop().expect("a top frame");
            let top_literal = &done.trigger.literal;
            let unifies = |t: &Term| crate::model::unifier(t, top_literal).is_some();
            // Whether a frame's current step is `!L` for the goal just finished.
            let calls_top = |f: &Frame| f.calling.as_ref().is_some_and(&unifies);
            let handled_failure =
                done.trigger.kind != TriggerKind::Belief && done.trigger.op == TriggerOp::Del;
            if handled_failure && !int.frames.is_empty() {
                // `im` is the frame just popped; `None` when the top frame, peeked, is the
                // one whose `!g` step posted the goal.
                let top = int.frames.last().expect("a frame");
                let mut im = if calls_top(top) {
                    None
                } else {
                    int.frames.pop()
                };
                while !int.frames.is_empty() {
                    let Some(popped) = im.take() else { break };
                    let goal_frame = popped.trigger.kind != TriggerKind::Belief
                        && unifies(&popped.trigger.literal);
                    if goal_frame || calls_top(&popped) {
                        break;
                    }
                    im = int.frames.pop();
                }
                // The frame now on top goes on after its current step.
                if let Some(parent) = int.frames.last_mut() {
                    parent.calling = None;
                    self.normalize(parent);
                }
                continue;
            }
            if let Some(parent) = int.frames.last_mut() {
                // The subgoal's bindings flow back into the plan that posted it.
                let result = done.subst.apply(&done.trigger.literal).map_vars(&mut |v| {
                    if v.generation() == 0 {
                        Term::from(v.with_generation(1_000_000 + depth as u32))
                    } else {
                        Term::from(v.clone())
                    }
                });
                let asked = done.trigger.literal.map_vars(&mut |v| {
                    if v.generation() == depth as u32 {
                        Term::from(v.with_generation(0))
                    } else {
                        Term::from(v.clone())
                    }
                });
                let mut u = parent.subst.clone();
                if unify(&asked, &result, &mut u) {
                    parent.subst = u;
                }
                parent.calling = None;
                self.normalize(parent);
            }
        }
    }
}

/// A failure event's trigger with Jason's `error(Id)` and `code_line(Line)` annotations
/// and the exception's own (`agent_not_found(A)` of a `.send`) (`setDefaultFailureAnnots`;
/// `error_msg`, `code` and `code_src` are not given). The line
/// matters beyond plans that read it: when a failure plan ends, Jason drops the plans above
/// down to one whose goal unifies with the handled one, annotations included, so two
/// failures at different lines do not unify.
fn with_error(
    mut t: EventTrigger,
    (error, extra): (&str, &[Term]),
    line: Option<usize>,
) -> EventTrigger {
    let mut annots = vec![Term::structure("error", vec![Term::atom(error)])];
    annots.extend(extra.iter().cloned());
    if let Some(n) = line {
        annots.push(Term::structure("code_line", vec![Term::int(n as i64)]));
    }
    if let Some(l) = t.literal.add_annots(annots) {
        t.literal = l;
    }
    t
}
