//! The agent's state in the transition system: beliefs, the event queue, the intentions,
//! and which requests the user has made.

use crate::model::atoms::{AtomId, AtomSet};
use crate::model::term::Term;
use crate::model::Substitution;
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::Span;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// A triggering event's content: `+!g`, `-!g`, `+b`, `-b`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EventTrigger {
    /// `+` or `-`.
    pub op: TriggerOp,
    /// Belief, achievement or test goal.
    pub kind: TriggerKind,
    /// The ground (or partly bound) literal.
    pub literal: Term,
}

impl fmt::Display for EventTrigger {
    /// Jason's text of the trigger, without the `source(self)` every goal of the agent's
    /// own carries (other annotations are shown).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (op, kind) = (self.op.symbol(), self.kind.symbol());
        let own = Term::structure("source", vec![Term::atom("self")]);
        if self.literal.annots().contains(&own) {
            let rest: Vec<Term> = self
                .literal
                .annots()
                .iter()
                .filter(|a| **a != own)
                .cloned()
                .collect();
            let shown = self.literal.without_annots().add_annots(rest);
            if let Some(shown) = shown {
                return write!(f, "{op}{kind}{shown}");
            }
        }
        write!(f, "{op}{kind}{}", self.literal)
    }
}

/// An event in the queue. An internal event (a subgoal, a failure) carries the intention
/// that waits for it, suspended until a plan is chosen for the event.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Event {
    /// What happened.
    pub trigger: EventTrigger,
    /// The suspended intention, for internal events.
    pub intention: Option<Intention>,
    /// Where an external event came from (for internal ones, their intention's origin).
    pub origin: Origin,
    /// For a subgoal, the plan and `!g` step that posted it (failures are reported there).
    pub posted_at: Option<(u32, Span)>,
}

/// Where an intention came from; names intentions in traces and ties them to requests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Origin {
    /// The user's request with this index.
    Request(u8),
    /// The agent's initial goal with this index.
    InitialGoal(u8),
    /// `!!g` or a belief event handled by a plan.
    Spawned,
}

/// A position in a body: the block being executed and the next step in it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Cursor {
    /// The block (0 = the plan's body; then the bodies of `if`/`while`/`for`).
    pub block: u16,
    /// The next step in it.
    pub pos: u16,
    /// How the block ends.
    pub kind: CursorKind,
}

/// What happens at the end of a block.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum CursorKind {
    /// The block ends; the enclosing one goes on.
    Seq,
    /// A `while` body: the condition (the step at `at` in the enclosing block) is tested
    /// again.
    While {
        /// The block holding the `while` step.
        outer: u16,
        /// The `while` step's position there.
        at: u16,
        /// The bindings when the loop first ran, restored before each test (Jason's
        /// stdlib `loop` keeps them as its backup unifier).
        base: Substitution,
    },
    /// A `for` body: the next answer, with the bindings from before the loop.
    For {
        /// The answers not used yet, next first.
        rest: Vec<Substitution>,
        /// The bindings before the loop, restored after it.
        base: Substitution,
    },
}

/// One plan instance on an intention stack: Jason's intended means.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Frame {
    /// The plan's index in the library.
    pub plan: u32,
    /// The bindings of the plan's variables.
    pub subst: Substitution,
    /// Nested positions in the body, innermost last; empty when the body is done.
    pub cursors: Vec<Cursor>,
    /// The instantiated trigger the plan was chosen for.
    pub trigger: EventTrigger,
    /// The goal of the `!g` step this plan is executing, while it waits for `g`: Jason's
    /// current step of a plan below the top. `None` when its current step is another one
    /// (the step that failed, when a failure plan runs above it: Jason keeps the failed
    /// plan on the stack).
    pub calling: Option<Term>,
}

/// A stack of frames: the top frame runs, the ones below wait for its goal.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Intention {
    /// Bottom first.
    pub frames: Vec<Frame>,
    /// Where it came from.
    pub origin: Origin,
}

impl Intention {
    /// The literals of its achievement goals, bottom first: what `.intend` and `.desire`
    /// see of it (`Intention.hasTrigger` with `+!g`).
    pub fn goals(&self) -> impl Iterator<Item = &Term> {
        self.frames
            .iter()
            .filter(|f| f.trigger.op == TriggerOp::Add && f.trigger.kind == TriggerKind::Achieve)
            .map(|f| &f.trigger.literal)
    }
}

