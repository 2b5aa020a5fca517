//! `.wait`: an intention suspended until an event, a condition or a timeout. Mirrors the
//! stdlib's `wait` (`execute` and its `WaitEvent` listener) and the tasks Jason runs at
//! the beginning of the next cycle's deliberation (`TransitionSystem.runAtBeginOfNextCycle`,
//! run first in `deliberate()`).
//!
//! The model has no clock. A timer (`.wait(N)`, or the timeout of an event or condition
//! wait, when it is at least 0) may end its wait at the start of any later cycle: each
//! cycle branches over which running timers fired before it, and in which order (the
//! order their resumptions are queued). This contains every run real time allows, and
//! more: the durations are not compared, so `.wait(10)` may end after `.wait(1000)`
//! begun at the same time. When nothing else can happen, a cycle in which no timer fires
//! is not a step (the agent sleeps). A scenario run (`check::run`) takes the cycle in
//! which no timer fires whenever there is one, as Jason does when its cycles take far
//! less time than the waits.
//!
//! An event wait is woken by every event the agent adds (`Circumstance.addEvent` calls the
//! listener), relevant or not, whose trigger unifies with the one waited for; its
//! bindings are the plan's from then on. A condition wait is tested at each event added,
//! on the beliefs of that moment (`testResumeCondition`). A woken intention resumes at the
//! start of the next cycle, after the step; when its timer fires first, an event or
//! condition wait fails (`wait_timeout`), a timed one goes on.

use super::cycle::{Note, Semantics};
use super::state::{Event, EventTrigger, Intention, State, Waiting};
use crate::model::atoms::AtomId;
use crate::model::plans::BodyStep;
use crate::model::unify;
use crate::syntax::ast::TriggerOp;

/// Most timers that may fire before one cycle, in one branch: the orders of `k` timers
/// grow as `k!`.
const MAX_FIRED: usize = 3;

