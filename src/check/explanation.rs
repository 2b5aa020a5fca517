//! The explanation properties of SPEC §4, checked on every run for every user.
//!
//! A user's expected successors `N` change along a run, so they are part of the state: the
//! model explored here is the agent's reasoning cycle paired with one user's view of it
//! ([`Explained`]): `N` as Algorithm 1 updates it on the observed sequence, the last
//! observation, `N` and the marks of Algorithm 1 as the paper wrote it (at plan adoption),
//! and the explanations whose content is still to be judged against what the run really
//! does. Each property is then a check on transitions:
//!
//! * `demand-exact`: Algorithm 1's answer at an action equals the declarative one (the pair
//!   matches nothing in `N`, compared pair by pair), and `N` grows by exactly that pair;
//! * `demand-adoption`: the paper's Algorithm 1 — marking, when a plan is adopted, each
//!   action of its body whose pair with the one before is not in `N`, the first action paired
//!   with what the user saw last — marks exactly the actions the observed sequence flags.
//!   Only the body's own sequence of steps (block 0) is marked: actions inside `if`, `while`
//!   and `for` are not known at adoption;
//! * `content-truthful`: every literal of `Γ` is believed when the explanation is given;
//! * `content-covers` and `content-concise`: after the explanation, the run is followed until
//!   the truth of some literal of `Γ` changes. The step of the explained action's plan body
//!   that was running then (an action, or a subgoal whose sub-intention made the change) is
//!   the one the content must end at: `covers` fails when the content ends before it,
//!   `concise` when it ends after it. When the body ends and nothing changed, the content
//!   must run to the body's last step. A run in which the intention fails first decides
//!   nothing;
//! * with `emitted_by`, `demand-conformance` and `content-conformance`: the agent's own
//!   explanation action, executed before an environment action, must come exactly when
//!   Algorithm 1 says one is due, and carry the reference content.
//!
//! The runs are those of one agent ([`Alone`]) or every interleaving of several agents'
//! reasoning cycles ([`Among`]), one of which is the robot the users watch (`[explanation]
//! robot`): the same checks on either ([`Runs`]). Among several agents, a user sees the
//! robot's steps only: the requests that go to it and its actions, never another agent's
//! (so that the robot itself can know what the user saw, as `emitted_by` needs). Content
//! is about the robot's intentions and is judged on its beliefs, which change only in its
//! own cycles: an action's effects, and whatever other agents changed, come at the sense
//! that begins the robot's next cycle, and count for the step of the robot's body that was
//! running then (its intentions as they were before that cycle).
//!
//! One agent whose library is local runs on its compiled cycle ([`AloneCompiled`]), with
//! the tables the agent's own search filled. The user's view is interned and hashed once,
//! and what a transition's notes make of a view is computed once per view, notes (shared
//! by the compiled cycle) and beliefs, where it reads them: most transitions of a user's
//! search repeat one met on another state of the agent. When the agent's own search was
//! exact and complete, it kept its graph ([`Stored`]: every state, and a number for the
//! notes of each transition), and the users' searches read it ([`AloneStored`]) instead of
//! running the cycle again: a state of a user's search then costs less than a state of
//! the agent's (`docs/benchmarks.md`).

use super::chunked::{prefetch, Chunked, Narrow};
use super::explore::{explore_with, fingerprint, Graph, Limits, Options, Walk};
use super::model::{AgentState, CycleNotes, Model};
use super::recent::{recently, Recently};
use super::store::{pair_fingerprint, OutOfMemory};
use super::symmetry::{Renaming, Symmetry};
use super::trace::Builder;
use crate::explain::agent::{Explainer, Explanation, User};
use crate::explain::{Content, ContextLiteral, ExpectedSuccessors, Observation, Pair, PlanStep};
use crate::findings::{Counterexample, Finding, Phase, Status, StepKindTag, TraceStep};
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::plans::BodyStep;
use crate::model::project::Project;
use crate::model::term::Term;
use crate::semantics::compiled::{mix, Base, Part, Quick, ShortWords, Words};
use crate::semantics::{
    Compiled, Intention, Note, Notes, Origin, Packed, Semantics, State, System, SystemState,
};
use crate::syntax::{Diagnostic, Severity, Span};
use smallvec::SmallVec;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Debug;
use std::hash::Hash;
use std::marker::PhantomData;
use std::sync::{Arc, Mutex, MutexGuard};

/// Every explanation property, in report order.
pub const CHECKS: [&str; 7] = [
    "demand-exact",
    "demand-adoption",
    "content-covers",
    "content-concise",
    "content-truthful",
    "demand-conformance",
    "content-conformance",
];

/// The runs a user watches: the transitions of one agent's reasoning cycle, or of several
/// agents', one of which (the robot) is the agent the user watches.
pub trait Runs: Sync {
    /// A state of the runs.
    type State: Clone + Debug + Hash + Eq + Send + Sync;

    /// What a transition did: the notes of the agent that moved.
    type Notes: CycleNotes + Clone + Debug + Default + Send;

    /// Every agent's reasoning cycle, by index (one agent alone).
    fn agents(&self) -> &[Semantics<'_>];

    /// The robot's index among [`Runs::agents`].
    fn robot(&self) -> usize;

    /// The agents' names when there are several (the steps of a run then name their
    /// agent), `None` for one agent.
    fn names(&self) -> Option<&[String]>;

    /// The robot's beliefs in `s`.
    fn robot_beliefs<'s>(&self, s: &'s Self::State) -> &'s AtomSet;

    /// Every intention of the robot in `s` (see [`State::all_intentions`]).
    fn robot_intentions<'s>(&self, s: &'s Self::State) -> impl Iterator<Item = &'s Intention>;

    /// The environment in `s` (a run's initial state, as a counterexample lists it).
    fn world<'s>(&self, s: &'s Self::State) -> &'s AtomSet;

    /// Every initial state.
    fn initial(&self) -> Box<dyn Iterator<Item = Self::State> + '_>;

    /// Whether [`Runs::initial`] gives every initial state (among several agents, at most
    /// the project's bound of them are held).
    fn initial_complete(&self) -> bool {
        true
    }

    /// Every successor of `s`, in a fixed order: the agent that moved (for a request, the
    /// agent it goes to), what it did, and the state after.
    fn successors(&self, s: &Self::State) -> Vec<(u8, Self::Notes, Self::State)>;

    /// [`Runs::successors`], each handed to `f` in order: runs that can give them without
    /// a vector spare a user's search one per state.
    fn each_successor(&self, s: &Self::State, mut f: impl FnMut(u8, Self::Notes, Self::State)) {
        for (agent, notes, next) in self.successors(s) {
            f(agent, notes, next);
        }
    }

    /// The robot's beliefs after the sense that begins its next cycle in `s`, when that
    /// sense perceives or reads something. Among several agents the robot perceives the
    /// environment only there (its own actions' effects too); one agent alone perceives
    /// an action's effects as it acts: `None`.
    fn sensed(&self, _s: &Self::State) -> Option<AtomSet> {
        None
    }

    /// Whether the robot's next cycle in `s` begins by perceiving or reading something
    /// (what [`Runs::sensed`] gives then, and only then): its beliefs are about to change.
    fn to_sense(&self, _s: &Self::State) -> bool {
        false
    }

    /// An identity of `notes` (equal for notes that are the same shared values), when the
    /// runs share them: a user's view then moves through each such transition once.
    fn notes_key(&self, _notes: &Self::Notes) -> Option<SmallVec<[usize; 4]>> {
        None
    }

    /// Whether the user sees any of `notes` (a request, a plan adopted, an action, a
    /// failure), when the runs know it without reading them.
    fn shown(&self, _notes: &Self::Notes) -> Option<bool> {
        None
    }

    /// An identity of the robot's beliefs in `s` (with [`Runs::notes_key`]).
    fn beliefs_key(&self, _s: &Self::State) -> usize {
        0
    }

    /// An identity of the robot's intentions in `s` (see [`State::all_intentions`]), when
    /// the runs share them as [`Runs::notes_key`] shares notes.
    fn intentions_key(&self, _s: &Self::State) -> Option<SmallVec<[usize; 8]>> {
        None
    }

    /// Asks the processor to bring in what the successors of `s` will read
    /// ([`Model::prefetch`]).
    fn prefetch(&self, _s: &Self::State, _stage: usize) {}

    /// Without symmetry reduction, the fingerprint of `s` with the user's view numbered
    /// `view` (views are numbered as they are first met), when the runs number their
    /// states: cheaper than hashing both.
    fn fingerprint_numbered(&self, _s: &Self::State, _view: u64) -> Option<u64> {
        None
    }

    /// Under symmetry reduction, the fingerprint of `s` up to renaming, with `extra`
    /// (the user's view) renamed along; `None` when states are stored as they are.
    fn fingerprint_with<H: Hash>(
        &self,
        _s: &Self::State,
        _extra: impl Fn(&Renaming) -> H,
    ) -> Option<u64> {
        None
    }
}

/// Runs of one agent, whose states the agent's run properties read.
pub trait OneAgent: Runs {
    /// The agent's state at `s`.
    fn agent_state<'s>(&'s self, s: &'s Self::State) -> impl AgentState + 's;
}

impl OneAgent for Alone<'_> {
    fn agent_state<'s>(&'s self, s: &'s State) -> impl AgentState + 's {
        s
    }
}

impl OneAgent for AloneCompiled<'_, '_, '_> {
    fn agent_state<'s>(&'s self, s: &'s Self::State) -> impl AgentState + 's {
        s
    }
}

impl<'c> OneAgent for AloneStored<'_, 'c, '_, '_> {
    fn agent_state<'s>(&'s self, s: &'s Node<'c>) -> impl AgentState + 's {
        self.packed(s)
    }
}

/// One agent's reasoning cycle, with its states stored up to renaming of interchangeable
/// objects when `symmetry` is given.
#[derive(Clone, Copy)]
pub struct Alone<'a> {
    /// The agent, who is the robot.
    pub sem: &'a Semantics<'a>,
    /// Symmetry reduction over objects, if on.
    pub symmetry: Option<&'a Symmetry>,
}

impl Runs for Alone<'_> {
    type State = State;
    type Notes = Vec<Note>;

    fn agents(&self) -> &[Semantics<'_>] {
        std::slice::from_ref(self.sem)
    }

    fn robot(&self) -> usize {
        0
    }

    fn names(&self) -> Option<&[String]> {
        None
    }

    fn robot_beliefs<'s>(&self, s: &'s State) -> &'s AtomSet {
        &s.beliefs
    }

    fn robot_intentions<'s>(&self, s: &'s State) -> impl Iterator<Item = &'s Intention> {
        s.all_intentions()
    }

    fn world<'s>(&self, s: &'s State) -> &'s AtomSet {
        &s.beliefs
    }

    fn initial(&self) -> Box<dyn Iterator<Item = State> + '_> {
        Box::new(self.sem.initial_iter())
    }

    fn successors(&self, s: &State) -> Vec<(u8, Vec<Note>, State)> {
        self.sem
            .successors(s)
            .into_iter()
            .map(|t| (0, t.notes, t.next))
            .collect()
    }

    fn fingerprint_with<H: Hash>(&self, s: &State, extra: impl Fn(&Renaming) -> H) -> Option<u64> {
        self.symmetry.map(|sym| sym.fingerprint_with(s, extra))
    }
}

/// Every interleaving of the reasoning cycles of several agents, the user watching the one
/// numbered `robot`. No reduction: partial-order reduction would put off steps of the robot
/// the user sees, and symmetry over instances would rename the robot.
#[derive(Clone, Copy)]
pub struct Among<'a> {
    /// The agents.
    pub system: &'a System<'a>,
    /// The robot's index.
    pub robot: usize,
}

impl Runs for Among<'_> {
    type State = SystemState;
    type Notes = Vec<Note>;

    fn agents(&self) -> &[Semantics<'_>] {
        &self.system.agents
    }

    fn robot(&self) -> usize {
        self.robot
    }

    fn names(&self) -> Option<&[String]> {
        Some(self.system.names())
    }

    fn robot_beliefs<'s>(&self, s: &'s SystemState) -> &'s AtomSet {
        &s.agents[self.robot].beliefs
    }

    fn robot_intentions<'s>(&self, s: &'s SystemState) -> impl Iterator<Item = &'s Intention> {
        s.agents[self.robot].all_intentions()
    }

    fn world<'s>(&self, s: &'s SystemState) -> &'s AtomSet {
        &s.world
    }

    fn initial(&self) -> Box<dyn Iterator<Item = SystemState> + '_> {
        Box::new(self.system.initial_states().into_iter())
    }

    fn initial_complete(&self) -> bool {
        self.system.agents[0].project.initial.complete()
    }

    fn successors(&self, s: &SystemState) -> Vec<(u8, Vec<Note>, SystemState)> {
        self.system
            .successors(s)
            .into_iter()
            .map(|(step, t)| (step.agent, step.notes, t))
            .collect()
    }

    fn sensed(&self, s: &SystemState) -> Option<AtomSet> {
        self.system.sensed(s, self.robot)
    }

    fn to_sense(&self, s: &SystemState) -> bool {
        !s.mail[self.robot].is_empty() || !self.system.has_perceived(s, self.robot)
    }
}

/// One agent's compiled reasoning cycle ([`Compiled`]): the runs of [`Alone`], with the
/// same states (packed into shared parts), notes and fingerprints, each phase of the cycle
/// computed once for all the states that share its parts.
pub struct AloneCompiled<'c, 's, 'p> {
    compiled: &'c Compiled<'s, 'p>,
    symmetry: Option<&'c Symmetry>,
    recent: Recent<'c>,
}

impl<'c, 's, 'p> AloneCompiled<'c, 's, 'p> {
    /// The runs of the agent `compiled` is the cycle of, with symmetry reduction over
    /// objects if `symmetry`.
    pub fn new(
        compiled: &'c Compiled<'s, 'p>,
        symmetry: Option<&'c Symmetry>,
    ) -> AloneCompiled<'c, 's, 'p> {
        AloneCompiled {
            compiled,
            symmetry,
            recent: Recent::default(),
        }
    }
}

impl Clone for AloneCompiled<'_, '_, '_> {
    /// The same runs, with no successors kept yet.
    fn clone(&self) -> Self {
        AloneCompiled::new(self.compiled, self.symmetry)
    }
}

/// How many agent states [`Recent`] keeps (a power of two).
const RECENT: usize = 1 << 17;

/// The agent's successors of the states met last, one per slot of a table indexed by the
/// state's hash: a user's search meets an agent state once per view the user may have
/// there, and computing its successors each time was a quarter of the search. On the
/// store-cup library (7.7 views a state) 85% of the lookups hit; on the 4-cup kitchen
/// about 15% of a possible 40%, its views of a state coming at distant depths.
///
/// Where few lookups hit (the kitchen's 1.5 views a state under symmetry), the slot's lock
/// and the shared counts cost more than the successors they save (symmetric 4-cup kitchen:
/// its users' searches took 1.5-1.9 s with the table, 1.4-1.8 s without). So one lookup in
/// [`SAMPLE`] always goes through the table and counts whether it hit, and the others use
/// the table only while at least half of the counted lookups hit.
struct Recent<'c> {
    slots: Box<[Mutex<Option<Known<'c>>>]>,
    /// Counted lookups and hits, 32 bits each (hits in the low half).
    counts: std::sync::atomic::AtomicU64,
}