/// An intention whose environment action waits for its feedback: Jason's pending action
/// (`Circumstance.PA`). It returns to the queue, or fails, in the next cycle's `ProcAct`,
/// after that cycle's deliberation.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Pending {
    /// The intention, its action's step done.
    pub intention: Intention,
    /// When the action failed: why, and where.
    pub failure: Option<ActionFailure>,
}

/// Why an environment action failed.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ActionFailure {
    /// The plan of the step.
    pub plan: u32,
    /// The step.
    pub span: Span,
    /// The action, as it was sent.
    pub action: Term,
    /// Why it failed (`its precondition does not hold`), naming no object.
    pub why: String,
}

/// An intention suspended by `.wait`: Jason's pending intention (`Circumstance.PI`), with
/// the `WaitEvent` listener that resumes it (stdlib `wait`); or by `.send` of `askOne` or
/// `askAll` with an answer variable, until the answer comes (stdlib `send`, resumed by
/// `TransitionSystem.resumeSyncAskIntention`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Waiting {
    /// The intention, its top plan past the `.wait` (or `.send`) step.
    pub intention: Intention,
    /// The `.wait` (or `.send`) step: its plan, block and position, and where it is written.
    pub step: (u32, u16, u16, Span),
    /// For an ask: its id (`samidN`, the answer's `in_reply_to`) and the term the answer
    /// is unified with (the `.send`'s fourth argument, as the step ran).
    pub ask: Option<(u8, Term)>,
    /// Whether a timer runs (a timeout of at least 0 ms): it may end the wait at the start
    /// of any later cycle.
    pub timed: bool,
    /// The event or condition waited for has come: the intention resumes at the start of
    /// the next cycle (`runAtBeginOfNextCycle`).
    pub woken: bool,
}

/// A plan in the library of an agent that adds or removes plans: its index, and the sources
/// its label carries (bit `i`: [`crate::model::library::LibraryChanges::sources`]`[i]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct InLibrary {
    /// The plan.
    pub plan: u32,
    /// Its sources (never none: a plan with no source left is removed).
    pub sources: u64,
}

/// A belief other agents told (Jason: `b[source(a)]`, by a `tell` message): who told it
/// (bit `k`: the agent of index `k`), and whether the agent also believes it of its own
/// (`source(self)`). Beliefs with no such entry have their one usual source.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Told {
    /// The belief.
    pub atom: AtomId,
    /// The agents that told it, one bit each (never none).
    pub from: u64,
    /// Whether it is also the agent's own.
    pub own: bool,
}

/// The whole agent state.
///
/// Its hash is built from the hashes of its parts ([`part_hash`] of the beliefs, of each
/// event and of each intention), so that a representation that keeps those parts shared
/// and their hashes cached (the compiled search's) fingerprints a state exactly as this one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct State {
    /// Beliefs: the environment's atoms as perceived (exactly) and the mental notes.
    pub beliefs: AtomSet,
    /// Jason's belief-base order where it can matter: the believed atoms of the
    /// predicates some query asks with variables ([`super::Semantics::is_ordered`]),
    /// grouped by predicate (in predicate order), newest first in each group, as
    /// `DefaultBeliefBase` keeps a predicate's beliefs (each added one goes in front).
    pub order: Vec<AtomId>,
    /// Pending events, first in first out.
    pub events: Vec<Event>,
    /// Running intentions, in round-robin order: the first runs next.
    pub intentions: Vec<Intention>,
    /// The intention whose action awaits its feedback, if any.
    pub pending: Option<Pending>,
    /// Intentions suspended by `.wait`: the woken ones first, in the order they were woken
    /// (their resumptions are queued in that order), then the others, oldest first.
    pub waiting: Vec<Waiting>,
    /// Bit `i`: request `i` has been made in this run.
    pub requested: u64,
    /// The plan library in Jason's order, when steps have made it differ from the agent's
    /// own plans (`None`: those, in source order, as loaded).
    pub library: Option<Arc<[InLibrary]>>,
    /// The beliefs other agents told, by atom (empty outside a system of several agents).
    pub told: Vec<Told>,
    /// The ids of the agent's asks that wait for an answer, one bit each (`samidN`): set
    /// when the ask is sent, cleared when its answer is read, whether an intention still
    /// waits for it or not (Jason ignores an answer that comes after the timeout), so no
    /// id is used again while an answer to it may come.
    pub asked: u64,
    /// Jason's `Circumstance.AI` holds a running intention, `intentions[0]`: one with an
    /// atomic plan went back to the queue (`addRunningIntention`). Cleared when the act
    /// phase selects it (`removeAtomicIntention`); while set, no event is selected. It
    /// outlives the atomic plan by one cycle when that plan ends above a plan that is not
    /// atomic (`applyClrInt` pops the plan after the intention went back to `AI`). An
    /// atomic intention that waits for its action's feedback, in `.wait` or for an answer
    /// is Jason's suspended `AI` (`atomicIntSuspended`): it is in [`State::pending`] or
    /// [`State::waiting`], and this is not set (see `src/semantics/atomic.rs`).
    pub atomic: bool,
}

