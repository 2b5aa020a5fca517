//! The internal actions that change intentions other than the one running them:
//! `.succeed_goal` and `.fail_goal`, over the events, the running intentions and the one
//! waiting for its action. Mirrors the stdlib's `succeed_goal` (`drop`, `dropIntention`)
//! and `fail_goal` (`dropInEvent`), with `Intention.dropGoal`. The other internal actions
//! that touch the agent's state (`.print`, `.abolish`, `.drop_desire`/`.drop_intention`,
//! and those answered as queries, such as `.desire`/`.intend`) run where `execute.rs`
//! executes the step.

use super::cycle::{Note, Semantics};
use super::state::{Event, EventTrigger, Intention, State};
use crate::model::term::Term;
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::Span;

impl Semantics<'_> {
    /// `.succeed_goal(g)` / `.fail_goal(g)` run by `current`, as Jason's
    /// `succeed_goal.drop`: in the events, then in the running intentions, then in the
    /// running one, then in the one waiting for its action, then in those in `.wait`,
    /// every intention pursuing `g`
    /// drops its plans down to and including `g`'s ([`Semantics::drop_goal_in`]); an event
    /// `+!g` is dropped (succeed: the intention that posted it goes on) or becomes `-!g`
    /// (fail). The running intention then goes on after its current step
    /// (`removeActionReQueue`, after the others), which, when its own `g` was dropped, is
    /// the `!g` of the plan below.
    pub(super) fn goal_directive(
        &self,
        s: &mut State,
        current: Intention,
        g: &Term,
        fail: bool,
        at: (u32, Span),
        notes: &mut Vec<Note>,
    ) {
        let is_goal = |t: &EventTrigger| {
            t.op == TriggerOp::Add
                && t.kind == TriggerKind::Achieve
                && crate::model::unifier(g, &t.literal).is_some()
        };
        for ev in std::mem::take(&mut s.events) {
            if let Some(int) = &ev.intention {
                if int.frames.iter().any(|f| is_goal(&f.trigger)) {
                    let int = ev.intention.expect("checked");
                    if let Some(int) = self.drop_goal_in(s, int, g, fail, false, at, notes) {
                        // `resumeIntention`.
                        self.add_running(s, int);
                    }
                    continue;
                }
            }
            if !is_goal(&ev.trigger) {
                s.events.push(ev);
            } else if fail {
                // `fail_goal.dropInEvent`: the event turns into `-!g`, in its place.
                self.post_event(
                    s,
                    Event {
                        trigger: EventTrigger {
                            op: TriggerOp::Del,
                            ..ev.trigger
                        },
                        ..ev
                    },
                );
            } else if let Some(mut int) = ev.intention {
                if let Some(top) = int.frames.last_mut() {
                    top.calling = None;
                    self.normalize(top);
                }
                if self.clear_finished(&mut int, notes) {
                    self.add_running(s, int);
                }
            } else {
                notes.push(Note::Finished(ev.origin));
            }
        }
        for int in std::mem::take(&mut s.intentions) {
            if int.frames.iter().any(|f| is_goal(&f.trigger)) {
                if let Some(int) = self.drop_goal_in(s, int, g, fail, false, at, notes) {
                    s.intentions.push(int);
                }
            } else {
                s.intentions.push(int);
            }
        }
        let mut current = Some(current);
        if let Some(int) = current.take_if(|i| i.frames.iter().any(|f| is_goal(&f.trigger))) {
            current = self.drop_goal_in(s, int, g, fail, true, at, notes);
        }
        if let Some(p) = s.pending.take() {
            if p.intention.frames.iter().any(|f| is_goal(&f.trigger)) {
                if let Some(int) = self.drop_goal_in(s, p.intention, g, fail, false, at, notes) {
                    self.add_running(s, int);
                }
            } else {
                s.pending = Some(p);
            }
        }
        // Last, the pending intentions (`Circumstance.PI`): those in `.wait`.
        let (hit, kept): (Vec<_>, Vec<_>) = std::mem::take(&mut s.waiting)
            .into_iter()
            .partition(|w| w.intention.frames.iter().any(|f| is_goal(&f.trigger)));
        s.waiting = kept;
        for w in hit {
            if let Some(int) = self.drop_goal_in(s, w.intention, g, fail, false, at, notes) {
                self.add_running(s, int);
            }
        }
        if let Some(mut int) = current {
            // `removeActionReQueue`, once the internal action is done: the step just run
            // is done (for a plan below a dropped goal, that is its `!g`), and the
            // intention back in the queue (`AI` when atomic), then `applyClrInt`.
            if let Some(top) = int.frames.last_mut() {
                top.calling = None;
                self.normalize(top);
            }
            let atomic = self.is_atomic(&int);
            if self.clear_finished(&mut int, notes) {
                self.requeue(s, int, atomic);
            }
        }
    }

    /// Whether `.fail_goal(g)` would drop the bottom goal of some intention (`current`, the
    /// running one, or one in an event, in the queue, awaiting feedback or in `.wait`):
    /// `Intention.dropGoal` then leaves it empty, and `fail_goal.dropIntention` passes it to
    /// `TransitionSystem.findEventForFailure`, whose `getPLForIM(i.peek())` throws.
    pub(super) fn fails_a_bottom_goal(&self, s: &State, current: &Intention, g: &Term) -> bool {
        let bottom = |i: &Intention| {
            i.frames.first().is_some_and(|f| {
                f.trigger.op == TriggerOp::Add
                    && f.trigger.kind == TriggerKind::Achieve
                    && crate::model::unifier(g, &f.trigger.literal).is_some()
            })
        };
        bottom(current)
            || s.intentions.iter().any(bottom)
            || s.events
                .iter()
                .filter_map(|e| e.intention.as_ref())
                .any(bottom)
            || s.pending.as_ref().is_some_and(|p| bottom(&p.intention))
            || s.waiting.iter().any(|w| bottom(&w.intention))
    }

    /// Jason's `dropIntention` of `succeed_goal` and `fail_goal` on an intention pursuing
    /// `g` (`Intention.dropGoal` pops its plans down to and including the lowest plan for
    /// `g`). Succeed: the plan below goes on after its `!g` (for the running intention,
    /// the caller does that); the intention is returned to run on. Fail: the failure event
    /// for `+!g` is looked for from the plan below (`findEventForFailure`); with one, the
    /// intention waits in it (the running one with its current step done, as Jason's
    /// `removeActionReQueue` then removes it); with none, the running intention goes on
    /// and any other is dropped. Returns the intention when it runs on.
    #[allow(clippy::too_many_arguments)]
    fn drop_goal_in(
        &self,
        s: &mut State,
        mut int: Intention,
        g: &Term,
        fail: bool,
        current: bool,
        at: (u32, Span),
        notes: &mut Vec<Note>,
    ) -> Option<Intention> {
        let j = int
            .frames
            .iter()
            .position(|f| {
                f.trigger.op == TriggerOp::Add
                    && f.trigger.kind == TriggerKind::Achieve
                    && crate::model::unifier(g, &f.trigger.literal).is_some()
            })
            .expect("the intention pursues g");
        let dropped = int.frames[j].trigger.clone();
        int.frames.truncate(j);
        if !fail {
            if int.frames.is_empty() {
                notes.push(Note::Finished(int.origin));
                return None;
            }
            if current {
                return Some(int);
            }
            if let Some(top) = int.frames.last_mut() {
                top.calling = None;
                self.normalize(top);
            }
            return self.clear_finished(&mut int, notes).then_some(int);
        }
        let tevent = EventTrigger {
            op: TriggerOp::Add,
            kind: TriggerKind::Achieve,
            literal: g.clone(),
        };
        match self.find_event_for_failure(s.library.as_deref(), &int, &tevent) {
            Some(_) if current && self.is_atomic(&int) => {
                // `removeActionReQueue` then makes it `AI` too.
                notes.push(self.atomic_beyond(at.0, at.1, "`.fail_goal` of its own goal"));
                None
            }
            Some(fail) => {
                if current {
                    if let Some(top) = int.frames.last_mut() {
                        top.calling = None;
                        self.normalize(top);
                    }
                }
                let origin = int.origin;
                self.post_event(
                    s,
                    Event {
                        trigger: fail,
                        intention: Some(int),
                        origin,
                        posted_at: Some(at),
                    },
                );
                None
            }
            None if current => Some(int),
            None => {
                let goal = int
                    .frames
                    .first()
                    .map_or(dropped.clone(), |f| f.trigger.clone());
                notes.push(Note::GoalFailed {
                    goal,
                    cause: dropped,
                    plan: Some(at.0),
                    span: Some(at.1),
                    reason: "failed by .fail_goal".into(),
                    origin: int.origin,
                });
                None
            }
        }
    }
}