/// One lookup in this many (by the state's hash) is counted.
const SAMPLE: u64 = 64;

/// An agent state and its successors.
type Known<'c> = (Packed<'c>, Arc<[(Notes<'c>, Packed<'c>)]>);

impl Default for Recent<'_> {
    fn default() -> Self {
        Recent {
            slots: (0..RECENT).map(|_| Mutex::new(None)).collect(),
            counts: std::sync::atomic::AtomicU64::new(0),
        }
    }
}

impl<'c> Recent<'c> {
    /// Whether the successors of `s` are to be computed without the table: `s` is not
    /// a counted lookup, and fewer than half of the counted ones hit.
    fn bypassed(&self, s: &Packed<'c>) -> bool {
        let c = self.counts.load(std::sync::atomic::Ordering::Relaxed);
        !Self::counted(s.address_hash()) && (c & 0xffff_ffff) * 2 < c >> 32
    }

    /// Whether a lookup of the state with this address hash is counted.
    fn counted(hash: u64) -> bool {
        (hash >> 32).is_multiple_of(SAMPLE)
    }

    /// The successors of `s` in `compiled` through the table: kept ones when `s` was met
    /// last in its slot.
    fn successors(&self, compiled: &'c Compiled, s: &Packed<'c>) -> Arc<[(Notes<'c>, Packed<'c>)]> {
        use std::sync::atomic::Ordering::Relaxed;
        let hash = s.address_hash();
        let counted = Self::counted(hash);
        let slot = &self.slots[hash as usize & (RECENT - 1)];
        // A panic in another search thread is re-raised by the explorer; a slot holds
        // a whole entry or none.
        let lock = || slot.lock().unwrap_or_else(|e| e.into_inner());
        let known = lock()
            .as_ref()
            .filter(|(p, _)| p == s)
            .map(|(_, succ)| succ.clone());
        if counted {
            // Halved before either half overflows: the recent lookups weigh more.
            let hit = u64::from(known.is_some());
            let _ = self.counts.fetch_update(Relaxed, Relaxed, |c| {
                let c = if c >> 32 >= 1 << 30 {
                    (c >> 1) & !(1 << 31)
                } else {
                    c
                };
                Some(c + (1 << 32) + hit)
            });
        }
        if let Some(succ) = known {
            return succ;
        }
        let succ: Arc<[_]> = compiled.successors(s).into();
        *lock() = Some((*s, succ.clone()));
        succ
    }
}

impl<'c> Runs for AloneCompiled<'c, '_, '_> {
    type State = Packed<'c>;
    type Notes = Notes<'c>;

    fn agents(&self) -> &[Semantics<'_>] {
        std::slice::from_ref(self.compiled.semantics())
    }

    fn robot(&self) -> usize {
        0
    }

    fn names(&self) -> Option<&[String]> {
        None
    }

    fn robot_beliefs<'s>(&self, s: &'s Packed<'c>) -> &'s AtomSet {
        s.beliefs()
    }

    fn robot_intentions<'s>(&self, s: &'s Packed<'c>) -> impl Iterator<Item = &'s Intention> {
        s.all_intentions()
    }

    fn world<'s>(&self, s: &'s Packed<'c>) -> &'s AtomSet {
        s.beliefs()
    }

    fn initial(&self) -> Box<dyn Iterator<Item = Packed<'c>> + '_> {
        Box::new(self.compiled.initial_iter())
    }

    fn successors(&self, s: &Packed<'c>) -> Vec<(u8, Notes<'c>, Packed<'c>)> {
        if self.recent.bypassed(s) {
            return (self.compiled.successors(s).into_iter())
                .map(|(notes, next)| (0, notes, next))
                .collect();
        }
        (self.recent.successors(self.compiled, s).iter())
            .map(|(notes, next)| (0, notes.clone(), *next))
            .collect()
    }

    fn notes_key(&self, notes: &Notes<'c>) -> Option<SmallVec<[usize; 4]>> {
        Some(notes.key())
    }

    fn beliefs_key(&self, s: &Packed<'c>) -> usize {
        s.beliefs_key()
    }

    fn intentions_key(&self, s: &Packed<'c>) -> Option<SmallVec<[usize; 8]>> {
        Some(s.intentions_key())
    }

    fn fingerprint_with<H: Hash>(
        &self,
        s: &Packed<'c>,
        extra: impl Fn(&Renaming) -> H,
    ) -> Option<u64> {
        self.symmetry
            .map(|sym| sym.fingerprint_with_compiled(self.compiled, s, extra))
    }
}

/// The agent's graph as its exact, complete search stored it on the compiled cycle: every
/// state, and the notes of each of its transitions in the graph's order. A user's search
/// then follows the stored transitions ([`AloneStored`]) instead of running the cycle
/// again: a user meets each agent state once per view it may have there. About 8 bytes
/// a state: the state in a word of 6 bytes ([`Words`], [`ShortWords`]), and a number per
/// transition for its notes ([`NoteIds`]).
#[derive(Default)]
pub struct Stored<'c> {
    /// The states in the graph's order, as [`Stored::words`] made them, while the search
    /// adds them.
    building: StateWords,
    /// The same once the search is over ([`Stored::finish`]), shared with what gives the
    /// graph's fingerprints from them ([`Stored::fingerprints`]).
    states: Arc<StateWords>,
    words: Words<'c>,
    /// Per transition, state by state in the graph's order, its notes' number: a state's
    /// begin where its edges do ([`Graph::first_transition`]). Held in two bytes each
    /// while the numbers fit (6-cup kitchen: 71.7 M transitions, 287 MB in four bytes).
    notes: Narrow,
    /// The notes by number, once the search is over ([`Stored::finish`]), each with
    /// whether the user sees any of them ([`shown`]).
    distinct: Vec<Vec<(Notes<'c>, bool)>>,
    /// Whether a state could not be held (too many transitions to number, too many
    /// agendas and requests or an address beyond a word's bits ([`Words::word`]), or memory):
    /// the graph is then unusable.
    broken: bool,
}

impl<'c> Stored<'c> {
    /// Adds the next state (in the search's numbering) and its transitions' notes, by
    /// their numbers in [`NoteIds`].
    pub fn push(&mut self, state: Packed<'c>, notes: impl IntoIterator<Item = u32>) {
        if self.broken {
            return;
        }
        let Some(word) = self.words.word(&state) else {
            self.broken = true;
            return;
        };
        let held = || -> Result<(), OutOfMemory> {
            self.building.push(word)?;
            for n in notes {
                self.notes.push(n)?;
            }
            Ok(())
        };
        if held().is_err() {
            self.broken = true;
        }
    }

    /// The notes `ids` numbered, held from now on.
    pub fn finish(&mut self, ids: NoteIds<'c>) {
        self.states = Arc::new(std::mem::take(&mut self.building));
        self.broken |= ids.full.into_inner();
        self.distinct = (ids.shards.into_iter())
            .map(|s| {
                let notes = s.into_inner().unwrap_or_else(|e| e.into_inner()).1;
                (notes.into_iter())
                    .map(|n| {
                        let seen = n.iter().any(shown);
                        (n, seen)
                    })
                    .collect()
            })
            .collect();
    }

    /// Whether every state of `graph` is held, each with the notes of all its transitions.
    pub fn covers<S>(&self, graph: &Graph<S>) -> bool {
        !self.broken
            && graph.complete()
            && self.states.len() == graph.len()
            && graph.kept_transitions() == Some(self.notes.len() as u64)
    }

    /// What gives the fingerprint of the graph's state `i` from its word, once the search
    /// is over ([`Stored::finish`]), `compiled` being the cycle it ran: the graph's store
    /// need not keep them then ([`Graph::derive_fingerprints`]).
    pub fn fingerprints(&self, compiled: &Compiled<'_, '_>) -> crate::check::store::Derived {
        let (states, hashes) = (Arc::clone(&self.states), self.words.hashes(compiled));
        Box::new(move |i| {
            (hashes.fingerprint(states.get(i as usize)))
                .expect("a stored state's word is one its words made")
        })
    }

    /// The notes numbered `id`, and whether the user sees any of them.
    fn notes(&self, id: u32) -> &(Notes<'c>, bool) {
        &self.distinct[id as usize % SHARDS][id as usize / SHARDS]
    }
}

/// The words of a graph's states ([`Words::word`]) in its order: in 6 bytes each
/// ([`ShortWords`]) while every one fits, else all in 8 (widened once).
enum StateWords {
    Short(ShortWords, Chunked<[u16; 3]>),
    Long(Chunked<u64>),
}

impl Default for StateWords {
    fn default() -> StateWords {
        StateWords::Long(Chunked::default())
    }
}

/// A 48-bit number in three halves, and back.
fn halves(x: u64) -> [u16; 3] {
    [x as u16, (x >> 16) as u16, (x >> 32) as u16]
}

fn unhalves([a, b, c]: [u16; 3]) -> u64 {
    u64::from(a) | u64::from(b) << 16 | u64::from(c) << 32
}

impl StateWords {
    /// Appends `word`.
    fn push(&mut self, word: u64) -> Result<(), OutOfMemory> {
        match self {
            StateWords::Long(held) if held.len() == 0 => {
                *self = StateWords::Short(ShortWords::around(word), Chunked::default());
                self.push(word)
            }
            StateWords::Long(held) => held.push(word),
            StateWords::Short(short, held) => match short.short(word) {
                Some(x) => held.push(halves(x)),
                None => {
                    let mut long = Chunked::default();
                    for x in held.iter() {
                        long.push(short.long(unhalves(x)))?;
                    }
                    long.push(word)?;
                    *self = StateWords::Long(long);
                    Ok(())
                }
            },
        }
    }

    /// Word `i`.
    #[inline]
    fn get(&self, i: usize) -> u64 {
        match self {
            StateWords::Short(short, held) => short.long(unhalves(held.get(i))),
            StateWords::Long(held) => held.get(i),
        }
    }

    /// Asks for word `i` to be brought into the cache.
    #[inline]
    fn prefetch(&self, i: usize) {
        match self {
            StateWords::Short(_, held) => held.prefetch(i),
            StateWords::Long(held) => held.prefetch(i),
        }
    }

    fn len(&self) -> usize {
        match self {
            StateWords::Short(_, held) => held.len(),
            StateWords::Long(held) => held.len(),
        }
    }
}

/// Numbers for the distinct notes of the agent's transitions (notes the compiled cycle
/// shares are equal when they are the same values: [`Notes::key`]), given as the search
/// meets them, from any thread.
pub struct NoteIds<'c> {
    shards: [Mutex<NotesShard<'c>>; SHARDS],
    /// Whether a shard ran out of numbers.
    full: std::sync::atomic::AtomicBool,
    /// Tells these numbers from another search's in the threads' caches ([`RECENT_IDS`]).
    serial: u64,
}

/// One shard of [`NoteIds`]: numbers by key, and the notes by number (divided by
/// [`SHARDS`]: the rest of the division is the shard).
type NotesShard<'c> = (HashMap<SmallVec<[usize; 4]>, u32, Quick>, Vec<Notes<'c>>);

/// How many numbers of notes each thread keeps at hand (a power of two).
const RECENT_IDS: usize = 1 << 10;

thread_local! {
    /// Numbering notes through the shards' locks and maps was most of what keeping the
    /// graph cost the agent's search (7% of it): each thread keeps the numbers it gave
    /// last, by the notes' key (of at most two phases).
    static NUMBERED: Recently<[usize; 4], u32> = const { std::cell::RefCell::new(Vec::new()) };
}

impl Default for NoteIds<'_> {
    fn default() -> Self {
        NoteIds {
            shards: Default::default(),
            full: Default::default(),
            serial: super::recent::serial(),
        }
    }
}

impl<'c> NoteIds<'c> {
    /// The number of `notes`.
    pub fn id(&self, notes: &Notes<'c>) -> u32 {
        let Some(words) = notes.short_key() else {
            return self.numbered(notes.key(), notes);
        };
        recently(
            &NUMBERED,
            RECENT_IDS,
            (self.serial, words),
            || self.numbered(notes.key(), notes),
            |id| *id,
        )
    }

    /// The number of `notes`, of key `key`, from the shards.
    fn numbered(&self, key: SmallVec<[usize; 4]>, notes: &Notes<'c>) -> u32 {
        let hash = quick(&key);
        let k = (hash >> 40) as usize % SHARDS;
        let mut shard = self.shards[k].lock().unwrap_or_else(|e| e.into_inner());
        if let Some(&id) = shard.0.get(&key) {
            return id;
        }
        let Some(id) = (shard.1.len())
            .checked_mul(SHARDS)
            .and_then(|x| u32::try_from(x + k).ok())
        else {
            self.full.store(true, std::sync::atomic::Ordering::Relaxed);
            return 0;
        };
        shard.1.push(notes.clone());
        shard.0.insert(key, id);
        id
    }
}

/// A state of [`AloneStored`]: its number in the agent's graph, which alone identifies it
/// (hashed and compared), and its word in [`Stored`] (its belief base, agenda and
/// requests), in 12 bytes: a user's frontier holds millions of states (8.7 M at 6 cups),
/// and with the word split in the state an entry took 32 bytes instead of 20. (Reading the
/// word again from [`Stored`] when asked for took 12 bytes more off an entry, but made each
/// user's search 2-5 s slower, of 20-30 s.)
#[derive(Clone, Copy)]
#[repr(C, packed(4))]
pub struct Node<'c> {
    word: u64,
    index: u32,
    graph: PhantomData<&'c Part<Base>>,
}

// A packed struct's fields are copied out before use: a reference to one may be unaligned.
impl PartialEq for Node<'_> {
    fn eq(&self, o: &Node<'_>) -> bool {
        let (a, b) = (self.index, o.index);
        a == b
    }
}

impl Eq for Node<'_> {}

impl Hash for Node<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        { self.index }.hash(h);
    }
}

impl Node<'_> {
    /// The state's number in the agent's graph.
    pub fn index(&self) -> u32 {
        self.index
    }
}

impl Debug for Node<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "state {} of the agent's graph", { self.index })
    }
}

/// The notes of a transition of [`AloneStored`]: their number ([`NoteIds`]), which
/// identifies them, and the notes.
#[derive(Clone, Copy, Default)]
pub struct StoredNotes<'g, 'c> {
    id: u32,
    /// Whether the user sees any of them ([`shown`]).
    shown: bool,
    notes: Option<&'g Notes<'c>>,
}

impl Debug for StoredNotes<'_, '_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.notes()).finish()
    }
}

impl CycleNotes for StoredNotes<'_, '_> {
    fn notes(&self) -> impl Iterator<Item = &Note> {
        self.notes.into_iter().flat_map(|n| n.iter())
    }
}

/// The runs of [`AloneCompiled`] without symmetry, read from the agent's stored graph
/// ([`Stored`]): the same states, transitions, notes and order, so a user's search meets
/// the same states in the same order, without computing a successor again.
#[derive(Clone, Copy)]
pub struct AloneStored<'g, 'c, 's, 'p> {
    compiled: &'c Compiled<'s, 'p>,
    stored: &'g Stored<'c>,
    graph: &'g Graph,
}