/// The hash of one part of a state, and a state's fingerprint: foldhash's quality variant
/// (foldhash is hashbrown's default hasher; this variant passes the SMHasher3 suite
/// without failures, as SipHash-1-3 does) with a fixed seed, so it is the same in every
/// run and process. std's SipHash was a tenth of the instructions of a search (the
/// fingerprint, and the parts interned, per successor); this costs about a third of it,
/// and spreads non-adversarial inputs as uniformly, which is what the collision
/// probability printed with the statistics assumes.
pub fn part_hash<T: Hash>(x: &T) -> u64 {
    use std::hash::BuildHasher;
    foldhash::quality::FixedState::with_seed(0x6264_692d_6368_6563).hash_one(x)
}

/// Feeds a state's part hashes to `h`: the one definition of a state's hash, whatever holds
/// the parts.
#[allow(clippy::too_many_arguments)]
pub fn hash_parts<H: Hasher>(
    h: &mut H,
    beliefs: u64,
    events: impl ExactSizeIterator<Item = u64>,
    intentions: impl ExactSizeIterator<Item = u64>,
    pending: Option<u64>,
    waiting: impl ExactSizeIterator<Item = u64>,
    requested: u64,
    library: Option<u64>,
    told: Option<u64>,
    atomic: bool,
) {
    h.write_u64(beliefs);
    h.write_usize(events.len());
    events.for_each(|e| h.write_u64(e));
    h.write_usize(intentions.len());
    intentions.for_each(|i| h.write_u64(i));
    if let Some(p) = pending {
        h.write_u64(p);
    }
    // Only agents that wait have waiting intentions: other states hash as they always did.
    if waiting.len() > 0 {
        h.write_usize(waiting.len());
        waiting.for_each(|w| h.write_u64(w));
    }
    h.write_u64(requested);
    // Only for agents that change their library: every other state hashes as before.
    if let Some(l) = library {
        h.write_u64(l);
    }
    // Only agents told something by others, or asking: every other state hashes as before.
    if let Some(t) = told {
        h.write_u64(t);
    }
    // Only agents with atomic plans, while one runs: every other state hashes as before.
    if atomic {
        h.write_u8(1);
    }
}

impl Hash for State {
    fn hash<H: Hasher>(&self, h: &mut H) {
        hash_parts(
            h,
            part_hash(&(&self.beliefs, &self.order)),
            self.events.iter().map(part_hash),
            self.intentions.iter().map(part_hash),
            self.pending.as_ref().map(part_hash),
            self.waiting.iter().map(part_hash),
            self.requested,
            self.library.as_ref().map(part_hash),
            match (self.told.is_empty(), self.asked) {
                (true, 0) => None,
                (false, 0) => Some(part_hash(&self.told)),
                (_, asked) => Some(part_hash(&(&self.told, asked))),
            },
            self.atomic,
        );
    }
}

impl State {
    /// What other agents told of atom `a`, if anything.
    pub fn told(&self, a: AtomId) -> Option<&Told> {
        self.told
            .binary_search_by_key(&a, |t| t.atom)
            .ok()
            .map(|i| &self.told[i])
    }

    /// Whether the agent has nothing to do: no event, no intention (suspended ones wait
    /// inside events, or for the end of a `.wait` or for an answer).
    pub fn is_idle(&self) -> bool {
        self.events.is_empty()
            && self.intentions.is_empty()
            && self.pending.is_none()
            && self.waiting.is_empty()
    }

