//! Atomic intentions: an intention with a plan labelled `[atomic]` on its stack runs alone.
//! Mirrors `Circumstance`'s atomic intention `AI`, atomic event `AE` and
//! `atomicIntSuspended`, as `TransitionSystem` uses them.
//!
//! * An intention is atomic while some plan on its stack is (`Intention.isAtomic`: `push`
//!   and `pop` count its atomic intended means). Going back to the queue
//!   (`Circumstance.addRunningIntention`, by `removeActionReQueue`, `applyAddIM` or a
//!   resumption), an atomic intention becomes `AI` instead: here the first of
//!   [`State::intentions`], with [`State::atomic`] set.
//! * While `AI` is set, no event is selected (`applySelEv`), and the act phase takes it
//!   first (`applySelInt`: `removeAtomicIntention`, which clears `AI`). The step it runs
//!   puts it back in `AI` (`removeActionReQueue`) before `applyClrInt` pops its finished
//!   plans, so when an atomic plan ends above one that is not atomic, `AI` holds the
//!   intention one cycle more: no event is selected in the next cycle, and it runs first.
//! * An event carrying an atomic intention (`Event.isAtomic`: its subgoal, its belief
//!   update with the intention's focus, its failure) is `AE`, not queued
//!   (`Circumstance.addEvent`): selected before any other (`applySelEv`:
//!   `removeAtomicEvent`), here the first of [`State::events`].
//! * An atomic intention that waits for its action's feedback (`addPendingAction`), in
//!   `.wait` or for an answer (`addPendingIntention`) stays `AI`, suspended: no event is
//!   selected, and no other intention runs (`applySelInt`: `isAtomicIntentionSuspended`),
//!   until it comes back (`removePendingAction`, `removePendingIntention`). An agent whose
//!   atomic intention sleeps in `.wait` does nothing else (`canSleep`, its atomic case),
//!   though it still perceives and reads its mail.
//! * When its action fails, the failure event is `AE` and `AI` is cleared
//!   (`applyProcAct`: `removeAtomicIntention` after `generateGoalDeletion`), so in that
//!   cycle another intention may run.
//!
//! `!!g` in an atomic plan is an external event: queued, and selected only once the atomic
//! intention is done. Refused, at the step where Jason leaves `AI` naming an intention
//! that is also in a failure event (or dropped), so that it runs on from `AI` as well: a
//! timeout of `.wait` for an event or a condition, an ask's answer that does not unify
//! with the `.send`'s fourth argument, and `.fail_goal` of the atomic intention's own goal
//! when a failure plan takes it and it stays atomic.

use super::cycle::{Note, Semantics};
use super::state::{Event, Intention, State};
use crate::syntax::Span;

impl Semantics<'_> {
    /// Jason's `Intention.isAtomic`: some plan on its stack is atomic.
    pub fn is_atomic(&self, int: &Intention) -> bool {
        int.frames.iter().any(|f| self.plan(f.plan).atomic)
    }

    /// `Circumstance.addRunningIntention`: an atomic intention becomes `AI`, first of the
    /// queue; any other goes to the back.
    pub(super) fn add_running(&self, s: &mut State, int: Intention) {
        let atomic = self.is_atomic(&int);
        self.requeue(s, int, atomic);
    }

    /// [`Semantics::add_running`] of an intention that went back to the queue when it was
    /// `atomic` (`removeActionReQueue`), and whose finished plans were popped since
    /// (`applyClrInt`): it is `AI` even when it is atomic no more.
    pub(super) fn requeue(&self, s: &mut State, int: Intention, atomic: bool) {
        if atomic {
            debug_assert!(!s.atomic, "one atomic intention at a time");
            s.intentions.insert(0, int);
            s.atomic = true;
        } else {
            s.intentions.push(int);
        }
    }

    /// `Circumstance.hasAtomicIntention`: `AI` is set, running or suspended. No event is
    /// selected then (`applySelEv`).
    pub(super) fn has_atomic_intention(&self, s: &State) -> bool {
        s.atomic || self.atomic_suspended(s)
    }

    /// `Circumstance.isAtomicIntentionSuspended`: the atomic intention waits for its
    /// action's feedback, in `.wait` or for an answer. No other intention runs then
    /// (`applySelInt`).
    pub(super) fn atomic_suspended(&self, s: &State) -> bool {
        s.pending
            .as_ref()
            .is_some_and(|p| self.is_atomic(&p.intention))
            || s.waiting.iter().any(|w| self.is_atomic(&w.intention))
    }

    /// Whether the agent's atomic intention sleeps: it is in `.wait` (or waits for an
    /// answer) and nothing it waits for has come. Then the agent does nothing but perceive,
    /// read its mail and let its timers fire (`TransitionSystem.canSleep`, its atomic case):
    /// its events and other intentions wait.
    pub fn atomic_sleeps(&self, s: &State) -> bool {
        s.pending.is_none()
            && s.waiting
                .iter()
                .any(|w| !w.woken && self.is_atomic(&w.intention))
    }

    /// Queues an event (`Circumstance.addEvent`): one whose intention is atomic is `AE`,
    /// selected before the others, so it goes first.
    pub(super) fn queue_event(&self, s: &mut State, ev: Event) {
        if ev.intention.as_ref().is_some_and(|i| self.is_atomic(i)) {
            debug_assert!(
                !s.events
                    .iter()
                    .any(|e| e.intention.as_ref().is_some_and(|i| self.is_atomic(i))),
                "one atomic event at a time"
            );
            s.events.insert(0, ev);
        } else {
            s.events.push(ev);
        }
    }

    /// A step Jason runs so that `AI` goes on naming an atomic intention that is also in a
    /// failure event (or was dropped): refused, the run leaves the model here.
    pub(super) fn atomic_beyond(&self, plan: u32, span: Span, what: &str) -> Note {
        Note::Beyond {
            text: self.project.map.slice(span).trim().to_string(),
            plan,
            span,
            reason: format!(
                "{what} in an atomic intention: Jason 3 leaves it its atomic intention (Circumstance.AI) while it fails, so it runs on from there as well, and bdi-check does not model that"
            ),
        }
    }
}