impl Semantics<'_> {
    /// Queues an event the agent adds, and tells the waiting intentions of it.
    pub(super) fn post_event(&self, s: &mut State, ev: Event) {
        self.event_added(s, &ev.trigger);
        self.queue_event(s, ev);
    }

    /// `WaitEvent.eventAdded` for every waiting intention not woken yet: an event wait
    /// whose trigger unifies with `trigger` is woken with its bindings, and every
    /// condition wait is tested on the current beliefs.
    pub(super) fn event_added(&self, s: &mut State, trigger: &EventTrigger) {
        if s.waiting.iter().all(|w| w.woken) {
            return;
        }
        let mut i = 0;
        while i < s.waiting.len() {
            // An ask waits for its answer, not for an event.
            if s.waiting[i].woken || s.waiting[i].ask.is_some() {
                i += 1;
                continue;
            }
            let (plan, block, pos, _) = s.waiting[i].step;
            let BodyStep::Wait {
                event, condition, ..
            } = &self.block(plan, block)[pos as usize].kind
            else {
                unreachable!("a waiting intention waits at a `.wait` step");
            };
            let subst = &s.waiting[i].intention.frames.last().expect("a frame").subst;
            let answer = match (event, condition) {
                (Some(te), _) if te.op == trigger.op && te.kind == trigger.kind => {
                    let mut u = subst.clone();
                    unify(&te.literal, &trigger.literal, &mut u).then_some(u)
                }
                (None, Some(cond)) => self.beliefs(s).answers(cond, subst).into_iter().next(),
                _ => None,
            };
            if let Some(u) = answer {
                let mut w = s.waiting.remove(i);
                w.woken = true;
                if let Some(top) = w.intention.frames.last_mut() {
                    top.subst = u;
                }
                // Woken ones come first, in the order they were woken.
                let at = s.waiting.iter().take_while(|w| w.woken).count();
                s.waiting.insert(at, w);
            }
            i += 1;
        }
    }

    /// The belief events of a belief update, told to the waiting intentions on the
    /// beliefs of each moment (Jason adds each event right after its belief changes).
    pub(super) fn belief_events_added(&self, s: &mut State, triggers: &[(EventTrigger, AtomId)]) {
        if s.waiting.iter().all(|w| w.woken) {
            return;
        }
        let end = s.beliefs.clone();
        // Back to the beliefs before the update, then forward one change at a time.
        for (t, a) in triggers {
            match t.op {
                TriggerOp::Add => s.beliefs.remove(*a),
                _ => s.beliefs.insert(*a),
            }
        }
        for (t, a) in triggers {
            match t.op {
                TriggerOp::Add => s.beliefs.insert(*a),
                _ => s.beliefs.remove(*a),
            }
            self.event_added(s, t);
        }
        debug_assert!(s.beliefs == end);
        s.beliefs = end;
    }

    /// The `.wait` step: the intention is suspended, unless it waits for a condition that
    /// holds already (then it goes on with the condition's answer, stdlib `wait.execute`).
    /// Returns the intention when it goes on.
    pub(super) fn suspend(
        &self,
        s: &mut State,
        mut int: Intention,
        step: (u32, u16, u16, crate::syntax::Span),
        timed: bool,
    ) -> Option<Intention> {
        let (plan, block, pos, _) = step;
        if let BodyStep::Wait {
            condition: Some(cond),
            ..
        } = &self.block(plan, block)[pos as usize].kind
        {
            let top = int.frames.last_mut().expect("a frame");
            if let Some(u) = self.beliefs(s).answers(cond, &top.subst).into_iter().next() {
                top.subst = u;
                return Some(int);
            }
        }
        s.waiting.push(Waiting {
            intention: int,
            step,
            ask: None,
            timed,
            woken: false,
        });
        None
    }

    /// Which timers may fire before the next cycle: every sequence of at most
    /// [`MAX_FIRED`] distinct running timers (indices into [`State::waiting`]), the empty
    /// one first. The empty one is left out when nothing else could happen in the cycle:
    /// the events and intentions of an agent whose atomic intention sleeps in `.wait` wait
    /// too, and only what it `sensed` (among several agents) makes the cycle a step.
    pub(super) fn timer_choices(&self, s: &State, sensed: bool) -> Vec<Vec<usize>> {
        let timers: Vec<usize> = (0..s.waiting.len())
            .filter(|&i| s.waiting[i].timed && !s.waiting[i].woken)
            .collect();
        let busy = if self.atomic_sleeps(s) {
            sensed || s.waiting.iter().any(|w| w.woken)
        } else {
            !s.events.is_empty()
                || !s.intentions.is_empty()
                || s.pending.is_some()
                || s.waiting.iter().any(|w| w.woken)
        };
        let mut out = Vec::new();
        if busy {
            out.push(Vec::new());
        }
        fn grow(timers: &[usize], seq: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
            for &t in timers {
                if seq.contains(&t) {
                    continue;
                }
                seq.push(t);
                out.push(seq.clone());
                if seq.len() < MAX_FIRED {
                    grow(timers, seq, out);
                }
                seq.pop();
            }
        }
        grow(&timers, &mut Vec::new(), &mut out);
        out
    }

    /// The tasks of the beginning of a cycle: the woken intentions resume, then those
    /// whose timers fired (`fired`, in firing order), each as its `WaitEvent.resume` does.
    pub(super) fn resume_waiting(&self, s: &mut State, fired: &[usize], notes: &mut Vec<Note>) {
        if s.waiting.is_empty() {
            return;
        }
        let woken = s.waiting.iter().take_while(|w| w.woken).count();
        let order: Vec<usize> = (0..woken).chain(fired.iter().copied()).collect();
        let mut all: Vec<Option<Waiting>> = std::mem::take(&mut s.waiting)
            .into_iter()
            .map(Some)
            .collect();
        for i in order {
            let w = all[i].take().expect("each waiting intention resumes once");
            if w.ask.is_some() {
                self.ask_timed_out(s, w, notes);
                continue;
            }
            let (plan, block, pos, span) = w.step;
            let BodyStep::Wait {
                event, condition, ..
            } = &self.block(plan, block)[pos as usize].kind
            else {
                unreachable!("a waiting intention waits at a `.wait` step");
            };
            let waits_for_something = event.is_some() || condition.is_some();
            let text = format!(
                "{} {}",
                self.project.map.slice(span).trim(),
                match (w.woken, waits_for_something) {
                    (true, _) => "ends: what it waited for came",
                    (false, false) => "ends: its time is up",
                    (false, true) => "times out",
                }
            );
            notes.push(Note::Internal {
                text: text.clone(),
                plan,
                origin: w.intention.origin,
            });
            let mut int = w.intention;
            let atomic = self.is_atomic(&int);
            if !w.woken && waits_for_something && atomic {
                // `WaitEvent.resume` fails it without clearing `AI` (as `applyProcAct`
                // does after a failed action): refused.
                notes.push(self.atomic_beyond(plan, span, "a `.wait` that times out"));
            } else if !w.woken && waits_for_something {
                // `generateGoalDeletion` with `wait_timeout`: the plan fails at its step.
                let failed = int.frames.last().map(|f| f.trigger.clone()).expect("frame");
                self.fail_intention(
                    s,
                    int,
                    &failed,
                    Some((plan, span)),
                    &format!("{text}: nothing it waited for came"),
                    ("wait_timeout", &[]),
                    notes,
                );
            } else if self.clear_finished(&mut int, notes) {
                // `resumeIntention`: back in the queue, the `.wait` step done (`AI` for an
                // atomic intention, see `atomic.rs`).
                self.requeue(s, int, atomic);
            }
        }
        s.waiting = all.into_iter().flatten().collect();
    }
}