    /// Every intention, running, waiting (for an action's feedback or in `.wait`) or
    /// suspended in an event.
    pub fn all_intentions(&self) -> impl Iterator<Item = &Intention> {
        self.intentions
            .iter()
            .chain(self.pending.iter().map(|p| &p.intention))
            .chain(self.waiting.iter().map(|w| &w.intention))
            .chain(self.events.iter().filter_map(|e| e.intention.as_ref()))
    }

    /// The requests still being served: the origin of some intention or event.
    pub fn pending_requests(&self) -> u64 {
        requests_of(
            self.intentions
                .iter()
                .chain(self.pending.iter().map(|p| &p.intention))
                .chain(self.waiting.iter().map(|w| &w.intention)),
            &self.events,
        )
    }
}

/// The requests that some intention or event serves, one bit each.
pub fn requests_of<'a>(
    intentions: impl IntoIterator<Item = &'a Intention>,
    events: impl IntoIterator<Item = &'a Event>,
) -> u64 {
    let origins = intentions
        .into_iter()
        .map(|i| i.origin)
        .chain(events.into_iter().map(|e| e.origin));
    origins.fold(0, |bits, o| match o {
        Origin::Request(r) => bits | 1 << r,
        _ => bits,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trigger(op: TriggerOp, kind: TriggerKind, annots: &[Term]) -> EventTrigger {
        EventTrigger {
            op,
            kind,
            literal: Term::literal("g", false, vec![Term::atom("a")], annots.to_vec()),
        }
    }

    #[test]
    fn a_trigger_shows_as_jason_writes_it_without_its_own_source() {
        let own = Term::structure("source", vec![Term::atom("self")]);
        let boss = Term::structure("source", vec![Term::atom("boss")]);
        let urgent = Term::atom("urgent");
        let show = |op, kind, annots: &[Term]| trigger(op, kind, annots).to_string();
        use TriggerKind::{Achieve, Belief, Test};
        use TriggerOp::{Add, Del};
        assert_eq!(show(Add, Achieve, std::slice::from_ref(&own)), "+!g(a)");
        assert_eq!(
            show(Del, Achieve, &[urgent.clone(), own.clone()]),
            "-!g(a)[urgent]"
        );
        assert_eq!(
            show(Add, Test, std::slice::from_ref(&boss)),
            "+?g(a)[source(boss)]"
        );
        assert_eq!(show(Add, Belief, &[]), "+g(a)");
        assert_eq!(show(Del, Belief, &[boss, own]), "-g(a)[source(boss)]");
    }

    fn intention(origin: Origin) -> Intention {
        Intention {
            frames: Vec::new(),
            origin,
        }
    }

    #[test]
    fn the_requests_served_are_the_origins_of_intentions_and_events() {
        let ints = [
            intention(Origin::Request(0)),
            intention(Origin::Spawned),
            intention(Origin::Request(3)),
        ];
        let events = [Event {
            trigger: trigger(TriggerOp::Add, TriggerKind::Achieve, &[]),
            intention: None,
            origin: Origin::Request(5),
            posted_at: None,
        }];
        assert_eq!(requests_of(&ints, &events), 0b10_1001);
        assert_eq!(requests_of(&ints[1..2], &[]), 0);
        assert_eq!(requests_of(&[], &events), 1 << 5);
        // A request served twice (its intention and a subgoal's event) is one bit.
        let twice = [intention(Origin::Request(5)), intention(Origin::Request(5))];
        assert_eq!(requests_of(&twice, &[]), 1 << 5);
        assert_eq!(requests_of(&twice, &events), 1 << 5);
        // A state's: its intentions, the one awaiting feedback and its events.
        let state = State {
            beliefs: AtomSet::empty(0),
            order: Vec::new(),
            events: events.to_vec(),
            intentions: vec![intention(Origin::Request(1))],
            pending: Some(Pending {
                intention: intention(Origin::Request(2)),
                failure: None,
            }),
            waiting: Vec::new(),
            requested: 0,
            library: None,
            told: Vec::new(),
            asked: 0,
            atomic: false,
        };
        assert_eq!(state.pending_requests(), 0b10_0110);
    }
}