impl<'g, 'c, 's, 'p> AloneStored<'g, 'c, 's, 'p> {
    /// The runs of `graph`, the complete graph of an exact search on `compiled`, whose
    /// states and notes `stored` holds; `None` unless it holds them all.
    pub fn new(
        compiled: &'c Compiled<'s, 'p>,
        stored: &'g Stored<'c>,
        graph: &'g Graph,
    ) -> Option<AloneStored<'g, 'c, 's, 'p>> {
        stored.covers(graph).then_some(AloneStored {
            compiled,
            stored,
            graph,
        })
    }

    fn node(&self, index: u32) -> Node<'c> {
        Node {
            word: self.stored.states.get(index as usize),
            index,
            graph: PhantomData,
        }
    }

    /// The agent's belief base at `s`, and the number of its agenda and requests.
    #[inline]
    fn split(&self, s: &Node<'c>) -> (&'c Part<Base>, u32) {
        // SAFETY: a node's word is one of `Stored::states` (`AloneStored::node`), which
        // `Stored::words` made.
        unsafe { self.stored.words.split(s.word) }
    }

    /// The agent's state at `s`.
    fn packed(&self, s: &Node<'c>) -> Packed<'c> {
        let (beliefs, rest) = self.split(s);
        self.stored.words.packed(beliefs, rest)
    }
}

impl<'g, 'c> Runs for AloneStored<'g, 'c, '_, '_> {
    type State = Node<'c>;
    type Notes = StoredNotes<'g, 'c>;

    fn agents(&self) -> &[Semantics<'_>] {
        std::slice::from_ref(self.compiled.semantics())
    }

    fn robot(&self) -> usize {
        0
    }

    fn names(&self) -> Option<&[String]> {
        None
    }

    fn robot_beliefs<'s>(&self, s: &'s Node<'c>) -> &'s AtomSet {
        &self.split(s).0 .0
    }

    fn robot_intentions<'s>(&self, s: &'s Node<'c>) -> impl Iterator<Item = &'s Intention> {
        self.packed(s).all_intentions()
    }

    fn world<'s>(&self, s: &'s Node<'c>) -> &'s AtomSet {
        &self.split(s).0 .0
    }

    fn initial(&self) -> Box<dyn Iterator<Item = Node<'c>> + '_> {
        // The search numbers the initial states first, in the order the cycle gives them.
        Box::new((0..self.graph.initial as u32).map(|i| self.node(i)))
    }

    fn successors(&self, s: &Node<'c>) -> Vec<(u8, StoredNotes<'g, 'c>, Node<'c>)> {
        let mut out = Vec::new();
        self.each_successor(s, |agent, notes, next| out.push((agent, notes, next)));
        out
    }

    fn each_successor(&self, s: &Node<'c>, mut f: impl FnMut(u8, StoredNotes<'g, 'c>, Node<'c>)) {
        let targets = (self.graph.successors(s.index))
            .expect("a complete graph keeps every state's transitions");
        let st = self.stored;
        let from = (self.graph.first_transition(s.index))
            .expect("a complete graph keeps every state's transitions") as usize;
        for (k, &t) in targets.iter().enumerate() {
            let id = st.notes.get(from + k);
            let (notes, shown) = st.notes(id);
            let notes = Some(notes);
            f(
                0,
                StoredNotes {
                    id,
                    shown: *shown,
                    notes,
                },
                self.node(t),
            );
        }
    }

    fn prefetch(&self, s: &Node<'c>, stage: usize) {
        let st = self.stored;
        match stage {
            // The state itself was read when it was met, long before.
            0 => self.graph.prefetch_successors(s.index, false),
            1 => {
                self.graph.prefetch_successors(s.index, true);
                if let Some(from) = self.graph.first_transition(s.index) {
                    st.notes.prefetch(from as usize);
                }
                let (beliefs, rest) = self.split(s);
                prefetch(beliefs);
                prefetch(self.stored.words.agenda_key(rest) as *const u8);
            }
            _ => {
                for &t in self.graph.successors_unchecked(s.index) {
                    st.states.prefetch(t as usize);
                }
            }
        }
    }

    fn notes_key(&self, notes: &StoredNotes<'g, 'c>) -> Option<SmallVec<[usize; 4]>> {
        Some(smallvec::smallvec![notes.id as usize])
    }

    fn shown(&self, notes: &StoredNotes<'g, 'c>) -> Option<bool> {
        Some(notes.shown)
    }

    fn beliefs_key(&self, s: &Node<'c>) -> usize {
        self.split(s).0 as *const Part<Base> as usize
    }

    fn intentions_key(&self, s: &Node<'c>) -> Option<SmallVec<[usize; 8]>> {
        let (_, rest) = self.split(s);
        Some(smallvec::smallvec![self.stored.words.agenda_key(rest)])
    }

    fn fingerprint_numbered(&self, s: &Node<'c>, view: u64) -> Option<u64> {
        // Exact: the pair's own bits, mixed. The user's store keeps the first four views met
        // at each agent state by the state's number (`Store::fingerprints_by_place`).
        Some(pair_fingerprint(u32::try_from(view).ok()?, s.index))
    }
}

/// The runs of an agent, or of several, as one user watching the robot sees them.
pub struct Explained<'a, W = Alone<'a>> {
    runs: W,
    ex: &'a Explainer<'a>,
    user: &'a User,
    tables: Tables,
    /// Tells this search's entries from another's in the threads' caches ([`recently`]).
    serial: u64,
}

/// How many entries of a memo each thread keeps at hand ([`recently`]; a power of two).
const READ_RECENTLY: usize = 1 << 14;

thread_local! {
    /// [`Tables::seen`]'s entries for notes of one word ([`Runs::notes_key`]) on which no
    /// explanation is due, by view (number) and word. A user's search on a stored graph
    /// reads that memo at most transitions, and few of its entries at a time: 98.5% of
    /// the reads hit a table of 2^14 (5-cup kitchen), and the shared memo's lock, hashing
    /// and probe were a tenth of the search.
    static SEEN_RECENTLY: Recently<(usize, usize), Kept> = const { std::cell::RefCell::new(Vec::new()) };
    /// [`Tables::seen`]'s entries for notes of one word on which explanations were due, by
    /// view (number), word and the explanations' words ([`Explained::given_key`]: how
    /// many, then up to two). A fifth of a user's transitions on the kitchen take this
    /// path, and the shared memo's lock and probe of a key of two `SmallVec`s.
    static DUE_RECENTLY: Recently<(usize, usize, [usize; 3]), Kept> = const { std::cell::RefCell::new(Vec::new()) };
    /// [`Tables::judged`]'s entries for robot states of one intentions word, by view
    /// (number), [`judged_flags`] and the word: the view's number alone when the entry
    /// finds no violation (read without following the pointer, as [`Kept`]), else the entry.
    static JUDGED_RECENTLY: Recently<(usize, usize, usize), Result<u32, Arc<Judged>>> = const { std::cell::RefCell::new(Vec::new()) };
    /// Whether every mark of a view is of a frame still in the robot's intentions, by
    /// view (number) and the robot's intentions of one word ([`Explained::marks_alive`]).
    static ALIVE_RECENTLY: Recently<(u32, usize), bool> = const { std::cell::RefCell::new(Vec::new()) };
    /// [`Tables::contents`]' entries, by action note (address).
    static CONTENTS_RECENTLY: Recently<usize, Arc<Option<(Explanation, LiteralAtoms)>>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Whether the user sees the note `n` (a request, a plan adopted, an action, a failure):
/// a step of the robot with none of these, no explanation to judge and every mark in place
/// leaves the user's view as it was.
fn shown(n: &Note) -> bool {
    matches!(
        n,
        Note::Request { .. }
            | Note::Plan { .. }
            | Note::Action { .. }
            | Note::ActionFailed { .. }
            | Note::GoalFailed { .. }
    )
}

/// A [`JudgedKey`]'s failure, sense and changes as one word, when its view has at most 62
/// open explanations (bit 0 failed, bit 1 unsensed, bit `k + 2` the `k`-th changed).
fn judged_flags(failed: bool, unsensed: bool, changed: &[bool]) -> Option<usize> {
    (changed.len() <= usize::BITS as usize - 2).then(|| {
        (changed.iter().enumerate()).fold(
            usize::from(failed) | usize::from(unsensed) << 1,
            |bits, (k, &c)| bits | usize::from(c) << (k + 2),
        )
    })
}

/// Tables are split in this many shards, each behind its own lock.
const SHARDS: usize = 32;

/// The views met so far, each once, and what the notes of a transition made of a view
/// (with the robot's beliefs), each once: most transitions of a user's search repeat one
/// already met on another state of the agent.
#[derive(Default)]
struct Tables {
    /// The views met so far, each once, by number: a state holds its view's number. A
    /// shared pointer there had every transition and every state dropped count references
    /// (3-5 atomic operations a transition, on the views' scattered cache lines), and a
    /// number is read without them.
    views: boxcar::Vec<(u64, View)>,
    /// Per hash of a view, the numbers of the views of that hash.
    numbers: [Mutex<ViewNumbers>; SHARDS],
    seen: Table<SeenKey, Seen>,
    judged: Table<JudgedKey, Judged>,
    /// Per action note (by address) and beliefs (by [`Runs::beliefs_key`]): Algorithm 2's
    /// explanation and the truth of its context, one of `judgeables` (interned, so that its
    /// address stands for it in a memo key while the search lasts).
    explained: Table<(usize, usize), Option<Judgeable>>,
    /// Per action note (by address): Algorithm 2's explanation and the atoms of its
    /// context's literals, when its content does not read the beliefs (`syntactic`).
    contents: Table<usize, Option<(Explanation, LiteralAtoms)>>,
    /// Per action note (by address) and explanation given (by the address of its
    /// interned [`Judgeable`]): the obligation it opens. Made anew, each was hashed, and
    /// compared whole with the one of the same view already interned (4-cup kitchen: a
    /// tenth of the users' instructions).
    obligations: Table<(usize, usize), Hashed<Obligation>>,
    /// Each distinct value of `explained` once, so that equal ones have one address: what
    /// a transition makes of a view depends on the beliefs only through them.
    judgeables: [Mutex<HashSet<Arc<Option<Judgeable>>, Quick>>; SHARDS],
    /// Per context atom, the atoms it unifies with.
    instances: [Mutex<Instances>; SHARDS],
    /// Under symmetry, per view (by number: views are interned) and renaming: the hash
    /// of the view renamed. A state's fingerprint tries a renaming or more of every
    /// successor, and renaming a view's terms and hashing them cost more than the rest
    /// of the user's search; a view meets few renamings.
    renamed: [Mutex<RenamedViews>; SHARDS],
}

/// Per hash of a view, the numbers of the views of that hash (one shard of
/// [`Tables::numbers`]).
type ViewNumbers = HashMap<u64, SmallVec<[u32; 1]>, Quick>;

/// Per view (by number) and renaming: the hash of the view renamed (one shard of
/// [`Tables::renamed`]).
type RenamedViews = HashMap<(usize, SmallVec<[u16; 16]>), u64, Quick>;

/// What a fingerprint reads of a view, renamed (see [`Explained::renamed_view`]).
type RenamedView = (
    Vec<Pair>,
    Option<Observation>,
    Vec<Pair>,
    Vec<(Origin, u16, u32, u16)>,
    Vec<Obligation>,
    Option<Term>,
);

/// Per context atom, the atoms it unifies with (one shard of [`Tables::instances`]).
type Instances = HashMap<Term, Arc<[AtomId]>, Quick>;

/// `x`'s hash by [`Quick`], as the tables compute it.
fn quick<T: Hash + ?Sized>(x: &T) -> u64 {
    use std::hash::BuildHasher;
    Quick::default().hash_one(x)
}

/// Algorithm 2's explanation, and the truth of each literal of its context when given.
type Judgeable = (Explanation, Vec<bool>);

/// A memo: values by key, in shards.
type Table<K, V> = [Mutex<HashMap<K, Arc<V>, Quick>>; SHARDS];

/// A view after a transition judged: the view (its number), and the violations found.
type Judged = (u32, Vec<Violation>);

/// A view (by number) after a transition's notes (by address), whether they failed,
/// whether the robot has yet to sense, whether each open explanation's context changed on
/// the robot's beliefs after it, and its intentions after it (by
/// [`Runs::intentions_key`]).
#[derive(PartialEq, Eq, Hash)]
struct JudgedKey(usize, bool, bool, SmallVec<[bool; 4]>, SmallVec<[usize; 8]>);

/// The value of `key` in `table`, computed (without the lock: computing interns views)
/// when it is new.
fn memo<K: Hash + Eq, V>(table: &Table<K, V>, key: K, compute: impl FnOnce() -> V) -> Arc<V> {
    memo_read(table, key, compute, Arc::clone)
}

/// [`memo`], read by `read` under the table's lock instead of returned: two threads
/// counting references to one entry from every transition made its cache line travel.
fn memo_read<K: Hash + Eq, V, R>(
    table: &Table<K, V>,
    key: K,
    compute: impl FnOnce() -> V,
    read: impl Fn(&Arc<V>) -> R,
) -> R {
    let hash = quick(&key);
    if let Some(v) = shard(table, hash).get(&key) {
        return read(v);
    }
    let v = Arc::new(compute());
    read(shard(table, hash).entry(key).or_insert(v))
}

/// A [`Seen`] as a thread's cache ([`recently`]) keeps it: most give no explanation
/// and find no violation, and then the view's number (with the flags) is all a transition
/// takes, read from the cache's slot instead of through a pointer to the entry (a line
/// of the memo's, rarely in the cache: a dependent miss at most transitions).
#[derive(Clone)]
enum Kept {
    /// The view after, whether a failure was among the notes, and whether that view has no
    /// open explanation and no mark (nothing to judge after the transition).
    Plain {
        view: u32,
        failed: bool,
        quiet: bool,
    },
    /// Anything else.
    Whole(Arc<Seen>),
}

impl Kept {
    /// How a thread's cache keeps `seen`, a view after notes in `tables`.
    fn seen(seen: Arc<Seen>, tables: &Tables) -> Kept {
        match seen.given.is_none() && seen.violations.is_empty() && !seen.reads_beliefs {
            true => Kept::Plain {
                view: seen.view,
                failed: seen.failed,
                quiet: tables.quiet(seen.view),
            },
            false => Kept::Whole(seen),
        }
    }

    /// [`Seen::read_unless_due`].
    fn read_unless_due(&self) -> Result<SeenRead, SmallVec<[u32; 2]>> {
        match self {
            Kept::Whole(seen) => seen.read_unless_due(),
            Kept::Plain { .. } => Ok(self.read()),
        }
    }

    /// [`Seen::read`].
    fn read(&self) -> SeenRead {
        match self {
            Kept::Whole(seen) => seen.read(),
            &Kept::Plain {
                view,
                failed,
                quiet,
            } => SeenRead {
                view,
                given: None,
                violations: Vec::new(),
                failed,
                quiet: Some(quiet),
            },
        }
    }
}

/// What a transition takes of a [`Seen`].
struct SeenRead {
    view: u32,
    given: Option<Arc<[Option<GivenExplanation>]>>,
    violations: Vec<Violation>,
    failed: bool,
    /// Whether the view has no open explanation and no mark, when known.
    quiet: Option<bool>,
}

impl Seen {
    /// What a transition takes of it.
    fn read(&self) -> SeenRead {
        SeenRead {
            view: self.view,
            given: self.given.clone(),
            violations: self.violations.clone(),
            failed: self.failed,
            quiet: None,
        }
    }

    /// [`Seen::read`], or the notes whose explanation was due when it read the beliefs.
    fn read_unless_due(&self) -> Result<SeenRead, SmallVec<[u32; 2]>> {
        match self.reads_beliefs {
            true => Err(self.due.clone()),
            false => Ok(self.read()),
        }
    }
}

/// A view (by number: views are interned), the notes (by [`Runs::notes_key`]), and the
/// explanations the due ones get on the robot's beliefs (by address: interned), none when
/// no explanation is due.
#[derive(PartialEq, Eq, Hash)]
struct SeenKey(usize, SmallVec<[usize; 4]>, SmallVec<[usize; 2]>);

/// What a transition's notes made of a view: the view after them, the explanations given
/// at each, the violations, whether a failure was among them.
struct Seen {
    /// Its number.
    view: u32,
    given: Option<Arc<[Option<GivenExplanation>]>>,
    violations: Vec<Violation>,
    failed: bool,
    /// Whether the robot's beliefs were read (an explanation was due): else it is the same
    /// for every state.
    reads_beliefs: bool,
    /// The notes (by position) whose explanation was due: the beliefs were read through
    /// their explanations alone. Which are due depends on the view and the notes only.
    due: SmallVec<[u32; 2]>,
}

fn shard<T>(table: &[Mutex<T>; SHARDS], hash: u64) -> MutexGuard<'_, T> {
    // A panic in another search thread is re-raised by the explorer; a table it left is
    // consistent (every insertion is a single call).
    table[(hash >> 40) as usize % SHARDS]
        .lock()
        .unwrap_or_else(|e| e.into_inner())
}

impl Tables {
    /// The number of the view equal to `view`, numbered when new.
    fn intern(&self, view: View) -> u32 {
        let hash = fingerprint(&view);
        let mut numbers = shard(&self.numbers, hash);
        let same = numbers.entry(hash).or_default();
        if let Some(&n) = same.iter().find(|&&n| self.views[n as usize].1 == view) {
            return n;
        }
        // Numbers are taken while the shard is held: a view is numbered once.
        let n = u32::try_from(self.views.push((hash, view)))
            .expect("fewer than 2^32 views of a run (each a distinct state of the user)");
        same.push(n);
        n
    }

    /// The view numbered `n` (by [`Tables::intern`]).
    fn view(&self, n: u32) -> &View {
        &self.views[n as usize].1
    }

    /// Whether the view numbered `n` has no open explanation and no mark: a transition
    /// from a state of it that the user does not see leaves it as it is.
    fn quiet(&self, n: u32) -> bool {
        let view = self.view(n);
        view.open.is_empty() && view.marks.is_empty()
    }
}

/// A state of [`Explained`]: the runs' (the agent's, or the system's), and the user's view
/// of the run so far ([`Explained::expected`] and [`Explained::last_observed`] read it).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ExplainedState<S = State> {
    /// The agent, or every agent.
    pub state: S,
    /// The user's view, by its number in the search's views ([`Tables::intern`]: equal
    /// views have one number).
    view: u32,
}

/// The user's view of a run.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct View {
    /// `N` as Algorithm 1 updates it on the observed sequence.
    n: ExpectedSuccessors,
    /// The last observation, if any.
    prev: Option<Observation>,
    /// `N` as the paper's Algorithm 1 updates it at plan adoption.
    adoption: ExpectedSuccessors,
    /// Body actions that the paper's Algorithm 1 marked and that have not run yet.
    marks: Vec<Mark>,
    /// Explanations whose content the run has not judged yet, each hashed once: interning
    /// a view hashed every step of every open explanation anew.
    open: Vec<Hashed<Obligation>>,
    /// The agent's own explanation, emitted since the last environment action.
    emitted: Option<Term>,
}

/// A value left out of the equality and hash of what holds it: any two are equal, and
/// none is hashed.
#[derive(Clone, Copy, Debug, Default)]
struct Unhashed<T>(T);

impl<T> PartialEq for Unhashed<T> {
    fn eq(&self, _: &Unhashed<T>) -> bool {
        true
    }
}

impl<T> Eq for Unhashed<T> {}

impl<T> Hash for Unhashed<T> {
    fn hash<H: std::hash::Hasher>(&self, _: &mut H) {}
}

/// A value with its hash, shared: copied as a pointer, hashed as one word, compared by
/// address first.
#[derive(Debug)]
struct Hashed<T>(Arc<(u64, T)>);

impl<T: Hash> Hashed<T> {
    fn new(x: T) -> Hashed<T> {
        Hashed(Arc::new((fingerprint(&x), x)))
    }
}

impl<T> Clone for Hashed<T> {
    fn clone(&self) -> Hashed<T> {
        Hashed(self.0.clone())
    }
}

impl<T> std::ops::Deref for Hashed<T> {
    type Target = T;

    fn deref(&self) -> &T {
        &self.0 .1
    }
}

impl<T: PartialEq> PartialEq for Hashed<T> {
    fn eq(&self, o: &Hashed<T>) -> bool {
        Arc::ptr_eq(&self.0, &o.0) || (self.0 .0 == o.0 .0 && self.0 .1 == o.0 .1)
    }
}

impl<T: Eq> Eq for Hashed<T> {}

impl<T> Hash for Hashed<T> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        h.write_u64(self.0 .0);
    }
}

/// A body action marked at adoption: the frame (by intention, depth and plan) and the
/// action's position in the body.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct Mark {
    origin: Origin,
    depth: u16,
    plan: u32,
    pos: u16,
}

/// An explanation given, to be judged by what the run does next.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct Obligation {
    origin: Origin,
    depth: u16,
    plan: u32,
    block: u16,
    /// The explained action's position.
    from: u16,
    /// The position of the content's last step.
    end: u16,
    /// The position of the block's last action or subgoal.
    last: u16,
    gamma: Vec<ContextLiteral>,
    /// The atoms each literal of `gamma` may be: every transition asks whether the
    /// context changed, and a lookup per literal was a sixth of a user's search.
    /// A function of the literals, so left out of equality and hashing (a renamed copy
    /// made only to be fingerprinted may keep the old).
    atoms: Unhashed<LiteralAtoms>,
    /// Each literal's truth when the explanation was given.
    truth: Vec<bool>,
    /// The explained action and its step.
    action: Term,
    span: Span,
    /// The content's steps, for messages.
    steps: Vec<PlanStep>,
}

/// Per literal of an obligation's context, the atoms an instance of it may be
/// ([`Explainer::instances`]).
#[derive(Clone, Debug, Default)]
struct LiteralAtoms(Vec<Arc<[AtomId]>>);

impl LiteralAtoms {
    /// The truth of each literal of `gamma` (whose atoms these are) on `beliefs`.
    fn truths<'a>(
        &'a self,
        gamma: &'a [ContextLiteral],
        beliefs: &'a AtomSet,
    ) -> impl Iterator<Item = bool> + 'a {
        (gamma.iter().zip(&self.0))
            .map(|(l, atoms)| atoms.iter().any(|&a| beliefs.contains(a)) == l.positive)
    }
}

/// Up to 62 truths as a word: bit 0 set, bit `k + 1` the `k`-th truth. Odd, so never an
/// address (see [`Explained::given_key`]).
fn truth_bits(truths: impl Iterator<Item = bool>) -> usize {
    (truths.enumerate()).fold(1, |bits, (k, t)| bits | usize::from(t) << (k + 1))
}

/// An explanation given during a transition.
#[derive(Clone, Debug)]
pub struct GivenExplanation {
    /// The explained action.
    pub action: Term,
    /// What the user saw just before it, if anything.
    pub after: Option<Observation>,
    /// What Algorithm 2 says (shared with the explanation it was given from).
    pub content: Arc<Content>,
}

impl GivenExplanation {
    /// The sentence the user hears (made when asked: a search gives many explanations and
    /// reports few).
    pub fn text(&self, ex: &Explainer) -> String {
        ex.sentence(&self.action, &self.content)
    }
}

/// A property violated by a transition.
#[derive(Clone, Debug)]
pub struct Violation {
    /// The property (one of [`CHECKS`]).
    pub check: &'static str,
    /// Where: the explained (or emitted) action's step.
    pub span: Span,
    /// What was given and what the property demanded.
    pub message: String,
}

/// What one transition of [`Explained`] did.
#[derive(Clone, Debug, Default)]
pub struct Step<N = Vec<Note>> {
    /// The agent that moved (its index among [`Runs::agents`]; for a request, the agent it
    /// goes to).
    pub agent: u8,
    /// The agent's notes.
    pub notes: N,
    /// For each note up to the last at which an explanation was given, the explanation
    /// given at it, if any; `None` when none was (read it with [`Step::given_at`]). Not
    /// an empty `Arc`: std shares one for every empty slice, and counting its references
    /// from every transition of two threads was a tenth of a user's search.
    /// Shared with every transition that gives the same ones.
    pub given: Option<Arc<[Option<GivenExplanation>]>>,
    /// Properties violated.
    pub violations: Vec<Violation>,
}

impl<N> Step<N> {
    /// The explanation given at the `i`-th note, if any.
    pub fn given_at(&self, i: usize) -> Option<&GivenExplanation> {
        self.given.as_deref()?.get(i)?.as_ref()
    }
}

impl<'a> Explained<'a> {
    /// The runs of `sem` as `user` sees them, explained by `ex`.
    /// With `symmetry`, states are stored up to renaming of the interchangeable objects,
    /// in the agent state and in the user's view alike.
    pub fn new(
        sem: &'a Semantics<'a>,
        ex: &'a Explainer<'a>,
        user: &'a User,
        symmetry: Option<&'a Symmetry>,
    ) -> Explained<'a> {
        Explained::watching(Alone { sem, symmetry }, ex, user)
    }
}

impl<'a, W: Runs> Explained<'a, W> {
    /// The runs watched.
    pub fn runs(&self) -> &W {
        &self.runs
    }

    /// The runs `runs` as `user`, watching their robot, sees them, explained by `ex` (made
    /// for the robot).
    pub fn watching(runs: W, ex: &'a Explainer<'a>, user: &'a User) -> Explained<'a, W> {
        Explained {
            runs,
            ex,
            user,
            tables: Tables::default(),
            serial: super::recent::serial(),
        }
    }

    /// The robot's reasoning cycle.
    fn sem(&self) -> &Semantics<'_> {
        &self.runs.agents()[self.runs.robot()]
    }

    /// The user's view of a run that starts in `state`: nothing seen, `N` as the manifest
    /// gives it.
    pub fn start(&self, state: W::State) -> ExplainedState<W::State> {
        ExplainedState {
            state,
            view: self.tables.intern(View {
                n: self.user.expected.clone(),
                prev: None,
                adoption: self.user.expected.clone(),
                marks: Vec::new(),
                open: Vec::new(),
                emitted: None,
            }),
        }
    }

    /// The user's view in `s` (a state of this search).
    fn view_of(&self, s: &ExplainedState<W::State>) -> &View {
        self.tables.view(s.view)
    }

    /// The user's expected successors `N` in `s` (a state of this search), as Algorithm 1
    /// has updated them on the run so far.
    pub fn expected(&self, s: &ExplainedState<W::State>) -> &ExpectedSuccessors {
        &self.view_of(s).n
    }

    /// What the user saw last in `s` (a state of this search), if anything.
    pub fn last_observed(&self, s: &ExplainedState<W::State>) -> Option<&Observation> {
        self.view_of(s).prev.as_ref()
    }

    /// A step of the robot's plan `plan` as a message names it, its bindings read in the
    /// robot's state `robot`.
    fn step_text(&self, plan: u32, block: u16, pos: u16, robot: &W::State) -> String {
        let sem = self.sem();
        let Some(step) = sem.block(plan, block).get(pos as usize) else {
            return "the end of the body".into();
        };
        let subst = self
            .runs
            .robot_intentions(robot)
            .flat_map(|i| &i.frames)
            .find(|f| f.plan == plan)
            .map(|f| f.subst.clone())
            .unwrap_or_default();
        match &step.kind {
            BodyStep::Action(t) => subst.apply(t).to_string(),
            BodyStep::Achieve { goal, .. } => format!("!{}", subst.apply(goal)),
            _ => {
                let loc = sem.project.map.location(step.span);
                format!("the step at {}:{}", loc.line, loc.column)
            }
        }
    }

    /// Algorithm 1 as the paper wrote it, at the adoption of `plan`.
    fn adopt(
        &self,
        st: &mut View,
        plan: u32,
        origin: Origin,
        subst: &crate::model::Substitution,
        depth: u16,
    ) {
        let sem = self.sem();
        let mut prev = st.prev.clone();
        for (pos, step) in sem.block(plan, 0).iter().enumerate() {
            let BodyStep::Action(t) = &step.kind else {
                continue;
            };
            let action = subst.apply(t);
            if sem.is_emission(&action) {
                continue;
            }
            let next = Observation::Action(action);
            if st.adoption.learn(prev.as_ref(), &next) {
                st.marks.push(Mark {
                    origin,
                    depth,
                    plan,
                    pos: pos as u16,
                });
            }
            prev = Some(next);
        }
    }

    /// Judges the open explanations against the robot's intentions in `robot` and its
    /// beliefs `beliefs` (after a transition; among several agents, also after the sense
    /// that begins its cycle, its intentions as before that cycle). A failure in the
    /// transition decides nothing: its explanations are dropped. With `unsensed` (the
    /// robot has yet to perceive what changed, its last action's effects among them), a
    /// body that ended with no change is judged once it has.
    fn judge(
        &self,
        open: &mut Vec<Hashed<Obligation>>,
        (robot, beliefs): (&W::State, &AtomSet),
        failed: bool,
        unsensed: bool,
        out: &mut Vec<Violation>,
    ) {
        let pending = std::mem::take(open);
        if failed {
            return;
        }
        for o in pending {
            let frame = self
                .runs
                .robot_intentions(robot)
                .filter(|i| i.origin == o.origin)
                .filter_map(|i| i.frames.get(o.depth as usize))
                .find(|f| f.plan == o.plan);
            let at = frame.and_then(|f| f.cursors.iter().find(|c| c.block == o.block));
            let changed = self.context_changed(&o, beliefs);
            let real = match (changed, at) {
                // The step before the cursor ran (or waits for its sub-intention).
                (true, Some(c)) if c.pos > o.from => c.pos - 1,
                (true, _) => o.last,
                (false, None) if !unsensed => o.last,
                (false, _) => {
                    open.push(o);
                    continue;
                }
            };
            if o.end == real {
                continue;
            }
            let content: Vec<String> = o.steps.iter().map(|s| s.to_string()).collect();
            let real_text = self.step_text(o.plan, o.block, real, robot);
            let how = if changed {
                format!("the context first changes at {real_text}")
            } else {
                format!("the context does not change before the body ends at {real_text}")
            };
            out.push(if o.end < real {
                Violation {
                    check: "content-covers",
                    span: o.span,
                    message: format!(
                        "the explanation of {} ends at {}, but {how}: it does not cover the step that changes the context (given: ({}); demanded: up to {real_text})",
                        o.action,
                        content.last().map_or("", String::as_str),
                        content.join(", ")
                    ),
                }
            } else {
                Violation {
                    check: "content-concise",
                    span: o.span,
                    message: format!(
                        "the explanation of {} runs on to {}, but {how}: the steps after it are not needed (given: ({}); demanded: up to {real_text})",
                        o.action,
                        content.last().map_or("", String::as_str),
                        content.join(", ")
                    ),
                }
            });
        }
    }

    /// Whether a literal of the context `o` explained has another truth on `beliefs` than
    /// when the explanation was given.
    fn context_changed(&self, o: &Obligation, beliefs: &AtomSet) -> bool {
        (o.atoms.0.truths(&o.gamma, beliefs).zip(&o.truth)).any(|(now, then)| now != *then)
    }

    /// The atoms an instance of `atom` may be ([`Explainer::instances`]), kept per atom:
    /// each explanation given asks, and finding them anew (a term built and unified per
    /// atom of the predicate) costs.
    fn instances(&self, atom: &Term) -> Arc<[AtomId]> {
        let hash = quick(atom);
        if let Some(v) = shard(&self.tables.instances, hash).get(atom) {
            return v.clone();
        }
        let v: Arc<[AtomId]> = self.ex.instances(atom).into();
        shard(&self.tables.instances, hash)
            .entry(atom.clone())
            .or_insert(v)
            .clone()
    }

    /// The transition from `s` in which agent `agent` did `notes`, to `next`; `sensed`:
    /// the robot's beliefs after the sense that begins its cycle, when this is a cycle of
    /// the robot that began by perceiving or reading something.
    fn transition(
        &self,
        s: &ExplainedState<W::State>,
        agent: u8,
        notes: W::Notes,
        next: W::State,
        sensed: Option<&AtomSet>,
    ) -> (Step<W::Notes>, ExplainedState<W::State>) {
        let mut step = Step {
            agent,
            notes: W::Notes::default(),
            given: None,
            violations: Vec::new(),
        };
        let view = self.view_of(s);
        // Another agent's step (a cycle, or a request to it): the user sees none of it,
        // and the robot's state does not change. A step of the robot that the user does
        // not see (no request, no plan adopted, no action, no failure) and that leaves no
        // explanation to judge and every mark in place leaves the view as it was.
        let unseen = agent as usize != self.runs.robot()
            || (sensed.is_none()
                && view.open.is_empty()
                && !(self.runs.shown(&notes)).unwrap_or_else(|| notes.notes().any(shown))
                && self.marks_alive((s.view, view), &next));
        if unseen {
            step.notes = notes;
            let view = s.view;
            return (step, ExplainedState { state: next, view });
        }
        let before = &s.state;
        let seen = match (sensed, self.runs.notes_key(&notes)) {
            (None, Some(key)) => {
                let at = s.view as usize;
                let beliefs = Some(self.runs.beliefs_key(before));
                // Most notes do not read the beliefs (no explanation is due): one entry for
                // every state then.
                let first = || SeenKey(at, key.clone(), SmallVec::new());
                let see = || self.see(view, before, &notes, None, beliefs);
                let seen = match key.as_slice() {
                    &[word] => recently(
                        &SEEN_RECENTLY,
                        READ_RECENTLY,
                        (self.serial, (at, word)),
                        || Kept::seen(memo(&self.tables.seen, first(), see), &self.tables),
                        |s| s.read_unless_due(),
                    ),
                    _ => memo_read(&self.tables.seen, first(), see, |s| s.read_unless_due()),
                };
                match seen {
                    Ok(seen) => seen,
                    Err(due) => {
                        // The due notes are the same on every state; their explanations differ
                        // on far fewer states than the beliefs do.
                        let believed = self.runs.robot_beliefs(before);
                        let given = due
                            .iter()
                            .filter_map(|&i| match notes.notes().nth(i as usize)? {
                                note @ Note::Action { stack, .. } => {
                                    let key = (note as *const Note as usize, beliefs?);
                                    Some(self.given_key(key, believed, stack))
                                }
                                _ => None,
                            })
                            .collect::<SmallVec<[usize; 2]>>();
                        let see = || self.see(view, before, &notes, None, beliefs);
                        match (key.as_slice(), given.as_slice()) {
                            (&[word], g) if g.len() <= 2 => {
                                let nth = |k: usize| g.get(k).copied().unwrap_or(0);
                                let words = [g.len(), nth(0), nth(1)];
                                recently(
                                    &DUE_RECENTLY,
                                    READ_RECENTLY,
                                    (self.serial, (at, word, words)),
                                    || {
                                        let seen = memo(
                                            &self.tables.seen,
                                            SeenKey(at, key.clone(), given.clone()),
                                            see,
                                        );
                                        Kept::seen(seen, &self.tables)
                                    },
                                    |s| s.read(),
                                )
                            }
                            _ => memo_read(&self.tables.seen, SeenKey(at, key, given), see, |s| {
                                s.read()
                            }),
                        }
                    }
                }
            }
            (sensed, _) => self.see(view, before, &notes, sensed, None).read(),
        };
        step.given = seen.given;
        step.violations = seen.violations;
        step.notes = notes;
        if seen.quiet == Some(true) {
            return (
                step,
                ExplainedState {
                    state: next,
                    view: seen.view,
                },
            );
        }
        let after = self.tables.view(seen.view);
        if after.open.is_empty() && self.marks_alive((seen.view, after), &next) {
            return (
                step,
                ExplainedState {
                    state: next,
                    view: seen.view,
                },
            );
        }
        let unsensed = self.runs.to_sense(&next);
        let judged = match self.runs.intentions_key(&next) {
            Some(key) => {
                // Judging reads the beliefs only through whether each open explanation's
                // context changed (see `judge`).
                let beliefs = self.runs.robot_beliefs(&next);
                let changed: SmallVec<[bool; 4]> = after
                    .open
                    .iter()
                    .map(|o| self.context_changed(o, beliefs))
                    .collect();
                let at = seen.view as usize;
                let after = || self.after(seen.view, &next, seen.failed, unsensed);
                let read = |judged: &Arc<Judged>| (judged.0, judged.1.clone());
                match (
                    key.as_slice(),
                    judged_flags(seen.failed, unsensed, &changed),
                ) {
                    (&[word], Some(flags)) => recently(
                        &JUDGED_RECENTLY,
                        READ_RECENTLY,
                        (self.serial, (at, flags, word)),
                        || {
                            let judged = memo(
                                &self.tables.judged,
                                JudgedKey(at, seen.failed, unsensed, changed.clone(), key.clone()),
                                after,
                            );
                            match judged.1.is_empty() {
                                true => Ok(judged.0),
                                false => Err(judged),
                            }
                        },
                        |kept| kept.as_ref().map_or_else(read, |&view| (view, Vec::new())),
                    ),
                    _ => memo_read(
                        &self.tables.judged,
                        JudgedKey(at, seen.failed, unsensed, changed, key),
                        after,
                        read,
                    ),
                }
            }
            None => self.after(seen.view, &next, seen.failed, unsensed),
        };
        step.violations.extend(judged.1);
        (
            step,
            ExplainedState {
                state: next,
                view: judged.0,
            },
        )
    }

    /// The view `view` after a transition to `next` (the robot's state): its open
    /// explanations judged, its marks of frames gone dropped.
    fn after(
        &self,
        view: u32,
        next: &W::State,
        failed: bool,
        unsensed: bool,
    ) -> (u32, Vec<Violation>) {
        let mut violations = Vec::new();
        let before = self.tables.view(view);
        let mut st = before.clone();
        self.judge(
            &mut st.open,
            (next, self.runs.robot_beliefs(next)),
            failed,
            unsensed,
            &mut violations,
        );
        // Marks of frames that are gone (finished or failed) can never be executed.
        st.marks.retain(|m| self.alive(m, next));
        let view = if st == *before {
            view
        } else {
            self.tables.intern(st)
        };
        (view, violations)
    }

    /// What the robot's `notes` make of the user's `view`, the robot's state before them
    /// being `before` (`sensed`: its beliefs after the sense that began its cycle, when it
    /// perceived or read something).
    fn see(
        &self,
        view: &View,
        before: &W::State,
        notes: &W::Notes,
        sensed: Option<&AtomSet>,
        beliefs_key: Option<usize>,
    ) -> Seen {
        let mut st = view.clone();
        let mut violations = Vec::new();
        let mut given_at = Vec::new();
        // What the robot believes when its cycle acts: what it sensed at the start of it.
        let believed = sensed.unwrap_or(self.runs.robot_beliefs(before));
        if let Some(b) = sensed {
            // What changed since its last cycle (its last action's effects, what others
            // did) counts for the step that was running then.
            self.judge(&mut st.open, (before, b), false, false, &mut violations);
        }
        let mut failed = false;
        let mut reads_beliefs = sensed.is_some();
        let mut due = SmallVec::new();
        for (i, note) in notes.notes().enumerate() {
            let mut given = None;
            match note {
                Note::Request { index } => {
                    let goal = self.sem().requests[*index as usize].clone();
                    let obs = Observation::Request(goal);
                    st.n.observe(st.prev.as_ref(), &obs);
                    st.prev = Some(obs);
                }
                Note::Plan {
                    plan,
                    origin,
                    subst,
                    depth,
                } => self.adopt(&mut st, *plan, *origin, subst, *depth),
                Note::Action {
                    term,
                    stack,
                    plan,
                    span,
                    origin,
                    ..
                } => {
                    if self.sem().is_emission(term) {
                        st.emitted = Some(term.clone());
                    } else {
                        // The note (shared) and the beliefs identify the explanation.
                        let key = beliefs_key.map(|b| (note as *const Note as usize, b));
                        let mut read = false;
                        given = self.action(
                            (believed, &mut read, key),
                            &mut st,
                            term,
                            stack,
                            *plan,
                            *span,
                            *origin,
                            &mut violations,
                        );
                        if read {
                            reads_beliefs = true;
                            due.push(i as u32);
                        }
                    }
                }
                Note::ActionFailed { .. } | Note::GoalFailed { .. } => failed = true,
                _ => {}
            }
            if given.is_some() {
                given_at.resize(i, None);
                given_at.push(given);
            }
        }
        Seen {
            view: self.tables.intern(st),
            given: (!given_at.is_empty()).then(|| given_at.into()),
            violations,
            failed,
            reads_beliefs,
            due,
        }
    }

    /// Whether every mark of `view` (numbered `number`) is of a frame still on one of the
    /// robot's intentions in `s` ([`Explained::alive`]).
    fn marks_alive(&self, (number, view): (u32, &View), s: &W::State) -> bool {
        if view.marks.is_empty() {
            return true;
        }
        let all = || view.marks.iter().all(|m| self.alive(m, s));
        match self.runs.intentions_key(s).as_deref() {
            // Read on most of a user's transitions (perf: walking the intentions for each
            // mark was 5% of the newcomer's search at 6 cups), for few distinct pairs.
            Some(&[word]) => recently(
                &ALIVE_RECENTLY,
                READ_RECENTLY,
                (self.serial, (number, word)),
                all,
                |&alive| alive,
            ),
            _ => all(),
        }
    }

    /// Whether the frame of the mark `m` is still on one of the robot's intentions in `s`.
    fn alive(&self, m: &Mark, s: &W::State) -> bool {
        self.runs.robot_intentions(s).any(|i| {
            i.origin == m.origin
                && i.frames
                    .get(m.depth as usize)
                    .is_some_and(|f| f.plan == m.plan)
        })
    }

    /// An executed environment action: demand, adoption marks, content, conformance.
    #[allow(clippy::too_many_arguments)]
    fn action(
        &self,
        (believed, read, key): (&AtomSet, &mut bool, Option<(usize, usize)>),
        st: &mut View,
        term: &Term,
        stack: &[crate::semantics::FrameView],
        plan: u32,
        span: Span,
        origin: Origin,
        out: &mut Vec<Violation>,
    ) -> Option<GivenExplanation> {
        let obs = Observation::Action(term.clone());
        let prev = st.prev.clone();
        // For messages only.
        let after = || {
            prev.as_ref()
                .map_or("the start".to_string(), |o| o.to_string())
        };
        // Declaratively: novel when no pair of N matches, pair by pair.
        let novel = !st
            .n
            .initial()
            .iter()
            .any(|p| p.matches(prev.as_ref(), &obs))
            && !st
                .n
                .learned()
                .iter()
                .any(|p| p.prev == prev && p.next == obs);
        // `N` as it was (its pairs shared, not copied).
        let before = st.n.clone();
        let due = st.n.observe(prev.as_ref(), &obs);
        let pair = novel.then(|| Pair {
            prev: prev.clone(),
            next: obs.clone(),
        });
        st.prev = Some(obs);
        if due != novel || !grew_by(before.learned(), st.n.learned(), pair.as_ref()) {
            out.push(Violation {
                check: "demand-exact",
                span,
                message: format!(
                    "at {term} after {}, Algorithm 1 {} an explanation and N has {} learned pairs, but the pair is {} and N should have {}",
                    after(),
                    if due { "gave" } else { "gave no" },
                    st.n.learned().len(),
                    if novel { "novel" } else { "expected" },
                    before.learned().len() + usize::from(novel)
                ),
            });
        }
        // The paper's Algorithm 1 marked this action at adoption, or not.
        let depth = stack.len().saturating_sub(1) as u16;
        let (block, pos) = stack.last().map_or((0, 0), |f| f.at);
        let marked = block == 0
            && st
                .marks
                .iter()
                .position(|m| {
                    m.origin == origin && m.depth == depth && m.plan == plan && m.pos == pos
                })
                .map(|i| st.marks.remove(i))
                .is_some();
        if marked != due {
            out.push(Violation {
                check: "demand-adoption",
                span,
                message: format!(
                    "{term} after {} {} by the observed sequence, but Algorithm 1 at plan adoption {} it",
                    after(),
                    if due { "is surprising" } else { "is expected" },
                    if marked { "marked" } else { "did not mark" }
                ),
            });
        }
        let emitted = st.emitted.take();
        *read |= due;
        let explained = due.then(|| match key {
            Some(key) => self.explained(key, believed, stack),
            None => Arc::new(self.explain(believed, stack)),
        });
        let explanation = explained.as_deref().and_then(Option::as_ref);
        if self.sem().explains_itself() {
            self.conformance(
                term,
                &after(),
                emitted.as_ref(),
                explanation.map(|(e, _)| &*e.content),
                span,
                out,
            );
        }
        let (e, truth) = explanation?;
        let false_now: Vec<String> = e
            .content
            .context
            .iter()
            .zip(truth)
            .filter(|(_, t)| !**t)
            .map(|(l, _)| l.to_string())
            .collect();
        if !false_now.is_empty() {
            out.push(Violation {
                check: "content-truthful",
                span,
                message: format!(
                    "the explanation of {term} gives the context {}, but {} {} not believed when it is given",
                    e.content,
                    false_now.join(", "),
                    if false_now.len() == 1 { "is" } else { "are" }
                ),
            });
        }
        let given = GivenExplanation {
            action: term.clone(),
            after: prev,
            content: e.content.clone(),
        };
        let open = || {
            Hashed::new(Obligation {
                origin,
                depth,
                plan,
                block: e.block,
                from: pos,
                end: *e.positions.last().unwrap_or(&pos),
                last: e.last,
                gamma: e.content.context.clone(),
                atoms: Unhashed(LiteralAtoms(
                    (e.content.context.iter())
                        .map(|l| self.instances(&l.atom))
                        .collect(),
                )),
                truth: truth.clone(),
                action: term.clone(),
                span,
                steps: e.content.actions.clone(),
            })
        };
        // The note and the interned explanation make the obligation: one value for them,
        // shared by every view that has it.
        st.open.push(match (key, &explained) {
            (Some((note, _)), Some(j)) => {
                let at = Arc::as_ptr(j) as *const () as usize;
                memo_read(&self.tables.obligations, (note, at), open, |o| {
                    (**o).clone()
                })
            }
            _ => open(),
        });
        Some(given)
    }

    /// A word that tells apart the explanations of the action note `key.0` on the
    /// beliefs `key.1` (`believed`): the truth of each literal of its context, one bit
    /// each, when the content is the note's alone (most often: few truths, many beliefs);
    /// else the interned explanation's address. A bit pattern is odd or zero, an address
    /// neither.
    fn given_key(
        &self,
        key: (usize, usize),
        believed: &AtomSet,
        stack: &[crate::semantics::FrameView],
    ) -> usize {
        if !self.ex.is_semantic() {
            let bits = recently(
                &CONTENTS_RECENTLY,
                READ_RECENTLY,
                (self.serial, key.0),
                || self.content(key.0, stack),
                |content| match content.as_ref() {
                    None => Some(0),
                    Some((e, atoms)) if atoms.0.len() < usize::BITS as usize - 1 => {
                        Some(truth_bits(atoms.truths(&e.content.context, believed)))
                    }
                    Some(_) => None,
                },
            );
            if let Some(bits) = bits {
                return bits;
            }
        }
        Arc::as_ptr(&self.explained(key, believed, stack)) as usize
    }

    /// Algorithm 2's explanation of the action note at address `note` (on `stack`) and
    /// the atoms of its context's literals, when its content does not read the beliefs.
    fn content(
        &self,
        note: usize,
        stack: &[crate::semantics::FrameView],
    ) -> Arc<Option<(Explanation, LiteralAtoms)>> {
        memo(&self.tables.contents, note, || {
            let e = self.ex.explain(&AtomSet::default(), stack)?;
            let atoms = (e.content.context.iter())
                .map(|l| self.instances(&l.atom))
                .collect();
            Some((e, LiteralAtoms(atoms)))
        })
    }

    /// [`Explained::explain`] of the action note `key.0` on the beliefs `key.1`,
    /// memoized and interned ([`Tables::judgeables`]).
    fn explained(
        &self,
        key: (usize, usize),
        believed: &AtomSet,
        stack: &[crate::semantics::FrameView],
    ) -> Arc<Option<Judgeable>> {
        let hash = quick(&key);
        if let Some(v) = shard(&self.tables.explained, hash).get(&key) {
            return v.clone();
        }
        let v = if self.ex.is_semantic() {
            Arc::new(self.explain(believed, stack))
        } else {
            // The content is the note's: only the truths are the beliefs'.
            let content = self.content(key.0, stack);
            Arc::new(content.as_ref().as_ref().map(|(e, atoms)| {
                let truth = atoms.truths(&e.content.context, believed).collect();
                (e.clone(), truth)
            }))
        };
        let v = {
            let mut set = shard(&self.tables.judgeables, quick(&v));
            match set.get(&v) {
                Some(old) => old.clone(),
                None => {
                    set.insert(v.clone());
                    v
                }
            }
        };
        shard(&self.tables.explained, hash)
            .entry(key)
            .or_insert(v)
            .clone()
    }

    /// Algorithm 2's explanation of the action on top of `stack`, and the truth of each
    /// literal of its `Γ` in `believed`.
    fn explain(
        &self,
        believed: &AtomSet,
        stack: &[crate::semantics::FrameView],
    ) -> Option<Judgeable> {
        let e = self.ex.explain(believed, stack)?;
        let truth = e
            .content
            .context
            .iter()
            .map(|l| self.ex.literal_holds(believed, l))
            .collect();
        Some((e, truth))
    }

    /// The agent's own explanation against the reference (see [`emitted_content`]).
    fn conformance(
        &self,
        term: &Term,
        after: &str,
        emitted: Option<&Term>,
        reference: Option<&crate::explain::Content>,
        span: Span,
        out: &mut Vec<Violation>,
    ) {
        match (emitted, reference) {
            (None, None) => {}
            (Some(e), None) => out.push(Violation {
                check: "demand-conformance",
                span,
                message: format!(
                    "the agent explains {term} after {after} with {e}, but no explanation is due"
                ),
            }),
            (None, Some(r)) => out.push(Violation {
                check: "demand-conformance",
                span,
                message: format!(
                    "{term} after {after} is surprising, but the agent gives no explanation (demanded: {r})"
                ),
            }),
            (Some(e), Some(r)) => {
                if emitted_content(e) != Some(reference_content(term, r)) {
                    out.push(Violation {
                        check: "content-conformance",
                        span,
                        message: format!(
                            "the agent explains {term} with {e}, but the reference explanation is {r}"
                        ),
                    });
                }
            }
        }
    }
}

/// Whether the sorted pairs `after` are the sorted pairs `before` with `pair` added, or
/// the same pairs when there is none to add.
fn grew_by(before: &[Pair], after: &[Pair], pair: Option<&Pair>) -> bool {
    match pair {
        None => std::ptr::eq(before, after) || before == after,
        Some(p) => {
            let at = before.partition_point(|q| q < p);
            after.len() == before.len() + 1
                && after[..at] == before[..at]
                && after[at] == *p
                && after[at + 1..] == before[at..]
        }
    }
}

/// What an explanation says, in the shape the agent's `emitted_by` action carries it: the
/// explained action, `Γ` as a set, and the steps in order.
type Carried = (String, Vec<String>, Vec<String>);

/// What `explain(Action, [L1, ...], [S1, ...])` carries: `Γ` as a list of literals in any
/// order (`not p` written `neg(p)`, since a Jason list holds terms, not formulas) and the
/// steps in order (`!g` written `achieve(g)`). `None` when it has another shape.
pub fn emitted_content(t: &Term) -> Option<Carried> {
    let [action, context, steps] = t.args() else {
        return None;
    };
    let items = |l: &Term| -> Option<Vec<String>> {
        match l.list_elements()? {
            (items, None) => Some(items.iter().map(|x| x.to_string()).collect()),
            _ => None,
        }
    };
    let mut context = items(context)?;
    context.sort();
    context.dedup();
    Some((action.to_string(), context, items(steps)?))
}

/// The reference content in the shape of [`emitted_content`].
pub fn reference_content(action: &Term, c: &crate::explain::Content) -> Carried {
    let mut context: Vec<String> = c
        .context
        .iter()
        .map(|l| {
            if l.positive {
                l.atom.to_string()
            } else {
                format!("neg({})", l.atom)
            }
        })
        .collect();
    context.sort();
    context.dedup();
    (
        action.to_string(),
        context,
        c.actions
            .iter()
            .map(|s| match s {
                PlanStep::Action(a) => a.to_string(),
                PlanStep::Subgoal(g) => format!("achieve({g})"),
            })
            .collect(),
    )
}

impl<W: Runs> Model for Explained<'_, W> {
    type State = ExplainedState<W::State>;
    type Label = Step<W::Notes>;

    fn init_complete(&self) -> bool {
        self.runs.initial_complete()
    }

    fn init_states(&self) -> Box<dyn Iterator<Item = Self::State> + '_> {
        Box::new(self.runs.initial().map(|state| self.start(state)))
    }

    fn next_states(&self, s: &Self::State) -> Vec<(Step<W::Notes>, Self::State)> {
        let mut out = Vec::new();
        self.next_states_into(s, &mut out);
        out
    }

    fn next_states_into(&self, s: &Self::State, out: &mut Vec<(Step<W::Notes>, Self::State)>) {
        // A robot that does not sense first (one agent alone never does) senses nothing
        // (`Runs::to_sense`): the transitions are made as the successors come.
        if !self.runs.to_sense(&s.state) {
            (self.runs).each_successor(&s.state, |agent, notes, next| {
                out.push(self.transition(s, agent, notes, next, None));
            });
            return;
        }
        let robot = self.runs.robot() as u8;
        let succ = self.runs.successors(&s.state);
        // A cycle of the robot, not a request to it.
        let cycle = |agent: u8, notes: &W::Notes| {
            let mut it = notes.notes();
            agent == robot && !matches!((it.next(), it.next()), (Some(Note::Request { .. }), None))
        };
        // Every cycle of the robot from `s` begins with the same sense.
        let sensed = succ
            .iter()
            .any(|(a, notes, _)| cycle(*a, notes))
            .then(|| self.runs.sensed(&s.state))
            .flatten();
        out.extend(succ.into_iter().map(|(agent, notes, next)| {
            let sensed = sensed.as_ref().filter(|_| cycle(agent, &notes));
            self.transition(s, agent, notes, next, sensed)
        }));
    }

    fn prefetch(&self, s: &Self::State, stage: usize) {
        self.runs.prefetch(&s.state, stage);
    }

    fn fingerprint(&self, s: &Self::State) -> u64 {
        let v = self.view_of(s);
        let at = s.view as usize;
        let renamed = self.runs.fingerprint_with(&s.state, |r| {
            let key = (at, SmallVec::from_slice(r.perm()));
            let known = shard(&self.tables.renamed, mix(at as u64))
                .get(&key)
                .copied();
            known.unwrap_or_else(|| {
                let h = fingerprint(&self.renamed_view(v, r));
                shard(&self.tables.renamed, mix(at as u64)).insert(key, h);
                h
            })
        });
        renamed
            .or_else(|| self.runs.fingerprint_numbered(&s.state, u64::from(s.view)))
            .unwrap_or_else(|| fingerprint(s))
    }
}

impl<'a, W: Runs> Explained<'a, W> {
    /// The parts of view `v` that a fingerprint reads, renamed by `r`.
    fn renamed_view(&self, v: &View, r: &Renaming) -> RenamedView {
        let obs = |o: &Observation| match o {
            Observation::Request(t) => Observation::Request(r.term(t)),
            Observation::Action(t) => Observation::Action(r.term(t)),
        };
        let pairs = |n: &ExpectedSuccessors| {
            let mut v: Vec<Pair> = n
                .learned()
                .iter()
                .map(|p| Pair {
                    prev: p.prev.as_ref().map(obs),
                    next: obs(&p.next),
                })
                .collect();
            v.sort();
            v
        };
        let mut marks: Vec<(Origin, u16, u32, u16)> = v
            .marks
            .iter()
            .map(|m| (r.origin(m.origin), m.depth, m.plan, m.pos))
            .collect();
        marks.sort();
        let open: Vec<Obligation> = v
            .open
            .iter()
            .map(|o| Obligation {
                origin: r.origin(o.origin),
                gamma: o
                    .gamma
                    .iter()
                    .map(|l| ContextLiteral {
                        atom: r.term(&l.atom),
                        positive: l.positive,
                    })
                    .collect(),
                action: r.term(&o.action),
                steps: o
                    .steps
                    .iter()
                    .map(|p| match p {
                        PlanStep::Action(t) => PlanStep::Action(r.term(t)),
                        PlanStep::Subgoal(t) => PlanStep::Subgoal(r.term(t)),
                    })
                    .collect(),
                ..Obligation::clone(o)
            })
            .collect();
        (
            pairs(&v.n),
            v.prev.as_ref().map(obs),
            pairs(&v.adoption),
            marks,
            open,
            v.emitted.as_ref().map(|t| r.term(t)),
        )
    }
}

/// A transition of the product graph: source state, its position among the source's
/// transitions, and the target's fingerprint.
pub type Shown = (u32, u32, u64);

/// The first violation of each check at each place, with the transition that shows it.
pub struct UserResult {
    /// The user.
    pub user: String,
    /// `(check, file, offset)` → where it shows and what it is.
    pub violations: BTreeMap<(&'static str, u32, u32), (Shown, Violation)>,
    /// Whether every reachable state of the user's search was expanded.
    pub complete: bool,
    /// States of the user's search.
    pub states: usize,
    /// Seconds the user's search took (the run again to the violations included).
    pub seconds: f64,
    /// Explanations given on the transitions explored.
    pub given: usize,
}

/// What [`check_user`] gives: the search's results, and, when it found violations, the
/// product graph up to the last state a violation shows from, numbered, to read the runs
/// to them from ([`counterexample`]).
pub type UserSearch<S> = (UserResult, Option<Graph<ExplainedState<S>>>);

/// Explores the runs as `user` sees them and collects the violations. The search keeps
/// fingerprints alone ([`Options::numbered`]): most searches find nothing, and a run is
/// read from a user's graph only to a violation. When there are some, the search runs
/// again with numbers and parents, in the same order (the same states get the same
/// numbers), as far as the last state a violation shows from: at 6 cups, a user's
/// numbers and parents are 1.3 GB the memory of the first search does not hold.
pub fn check_user<W: Runs>(
    model: &Explained<W>,
    limits: Limits,
    opts: &Options,
    progress: impl FnMut(usize, u32, f64),
) -> UserSearch<W::State> {
    // The violations are found on the transitions as they are taken, and a counterexample
    // follows parent links: the user's graph keeps no edges (4 bytes a transition and 8 a
    // state, for searches of 100 M states at 6 cups).
    let opts = &Options {
        keep_edges: false,
        numbered: false,
        ..*opts
    };
    let (graph, violations, given) = user_search(model, limits, opts, progress);
    let mut r = UserResult {
        user: model.user.name.clone(),
        complete: graph.complete(),
        states: graph.len(),
        seconds: graph.seconds,
        violations,
        given,
    };
    drop(graph);
    let Some(last) = r.violations.values().map(|((src, _, _), _)| *src).max() else {
        return (r, None);
    };
    // Within what is left of the time the first search had (`--timeout` bounds the run).
    let again = Limits {
        max_states: limits.max_states.min(u64::from(last) + 1),
        timeout: limits.timeout.map(|t| (t - r.seconds).max(0.0)),
        ..limits
    };
    let numbered = &Options {
        numbered: true,
        ..*opts
    };
    let (graph, shown, _) = user_search(model, again, numbered, |_, _, _| {});
    r.seconds += graph.seconds;
    // The same order gives the same transitions; a bound (`--timeout`) may have cut the
    // second search short of some, whose runs are then not read.
    let same = r.violations.iter().all(|(key, (at, _))| {
        (shown.get(key)).is_some_and(|(again, _)| again == at && at.0 < graph.len() as u32)
    });
    debug_assert!(same || graph.bound == Some(super::explore::Bound::Time));
    (r, same.then_some(graph))
}

/// One search of [`check_user`]: its graph, the first violation of each check at each
/// place, and the explanations given.
#[allow(clippy::type_complexity)]
fn user_search<W: Runs>(
    model: &Explained<W>,
    limits: Limits,
    opts: &Options,
    progress: impl FnMut(usize, u32, f64),
) -> (
    Graph<ExplainedState<W::State>>,
    BTreeMap<(&'static str, u32, u32), (Shown, Violation)>,
    usize,
) {
    let mut violations = BTreeMap::new();
    let mut given = 0;
    let graph = explore_with(
        model,
        limits,
        opts,
        |_, _| (),
        |_, _, ()| {},
        |src, k, step: &Step<W::Notes>, fp| {
            given += step.given.iter().flat_map(|g| g.iter()).flatten().count();
            for v in &step.violations {
                violations
                    .entry((v.check, v.span.file.0, v.span.start))
                    .or_insert_with(|| ((src, k, fp), v.clone()));
            }
        },
        progress,
    );
    // The searching threads other than this one are gone, and their caches with them.
    SEEN_RECENTLY.with_borrow_mut(Vec::clear);
    DUE_RECENTLY.with_borrow_mut(Vec::clear);
    JUDGED_RECENTLY.with_borrow_mut(Vec::clear);
    CONTENTS_RECENTLY.with_borrow_mut(Vec::clear);
    (graph, violations, given)
}

/// The run to the violation `v`, shown by the `k`-th transition of state `src` of the
/// product graph (to a state with fingerprint `fp`), with the explanations the user got in
/// place. Under symmetry the run is a concrete one that reaches a renaming of the stored
/// states, so the last transition is found by what it violates. Among several agents,
/// every step names its agent (an explanation, the robot).
pub fn counterexample<W: Runs>(
    project: &Project,
    model: &Explained<W>,
    graph: &Graph<ExplainedState<W::State>>,
    (src, k, fp): Shown,
    v: &Violation,
) -> Counterexample {
    let path = graph.path_to(src);
    let mut labels: Vec<Step<W::Notes>> = Vec::new();
    let mut initial = Vec::new();
    if let Some(mut walk) = Walk::start(model, graph, path[0]) {
        initial = model
            .runs
            .world(&walk.state.state)
            .iter()
            .map(|a| project.atoms.display(a, &project.universe))
            .collect();
        for &j in &path[1..] {
            labels.extend(walk.step_to(j));
        }
        labels.extend(walk.step_by(k, fp, |l: &Step<W::Notes>| {
            l.violations
                .iter()
                .any(|w| w.check == v.check && w.span == v.span)
        }));
    }
    let (requests, steps, _) = render(model, &labels, None);
    Counterexample {
        initial,
        requests,
        steps,
        loop_start: None,
    }
}

/// The run of a run property's violation on a user's explanation search (`check::runs`):
/// each step the transition at the position the product took, then the loop if there is
/// one, with the explanations the user got in place. Among several agents, every step
/// names its agent (an explanation, the robot).
pub(crate) fn counterexample_via<W: Runs>(
    project: &Project,
    model: &Explained<W>,
    graph: &Graph<ExplainedState<W::State>>,
    v: &super::runs::Violation,
) -> Counterexample {
    let mut labels: Vec<Step<W::Notes>> = Vec::new();
    let mut initial = Vec::new();
    let mut loop_label = None;
    if let Some(mut walk) = v.path.first().and_then(|&i| Walk::start(model, graph, i)) {
        initial = model
            .runs
            .world(&walk.state.state)
            .iter()
            .map(|a| project.atoms.display(a, &project.universe))
            .collect();
        for (&j, &k) in v.path[1..].iter().zip(&v.path_via) {
            labels.extend(walk.step_by(k, graph.fingerprint(j), |_| true));
        }
        if v.cycle.len() >= 2 {
            loop_label = Some(labels.len());
            for (&j, &k) in v.cycle[1..].iter().zip(&v.cycle_via) {
                labels.extend(walk.step_by(k, graph.fingerprint(j), |_| true));
            }
        }
    }
    let (requests, steps, loop_start) = render(model, &labels, loop_label);
    Counterexample {
        initial,
        requests,
        steps,
        loop_start,
    }
}

/// The requests and trace steps of the transitions `labels` of a user's search, with the
/// explanations the user got in place (among several agents every step names its agent),
/// and where the steps of the transition `loop_label` begin.
fn render<W: Runs>(
    model: &Explained<W>,
    labels: &[Step<W::Notes>],
    loop_label: Option<usize>,
) -> (Vec<String>, Vec<TraceStep>, Option<usize>) {
    let user = model.user;
    let agents = model.runs.agents();
    let names = model.runs.names();
    let name = |k: usize| names.map(|n| n[k].clone());
    let mut builders: Vec<Builder> = agents
        .iter()
        .map(|sem| Builder::new(sem.project, sem))
        .collect();
    let mut steps: Vec<TraceStep> = Vec::new();
    let mut requests = Vec::new();
    let mut loop_start = None;
    for (at, l) in labels.iter().enumerate() {
        if Some(at) == loop_label {
            loop_start = Some(steps.len());
        }
        let mover = l.agent as usize;
        for (i, note) in l.notes.notes().enumerate() {
            if let Note::Request { index } = note {
                requests.push(agents[mover].requests[*index as usize].to_string());
            }
            if let Some(g) = l.given_at(i) {
                let text = g.text(model.ex);
                steps.push(TraceStep {
                    kind: StepKindTag::Explanation,
                    text: format!("to {}: {text} {}", user.name, g.content),
                    intention: None,
                    plan: None,
                    added: Vec::new(),
                    removed: Vec::new(),
                    explanation: Some(text),
                    agent: name(model.runs.robot()),
                });
            }
            let b = &mut builders[mover];
            let before = b.steps().len();
            b.push(vec![note.clone()]);
            for mut st in b.steps()[before..].iter().cloned() {
                st.agent = name(mover);
                steps.push(st);
            }
        }
    }
    (requests, steps, loop_start)
}

/// The explanation properties for every user of the manifest, on the runs of one agent:
/// one finding per property and user when it holds (or is undecided), one per property,
/// user and place when it fails. Nothing when the manifest has no `[explanation]` users.
/// Also returns whether every user's search was complete.
/// With `compiled` (the agent's compiled cycle, whose tables the agent's search filled),
/// the users' searches run on it; with `stored` (the agent's graph, from an exact search),
/// they read that graph instead. `spare` is work for a core the users' searches leave
/// (done at once, on a thread of its own) or free (done on the thread of the search that
/// ended); it is called once per such core.
#[allow(clippy::too_many_arguments)]
pub fn verify(
    project: &Project,
    sem: &Semantics,
    (compiled, stored): (Option<&Compiled>, Option<AloneStored>),
    symmetry: Option<&Symmetry>,
    limits: Limits,
    opts: &Options,
    progress: &mut dyn FnMut(&str, usize, u32, f64),
    spare: &(dyn Fn() + Sync),
) -> Result<(Vec<Finding>, bool, Vec<Phase>), Vec<Diagnostic>> {
    if let Some(stored) = stored.filter(|_| symmetry.is_none()) {
        // A user meets every agent state, with one view or more: 1.5-1.7 on the kitchen's
        // (2-6 cups), so room for 1.7 (a table up to 7/8 full holds 1.94 before it grows).
        let opts = &Options {
            room_for: stored.graph.len().saturating_mul(17) / 10,
            places: stored.graph.len(),
            ..*opts
        };
        return verify_runs(project, stored, limits, opts, progress, spare);
    }
    match compiled {
        Some(compiled) => verify_runs(
            project,
            AloneCompiled::new(compiled, symmetry),
            limits,
            opts,
            progress,
            spare,
        ),
        None => verify_runs(
            project,
            Alone { sem, symmetry },
            limits,
            opts,
            progress,
            spare,
        ),
    }
}

/// The explanation properties on every interleaving of the agents of `projects` (those of
/// `system`), for the users of the manifest, who watch the agent `[explanation] robot`
/// names (the first when it names none, as in a project of one agent).
pub fn verify_among(
    projects: &[Project],
    system: &System,
    limits: Limits,
    opts: &Options,
    progress: &mut dyn FnMut(&str, usize, u32, f64),
) -> Result<(Vec<Finding>, bool, Vec<Phase>), Vec<Diagnostic>> {
    let robot = robot_of(projects);
    verify_runs(
        &projects[robot],
        Among { system, robot },
        limits,
        opts,
        progress,
        &|| {},
    )
}

/// The index of the agent `[explanation] robot` names among `projects` (0 when none).
pub fn robot_of(projects: &[Project]) -> usize {
    projects[0]
        .manifest
        .explanation
        .as_ref()
        .and_then(|e| e.robot.as_ref())
        .and_then(|r| projects.iter().position(|p| p.name == r.value))
        .unwrap_or(0)
}

/// The explanation properties on `runs`, for the users of `project`'s manifest (the
/// robot's project). `spare`: as [`verify`]'s.
fn verify_runs<W: Runs + Clone>(
    project: &Project,
    runs: W,
    limits: Limits,
    opts: &Options,
    progress: &mut dyn FnMut(&str, usize, u32, f64),
    spare: &(dyn Fn() + Sync),
) -> Result<(Vec<Finding>, bool, Vec<Phase>), Vec<Diagnostic>> {
    let Some(section) = &project.manifest.explanation else {
        return Ok((Vec::new(), true, Vec::new()));
    };
    let users = crate::explain::agent::users(project, None)?;
    let sem = &runs.agents()[runs.robot()];
    let ex = Explainer::new(project, sem);
    let checks: &[&str] = if section.emitted_by.is_some() {
        &CHECKS
    } else {
        &CHECKS[..5]
    };
    let mut out = Vec::new();
    let mut complete = true;
    let mut phases = Vec::new();
    let models: Vec<Explained<W>> = (users.iter())
        .map(|user| Explained::watching(runs.clone(), &ex, user))
        .collect();
    let names: Vec<String> = (users.iter())
        .map(|u| format!("explanation:{}", u.name))
        .collect();
    // The users' searches run side by side: each is bound by its merging thread, and
    // together they keep the cores busy. The progress shown is the first one's, named
    // after them all. `--timeout` bounds each, as it does the whole run.
    let label = names.join(", ");
    // The cores are shared out among the users' searches: on two cores with two users,
    // each search expanding its own states on its merging thread took 9-12% less time than
    // two searches with two workers each (4-cup kitchen, and the 6-cup store-cup library).
    let threads = opts.threads;
    let opts = &Options {
        threads: (threads / users.len().max(1)).max(1),
        ..*opts
    };
    // The work waiting for a core (`spare`) runs next on each search's thread, in the
    // memory the search leaves (its graph is kept only to read runs to violations from).
    let results: Vec<UserSearch<W::State>> = std::thread::scope(|scope| {
        let left: Vec<_> = (users.len()..threads).map(|_| scope.spawn(spare)).collect();
        // Each search's thread keeps its array by place when the search drops it, for the
        // products' index (`runs::Scratch::head`), and gives it back after the spare work.
        let others: Vec<_> = (models.iter().skip(1))
            .map(|m| {
                scope.spawn(move || {
                    let keeping = super::slots::Keeping::start();
                    let r = check_user(m, limits, opts, |_, _, _| {});
                    spare();
                    drop(keeping);
                    r
                })
            })
            .collect();
        let first = models.first().map(|m| {
            let keeping = super::slots::Keeping::start();
            let r = check_user(m, limits, opts, |n, d, t| progress(&label, n, d, t));
            spare();
            drop(keeping);
            r
        });
        // A panic in the spare work is re-raised here, as a search thread's is.
        for h in left {
            h.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
        }
        // A panic in another user's search is re-raised here, as a search thread's is.
        (first.into_iter())
            .chain(
                others
                    .into_iter()
                    .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))),
            )
            .collect()
    });
    for (((user, model), (r, graph)), phase) in users.iter().zip(&models).zip(&results).zip(&names)
    {
        // Among several agents, the message says whom the user watches.
        let who = match runs.names().filter(|n| n.len() > 1) {
            Some(names) => format!("{}, watching {}", user.name, names[runs.robot()]),
            None => user.name.clone(),
        };
        complete &= r.complete;
        let states = r.states;
        phases.push(Phase {
            name: phase.clone(),
            seconds: r.seconds,
            states: Some(states),
            beside: names.iter().filter(|n| *n != phase).cloned().collect(),
        });
        for check in checks {
            let mut failed = false;
            for ((c, _, _), (shown, v)) in &r.violations {
                if c != check {
                    continue;
                }
                failed = true;
                let loc = project.map.location(v.span);
                out.push(Finding {
                    id: format!("{check}:{}:{}:{}", user.name, loc.file, loc.line),
                    check: check.to_string(),
                    severity: Severity::Error,
                    status: Status::Fail,
                    message: format!("for {who}: {}", v.message),
                    location: Some(loc),
                    counterexample: (graph.as_ref())
                        .map(|g| counterexample(project, model, g, *shown, v)),
                    span: Some(v.span),
                    related: Vec::new(),
                    suppressed: None,
                });
            }
            if failed {
                continue;
            }
            let (status, message) = if r.complete {
                (
                    Status::Pass,
                    format!(
                        "for {who}: holds on every run ({states} states with the user's N, {} explanations given)",
                        r.given
                    ),
                )
            } else {
                (
                    Status::Unknown,
                    format!(
                        "for {who}: holds on the {states} states reached with the user's N, but the search was cut short"
                    ),
                )
            };
            out.push(Finding {
                id: format!("{check}:{}", user.name),
                check: check.to_string(),
                severity: Severity::Error,
                status,
                message,
                location: Some(project.map.location(user.span)),
                counterexample: None,
                span: Some(user.span),
                related: Vec::new(),
                suppressed: None,
            });
        }
    }
    crate::check::done_with((results, models));
    Ok((out, complete, phases))
}

#[cfg(test)]
mod tests {
    /// A graph's words are held in 6 bytes while each fits, and all in 8 from the first
    /// that does not (a belief base more than 16 GiB below the first one's, or an agenda
    /// numbered 2^16): either way, each is read back as it was pushed.
    #[test]
    fn state_words_are_short_until_one_is_not() {
        // A word: the belief base's address divided by 8, and the agenda's number above
        // its 44 bits (`Words::word`).
        let word = |address: u64, rest: u64| address >> 3 | rest << 44;
        let first = 0x7f12_3456_7000;
        let words: Vec<u64> = (0..300_000u64)
            .map(|k| word(first + (k * 13_331 % (1 << 30)) * 8, k % 9_000))
            .collect();
        for (extra, short) in [
            (word(first + (1 << 33), 65_535), true),
            (word(first - (1 << 33), 3), true),
            (word(first - (1 << 34) - 8, 3), false),
            (word(first, 1 << 16), false),
        ] {
            let mut held = super::StateWords::default();
            for &w in words.iter().chain([&extra]) {
                held.push(w).expect("memory");
            }
            assert_eq!(
                matches!(held, super::StateWords::Short(..)),
                short,
                "{extra:x}"
            );
            assert_eq!(held.len(), words.len() + 1);
            for (i, &w) in words.iter().chain([&extra]).enumerate() {
                assert_eq!(held.get(i), w, "{extra:x}: word {i}");
            }
        }
    }

    /// A user's frontier on the agent's stored graph holds millions of entries (a state's
    /// number and the state: 8.7 M at 6 cups): a node keeps its word whole and packed,
    /// so that an entry takes 20 bytes instead of 32.
    #[test]
    fn a_frontier_entry_on_the_stored_graph_takes_20_bytes() {
        use super::{ExplainedState, Node};
        assert_eq!(std::mem::size_of::<Node<'static>>(), 12);
        assert_eq!(
            std::mem::size_of::<(u32, ExplainedState<Node<'static>>)>(),
            20
        );
    }

    /// The word that stands for a judged transition's failure, sense and changes in the
    /// threads' caches tells every two of them apart (of one view: as many changes), and
    /// is refused where they would not fit.
    #[test]
    fn judged_flags_tell_every_judgement_apart() {
        use super::judged_flags;
        for open in 0..6usize {
            let mut seen = std::collections::HashSet::new();
            for bits in 0..1usize << (open + 2) {
                let changed: Vec<bool> = (0..open).map(|k| bits >> (k + 2) & 1 == 1).collect();
                let flags = judged_flags(bits & 1 == 1, bits & 2 == 2, &changed);
                assert!(seen.insert(flags.expect("fits")), "{open} {bits}");
            }
        }
        assert!(judged_flags(true, false, &[true; 62]).is_some());
        assert_eq!(judged_flags(true, false, &[true; 63]), None);
    }

    /// Under symmetry, a user's state's fingerprint takes the renamed view's hash from a
    /// memo per view and renaming: on a walk of the kitchen's users' searches (two cups,
    /// both renamings met), each is the one made without the memo.
    #[test]
    fn renamed_views_are_remembered_per_view_and_renaming() {
        use super::*;
        use crate::check::model::Model;
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
        let project = crate::model::project::load_project(&root).expect("the kitchen loads");
        let sem = Semantics::new(&project).expect("the semantics");
        let sym = Symmetry::new(&project, &sem)
            .expect("symmetry is sound here")
            .expect("the kitchen declares symmetry");
        let compiled = Compiled::new(&sem).expect("a local library");
        let ex = crate::explain::agent::Explainer::new(&project, &sem);
        let users = crate::explain::agent::users(&project, None).expect("the users");
        let renamed = std::cell::Cell::new(0usize);
        for user in &users {
            let model = Explained::watching(AloneCompiled::new(&compiled, Some(&sym)), &ex, user);
            let mut seen = std::collections::HashSet::new();
            let mut queue: std::collections::VecDeque<_> = model.init_states().take(20).collect();
            while let Some(s) = queue.pop_front() {
                if seen.len() == 3_000 || !seen.insert(model.fingerprint(&s)) {
                    continue;
                }
                let direct = sym.fingerprint_with_compiled(&compiled, &s.state, |r| {
                    let moves = r.perm().iter().enumerate().any(|(i, &x)| x as usize != i);
                    renamed.set(renamed.get() + usize::from(moves));
                    fingerprint(&model.renamed_view(model.view_of(&s), r))
                });
                assert_eq!(model.fingerprint(&s), direct, "{}", user.name);
                queue.extend(model.next_states(&s).into_iter().map(|(_, t)| t));
            }
        }
        assert!(renamed.get() > 100, "{} renamed views", renamed.get());
    }

    /// Whether a view's marks are all alive in a state is read from the threads' cache by
    /// the view's number and the robot's agenda: for views met on walks of the kitchen's
    /// users' searches on its stored graph, each with states of the graph its marks may
    /// be dead in, asked twice in turns for both users on one thread (one cache for
    /// both), the cached answer is the one found by walking the intentions.
    #[test]
    fn marks_alive_are_remembered_per_view_and_agenda() {
        use super::*;
        use crate::check::{model::Agent, stored_search};
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
        let project = crate::model::project::load_project(&root).expect("the kitchen loads");
        let sem = Semantics::new(&project).expect("the semantics");
        let compiled = Compiled::new(&sem).expect("a local library");
        let agent = Agent {
            sem: &sem,
            symmetry: None,
        };
        let (stored, graph) = stored_search(&agent, &compiled, 1);
        let runs = AloneStored::new(&compiled, &stored, &graph).expect("every state held");
        let ex = crate::explain::agent::Explainer::new(&project, &sem);
        let users = crate::explain::agent::users(&project, None).expect("the users");
        let models: Vec<_> = (users.iter())
            .map(|user| Explained::watching(runs, &ex, user))
            .collect();
        // Per user, a state of each view met with marks.
        let mut marked: Vec<BTreeMap<u32, ExplainedState<Node>>> = vec![BTreeMap::new(); 2];
        for (k, model) in models.iter().enumerate() {
            let mut seen = HashSet::new();
            let mut queue: std::collections::VecDeque<_> = model.init_states().collect();
            while let Some(s) = queue.pop_front() {
                if seen.len() == 50_000 || !seen.insert(model.fingerprint(&s)) {
                    continue;
                }
                if !model.view_of(&s).marks.is_empty() {
                    marked[k].entry(s.view).or_insert_with(|| s.clone());
                }
                queue.extend(model.next_states(&s).into_iter().map(|(_, t)| t));
            }
        }
        // Every 97th state of the graph, and each view's own state's successors.
        let sample: Vec<u32> = (0..graph.len() as u32).step_by(97).collect();
        let (mut asked, mut dead) = (0, 0);
        for round in 0..2 {
            for (k, model) in models.iter().enumerate() {
                for (&number, s) in &marked[k] {
                    let view = model.view_of(s);
                    let nodes = (sample.iter().map(|&i| runs.node(i)))
                        .chain(runs.successors(&s.state).into_iter().map(|(_, _, t)| t));
                    for node in nodes {
                        let direct = view.marks.iter().all(|m| model.alive(m, &node));
                        assert_eq!(model.marks_alive((number, view), &node), direct, "{round}");
                        asked += 1;
                        dead += usize::from(!direct);
                    }
                }
            }
        }
        assert!(asked > 1_000 && dead > 100, "{asked} asked, {dead} dead");
    }

    /// Under symmetry a user's search stores exactly one state per class: as many states
    /// as the exact search's reachable pairs of agent state and view have orbits under the
    /// whole group of renamings. Each orbit is named here by the least hash of all its
    /// renamings: the unpacked state renamed whole, the view by `renamed_view` (the
    /// search's own renaming of views), without the canonical sort's choice of renamings,
    /// the compiled images or the memo of renamed views that the search uses. (A memo keyed
    /// by the view alone, not the renaming, passed every other test; this one fails it.)
    #[test]
    fn symmetric_users_store_one_state_per_class() {
        use super::*;
        use crate::check::model::Model;
        let limits = Limits {
            max_states: 10_000_000,
            max_depth: 100_000,
            timeout: None,
        };
        let opts = Options {
            threads: 1,
            ..Options::default()
        };
        // Two cups (the group is its generator and the identity), and three (six
        // renamings from two generators).
        for (dir, renamings) in [("specs/kitchen", 2), ("tests/verify/symmetric_store", 6)] {
            let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
            let project = crate::model::project::load_project(&root).expect("the project loads");
            let sem = Semantics::new(&project).expect("the semantics");
            let sym = Symmetry::new(&project, &sem)
                .expect("symmetry is sound here")
                .expect("the project declares symmetry");
            let group = sym.group();
            assert_eq!(group.len(), renamings, "{dir}");
            let compiled = Compiled::new(&sem).expect("a local library");
            let ex = crate::explain::agent::Explainer::new(&project, &sem);
            let users = crate::explain::agent::users(&project, None).expect("the users");
            assert!(!users.is_empty(), "{dir}");
            for user in &users {
                let exact = Explained::watching(AloneCompiled::new(&compiled, None), &ex, user);
                let symmetric =
                    Explained::watching(AloneCompiled::new(&compiled, Some(&sym)), &ex, user);
                let mut seen = HashSet::new();
                let mut classes = HashSet::new();
                let mut queue: std::collections::VecDeque<_> = exact.init_states().collect();
                while let Some(s) = queue.pop_front() {
                    if !seen.insert(exact.fingerprint(&s)) {
                        continue;
                    }
                    let whole = compiled.unpack(&s.state);
                    let least = (group.iter())
                        .map(|p| {
                            let view = symmetric.renamed_view(exact.view_of(&s), &sym.renaming(p));
                            fingerprint(&(sym.renamed(&whole, p), fingerprint(&view)))
                        })
                        .min();
                    classes.insert(least);
                    queue.extend(exact.next_states(&s).into_iter().map(|(_, t)| t));
                }
                let searched = check_user(&symmetric, limits, &opts, |_, _, _| {});
                let who = format!("{dir}, {}", user.name);
                assert!(searched.0.complete, "{who}");
                assert_eq!(searched.0.states, classes.len(), "{who}");
                // Symmetry merges states here, so a search that kept them apart would show.
                assert!(classes.len() < seen.len(), "{who}");
            }
        }
    }

    /// The table of recent successors gives the compiled cycle's successors whether it is
    /// in use (most lookups hit) or bypassed (few do), twice over each state of a walk of
    /// the kitchen, and it counts one lookup in `SAMPLE`.
    #[test]
    fn a_search_of_fingerprints_alone_reads_its_runs_from_a_second_one() {
        // `check_user` searches without numbers, then again with them as far as its
        // violations: the same violations, states and counterexamples as one numbered
        // search of the whole graph, the second search no longer than it must be.
        use super::*;
        let limits = Limits {
            max_states: 10_000_000,
            max_depth: 100_000,
            timeout: None,
        };
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/paper");
        let project = crate::model::project::load_project(&root).expect("the paper loads");
        let sem = Semantics::new(&project).expect("the semantics");
        let compiled = Compiled::new(&sem).expect("a local library");
        let ex = crate::explain::agent::Explainer::new(&project, &sem);
        let users = crate::explain::agent::users(&project, None).expect("the users");
        let mut failing = 0;
        for user in &users {
            let model = Explained::watching(AloneCompiled::new(&compiled, None), &ex, user);
            let opts = Options {
                keep_edges: false,
                ..Options::default()
            };
            let (whole, violations, given) = user_search(&model, limits, &opts, |_, _, _| {});
            let (r, graph) = check_user(&model, limits, &Options::default(), |_, _, _| {});
            assert_eq!((r.states, r.complete, r.given), (whole.len(), true, given));
            assert_eq!(
                r.violations.keys().collect::<Vec<_>>(),
                violations.keys().collect::<Vec<_>>()
            );
            let Some(graph) = graph else {
                assert!(violations.is_empty(), "{}", user.name);
                continue;
            };
            failing += 1;
            let last = violations.values().map(|((src, _, _), _)| *src).max();
            assert!(graph.len() < whole.len() && Some(graph.len() as u32 - 1) >= last);
            for (key, (shown, v)) in &r.violations {
                assert_eq!(Some(shown), violations.get(key).map(|(s, _)| s));
                let a = counterexample(&project, &model, &graph, *shown, v);
                let b = counterexample(&project, &model, &whole, *shown, v);
                assert!(!a.steps.is_empty() && a.steps == b.steps, "{}", user.name);
                assert_eq!((a.initial, a.requests), (b.initial, b.requests));
            }
        }
        assert!(failing > 0, "the paper's library fails for some user");
    }

    #[test]
    fn recent_successors_are_the_cycles_used_or_bypassed() {
        use super::*;
        use std::sync::atomic::Ordering::Relaxed;
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
        let project = crate::model::project::load_project(&root).expect("the kitchen loads");
        let sem = Semantics::new(&project).expect("the semantics");
        let compiled = Compiled::new(&sem).expect("a local library");
        let mut states: Vec<Packed> = compiled.initial_iter().take(50).collect();
        let mut k = 0;
        while k < states.len() && states.len() < 2_000 {
            states.extend(compiled.successors(&states[k]).into_iter().map(|(_, t)| t));
            k += 1;
        }
        let sampled = (states.iter())
            .filter(|s| Recent::counted(s.address_hash()))
            .count();
        assert!(sampled > 0 && sampled < states.len());
        // (lookups, hits): most of them hit, and none do.
        for (counts, bypassing) in [((1_000u64 << 32) | 900, false), (1_000u64 << 32, true)] {
            let runs = AloneCompiled::new(&compiled, None);
            runs.recent.counts.store(counts, Relaxed);
            for s in states.iter().chain(&states) {
                let counted = Recent::counted(s.address_hash());
                assert_eq!(runs.recent.bypassed(s), bypassing && !counted);
                let want = compiled.successors(s);
                let got = Runs::successors(&runs, s);
                assert_eq!(got.len(), want.len());
                for ((_, n, t), (m, u)) in got.iter().zip(&want) {
                    assert!(t == u && n.key() == m.key());
                }
            }
            let counted = (runs.recent.counts.load(Relaxed) >> 32) - (counts >> 32);
            assert_eq!(counted, 2 * sampled as u64);
        }
    }

    /// `demand-exact`'s check that `N` grew by exactly the novel pair: every other change
    /// of the sorted pairs is told from it.
    #[test]
    fn grew_by_tells_the_pair_added_from_any_other_change() {
        use crate::explain::Pair;
        let p = |a: &str, b: &str| Pair::parse(a, b).expect("a pair");
        let mut all = vec![p("a", "b"), p("a", "c"), p("b", "c"), p("c", "a")];
        all.sort();
        let (before, new) = ([all[0].clone(), all[1].clone(), all[3].clone()], &all[2]);
        assert!(super::grew_by(&before, &all, Some(new)));
        assert!(super::grew_by(&before, &before, None));
        // Nothing added, another pair added, a pair dropped or swapped, two added.
        assert!(!super::grew_by(&before, &before, Some(new)));
        assert!(!super::grew_by(&before, &all, None));
        assert!(!super::grew_by(&before, &all, Some(&all[0])));
        assert!(!super::grew_by(&before, &all[1..], Some(new)));
        let swapped = [
            all[0].clone(),
            all[2].clone(),
            all[2].clone(),
            all[3].clone(),
        ];
        assert!(!super::grew_by(&before, &swapped, Some(new)));
        let mut more = all.clone();
        more.push(p("d", "a"));
        assert!(!super::grew_by(&before, &more, Some(new)));
    }

    /// Explanations with the same content share a memo entry exactly when every literal of
    /// their context has the same truth: the word must tell every vector of truths apart.
    #[test]
    fn truth_bits_tell_every_vector_of_truths_apart() {
        let mut seen = std::collections::HashMap::new();
        for len in 0..=10usize {
            for v in 0..1u32 << len {
                let w = super::truth_bits((0..len).map(|k| v >> k & 1 == 1));
                assert_eq!(w & 1, 1, "odd, so never an address");
                // The content fixes the length: per length, one word per vector.
                assert!(seen.insert((len, w), v).is_none(), "{len} literals, {v:b}");
            }
        }
        assert_eq!(super::truth_bits((0..62).map(|_| true)), usize::MAX >> 1);
    }
}
