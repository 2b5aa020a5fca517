//! Properties decided on runs ([`crate::model::property`]): `ltl` formulas, and state
//! properties that use BDI modalities. The negated formula becomes a Büchi automaton
//! ([`Buchi`]); its product with the explored graph is searched breadth-first, and a
//! violation is an accepting cycle of the product: a lasso, the run to the loop then the
//! loop. A prefix after which every continuation violates the formula (the automaton is in
//! an accepting state that accepts anything) is reported as that prefix alone, as a
//! safety violation is.
//!
//! What a run is: a path of the state graph, one reasoning cycle per step (`X` is the next
//! cycle). A run may end in a state where the agent is idle, since the user may stop asking
//! at any point (`[requests] max` is a bound), or where nothing can happen (a deadlock); a
//! run that ends repeats its last state forever, and `did` is false there. Jason's
//! round-robin scheduling of intentions is part of the cycle, so every loop of the graph is
//! a run that is fair to the intentions.

use super::buchi::Buchi;
use super::checker::Checker;
use super::chunked::{Chunked, Lists, Narrow};
use super::model::AgentState;
use super::search::{bit, set_bit};
use super::slots::Slots;
use super::store::OutOfMemory;
use crate::findings::{Finding, Status};
use crate::model::ltl::Ltl;
use crate::model::property::{Atomic, Atomics, RunProperty};
use crate::model::subst::unifier;
use crate::model::term::Term;
use crate::semantics::{Note, Semantics};
use crate::syntax::manifest::PropertyKind;
use std::collections::{HashMap, VecDeque};

/// Which runs a passing property of one agent held on: Jason's round-robin selection
/// makes every run fair to the intentions.
pub(crate) const ONE_AGENT_RUNS: &str =
    "every run (each fair to the intentions: Jason's round-robin selection)";

/// Which runs a passing property of several agents held on, with weak fairness of agents
/// (`[bounds] fairness`) or without.
pub(crate) fn agents_runs(fair: bool) -> &'static str {
    if fair {
        "every run fair to the agents (and to each one's intentions)"
    } else {
        "every run, fair to each agent's intentions but not to the agents (`[bounds] fairness`)"
    }
}

/// The propositions that hold in one state (or one step), one bit per [`Atomic`].
pub(crate) type Letter = smallvec::SmallVec<[u64; 1]>;

/// The letters of the transitions that make a proposition true (`did`), by source state and
/// position. Keyed with the quick hasher: the merging thread inserts one per such
/// transition, and SipHash was most of that.
pub(crate) type StepLetters = HashMap<(u32, u32), Letter, crate::semantics::compiled::Quick>;

/// The letters of a search's states in the order the search stored them, each distinct
/// letter kept once (few differ: a search has far more states than letters).
#[derive(Default)]
pub(crate) struct Letters {
    /// Per state: an index into `table`, in as few bytes as the indices need ([`Narrow`]),
    /// in chunks that never move: a vector of millions would be copied into fresh memory at
    /// each doubling.
    pub(crate) ids: Narrow,
    /// The distinct letters.
    pub(crate) table: Vec<Letter>,
    /// The letters of more than one word, keyed with the quick hasher.
    index: HashMap<Letter, u32, crate::semantics::compiled::Quick>,
    /// Every one-word letter: open addressing by its word, each slot the word and its
    /// index plus one (0 when empty), at most half full. At 6 cups a direct-mapped table
    /// of the recent ones missed one state in eighteen, and each miss hashed a letter
    /// into `index` on the merging thread (perf: 4% of it).
    words: Vec<(u64, u32)>,
    /// The last letter's index: a state stored after another often has its letter.
    last: Option<u32>,
    /// One-word letters met lately, by their word (direct-mapped; the index plus one, 0
    /// when empty): perf put a tenth of the merging thread of the 5-cup kitchen with
    /// `ltl` properties in the index's probes.
    recent: Vec<(u64, u32)>,
}

/// Whether two letters are equal, one-word letters (most) compared as words: `==` on
/// slices calls `memcmp`, which was a twelfth of the merging thread's time in the 6-cup
/// kitchen's search with its `ltl` properties (perf).
#[inline]
fn same(a: &[u64], b: &[u64]) -> bool {
    match (a, b) {
        ([x], [y]) => x == y,
        _ => a == b,
    }
}

/// How many one-word letters [`Letters`] keeps at hand (a power of two).
const RECENT_LETTERS: usize = 1 << 10;

impl Letters {
    /// The letter of the next state stored.
    pub(crate) fn push(&mut self, letter: Letter) {
        let id = self.id(letter);
        if self.ids.push(id).is_err() {
            // As a vector that cannot grow does.
            std::alloc::handle_alloc_error(std::alloc::Layout::new::<u32>());
        }
    }

    fn id(&mut self, letter: Letter) -> u32 {
        if let Some(id) = self
            .last
            .filter(|&id| same(&self.table[id as usize], &letter))
        {
            return id;
        }
        let word = match letter.as_slice() {
            &[w] => Some(w),
            _ => None,
        };
        let slot = word.map(|w| {
            if self.recent.is_empty() {
                self.recent = vec![(0, 0); RECENT_LETTERS];
            }
            crate::semantics::compiled::mix(w) as usize & (RECENT_LETTERS - 1)
        });
        if let (Some(w), Some(k)) = (word, slot) {
            let (known, id) = self.recent[k];
            if id != 0 && known == w {
                self.last = Some(id - 1);
                return id - 1;
            }
        }
        let next = self.table.len() as u32;
        let id = match word {
            Some(w) => self.word_id(w, next),
            None => *self.index.entry(letter.clone()).or_insert(next),
        };
        if id == next {
            self.table.push(letter);
        }
        if let (Some(w), Some(k)) = (word, slot) {
            self.recent[k] = (w, id + 1);
        }
        self.last = Some(id);
        id
    }

    /// The index of the one-word letter `w` in `words`, given `next` when it is new.
    fn word_id(&mut self, w: u64, next: u32) -> u32 {
        // Half full at most: a probe then ends after two slots on average.
        if (next as usize + 1) * 2 > self.words.len() {
            let mut grown = vec![(0, 0); (self.words.len() * 2).max(1024)];
            for &(x, id) in self.words.iter().filter(|e| e.1 != 0) {
                let at = Self::word_slot(&grown, x);
                grown[at] = (x, id);
            }
            self.words = grown;
        }
        let at = Self::word_slot(&self.words, w);
        match self.words[at] {
            (_, 0) => {
                self.words[at] = (w, next + 1);
                next
            }
            (_, id) => id - 1,
        }
    }

    /// The slot of `words` that holds the word `w`, or the empty one where it goes.
    fn word_slot(words: &[(u64, u32)], w: u64) -> usize {
        let mask = words.len() - 1;
        let mut at = crate::semantics::compiled::mix(w) as usize & mask;
        while words[at].1 != 0 && words[at].0 != w {
            at = (at + 1) & mask;
        }
        at
    }
}

/// How each atomic proposition is evaluated on a state of the search.
pub(crate) struct RunAtoms {
    evals: Vec<Eval>,
    words: usize,
    /// The propositions about an agent's goals or the requests (the others are about
    /// beliefs, or about transitions): a state's letter evaluates these on each state.
    per_state: Vec<usize>,
    /// The agents (one bit each, the 64th and later all bits) whose actions some `did`
    /// proposition is about.
    doers: u64,
    /// Per agent and action: the `did` propositions it makes true. The merging thread
    /// asks at every action a search takes, and unifying the action with every pattern
    /// each time was a tenth of that thread.
    did: std::sync::Mutex<HashMap<(u8, Term), Letter, crate::semantics::compiled::Quick>>,
}

enum Eval {
    Beliefs(crate::model::cond::Cond),
    /// An agent's goal pattern; `true`: events count too (`.desire`).
    Goal(u8, Term, bool),
    /// The requests (one bit each) a `requested` pattern matches.
    Requested(u64),
    /// An action pattern of an agent.
    Did(u8, Term),
    /// An action pattern an explanation to the user is about.
    Explained(Term),
    /// Not read by the properties at hand: never set.
    Unread,
}

impl RunAtoms {
    /// The evaluation of `atomics` for the agent of `sem` (the one requests go to).
    pub(crate) fn new(atomics: &Atomics, sem: &Semantics) -> RunAtoms {
        RunAtoms::reading(atomics, sem, |_| true)
    }

    /// [`RunAtoms::new`] for the propositions of `props` alone, the others never set: a
    /// graph reduced by symmetry gives the right letters for these only.
    pub(crate) fn for_props(
        atomics: &Atomics,
        sem: &Semantics,
        props: &[(usize, RunProperty)],
    ) -> RunAtoms {
        let read: std::collections::HashSet<u32> = props
            .iter()
            .flat_map(|(_, p)| &p.instances)
            .flat_map(|i| i.formula.named_props())
            .collect();
        RunAtoms::reading(atomics, sem, |p| read.contains(&p))
    }

    fn reading(atomics: &Atomics, sem: &Semantics, read: impl Fn(u32) -> bool) -> RunAtoms {
        let evals = atomics
            .list
            .iter()
            .enumerate()
            .map(|(p, a)| match a {
                _ if !read(p as u32) => Eval::Unread,
                Atomic::Beliefs(c) => Eval::Beliefs(c.clone()),
                Atomic::Intends(k, g) => Eval::Goal(*k, g.clone(), false),
                Atomic::Desires(k, g) => Eval::Goal(*k, g.clone(), true),
                Atomic::Requested(g) => Eval::Requested(
                    sem.requests
                        .iter()
                        .enumerate()
                        .filter(|(_, r)| unifier(g, r).is_some())
                        .fold(0u64, |m, (i, _)| m | 1 << i),
                ),
                Atomic::Did(k, a) => Eval::Did(*k, a.clone()),
                Atomic::Explained(a) => Eval::Explained(a.clone()),
            })
            .collect::<Vec<_>>();
        let per_state = (evals.iter().enumerate())
            .filter(|(_, e)| matches!(e, Eval::Goal(..) | Eval::Requested(_)))
            .map(|(j, _)| j)
            .collect();
        let doers = evals.iter().fold(0u64, |m, e| match e {
            // Agents past the 64th share every bit.
            Eval::Did(k, _) => m | 1u64.checked_shl(u32::from(*k)).unwrap_or(u64::MAX),
            _ => m,
        });
        RunAtoms {
            words: evals.len().div_ceil(64).max(1),
            evals,
            per_state,
            doers,
            did: Default::default(),
        }
    }

    /// The propositions about states that hold in `s`.
    pub(crate) fn state_letter<S: AgentState>(&self, s: &S) -> Letter {
        self.state_letter_on(self.beliefs_letter(s.beliefs()), s)
    }

    /// The propositions about beliefs alone that hold on `beliefs`: a search keeps them
    /// per belief base, which far fewer than its states have.
    pub(crate) fn beliefs_letter(&self, beliefs: &crate::model::atoms::AtomSet) -> Letter {
        let mut out: Letter = smallvec::smallvec![0; self.words];
        for (j, e) in self.evals.iter().enumerate() {
            if matches!(e, Eval::Beliefs(c) if c.eval(beliefs)) {
                out[j / 64] |= 1 << (j % 64);
            }
        }
        out
    }

    /// The propositions about states that hold in `s`, where `on_beliefs` are those about
    /// its beliefs alone ([`RunAtoms::beliefs_letter`]).
    pub(crate) fn state_letter_on<S: AgentState>(&self, on_beliefs: Letter, s: &S) -> Letter {
        self.letter_on(on_beliefs, &[s], s.pending_requests())
    }

    /// The propositions about states that hold in a state of several agents: `everything`
    /// its atoms as [`crate::semantics::System::everything`] numbers them, `agents` the
    /// agents' states, the requests going to the first.
    pub(crate) fn system_letter(
        &self,
        everything: &crate::model::atoms::AtomSet,
        agents: &[crate::semantics::State],
    ) -> Letter {
        let minds: Vec<&crate::semantics::State> = agents.iter().collect();
        let pending = agents.first().map_or(0, |a| a.pending_requests());
        self.letter_on(self.beliefs_letter(everything), &minds, pending)
    }

    /// `on_beliefs` ([`RunAtoms::beliefs_letter`]) with the propositions about the agents'
    /// goals (`minds`) and the requests `pending`.
    fn letter_on<S: AgentState>(&self, on_beliefs: Letter, minds: &[&S], pending: u64) -> Letter {
        let mut out = on_beliefs;
        let mut goals: HashMap<(u8, bool), Vec<&Term>> = HashMap::new();
        for &j in &self.per_state {
            let holds = match &self.evals[j] {
                Eval::Goal(k, g, events) => minds.get(*k as usize).is_some_and(|m| {
                    goals
                        .entry((*k, *events))
                        .or_insert_with(|| m.goals(*events))
                        .iter()
                        .any(|t| unifier(g, t).is_some())
                }),
                Eval::Requested(mask) => pending & mask != 0,
                // Not in `per_state`.
                Eval::Beliefs(_) | Eval::Did(..) | Eval::Explained(_) | Eval::Unread => false,
            };
            if holds {
                out[j / 64] |= 1 << (j % 64);
            }
        }
        out
    }

    /// The propositions a transition of a user's explanation search makes true (`did` and
    /// `explained`), if any.
    pub(crate) fn explained_step_letter<N: super::model::CycleNotes>(
        &self,
        step: &super::explanation::Step<N>,
    ) -> Option<Letter> {
        let did = self.step_letter(step.agent, step.notes.notes());
        let n = step.notes.notes().count();
        let told =
            self.explained_letter((0..n).filter_map(|i| step.given_at(i).map(|g| &g.action)));
        match (did, told) {
            (Some(mut a), Some(b)) => {
                a.iter_mut().zip(b).for_each(|(x, y)| *x |= y);
                Some(a)
            }
            (a, b) => a.or(b),
        }
    }

    /// The `explained` propositions a transition that explained these actions to the user
    /// makes true, if any.
    pub(crate) fn explained_letter<'t>(
        &self,
        actions: impl Iterator<Item = &'t Term>,
    ) -> Option<Letter> {
        let mut out: Letter = smallvec::smallvec![0; self.words];
        let mut any = false;
        for t in actions {
            for (j, e) in self.evals.iter().enumerate() {
                if matches!(e, Eval::Explained(a) if unifier(a, t).is_some()) {
                    out[j / 64] |= 1 << (j % 64);
                    any = true;
                }
            }
        }
        any.then_some(out)
    }

    /// The `did` propositions a transition of `agent` (0 when there is one) with these
    /// notes makes true, if any.
    pub(crate) fn step_letter<'n>(
        &self,
        agent: u8,
        notes: impl Iterator<Item = &'n Note>,
    ) -> Option<Letter> {
        if self.doers & 1u64.checked_shl(u32::from(agent)).unwrap_or(u64::MAX) == 0 {
            return None;
        }
        let mut out: Letter = smallvec::smallvec![0; self.words];
        let mut any = false;
        for n in notes {
            let Note::Action { term, .. } = n else {
                continue;
            };
            let mut or = |did: &Letter| {
                for (o, d) in out.iter_mut().zip(did) {
                    *o |= d;
                }
                any |= did.iter().any(|&d| d != 0);
            };
            // A poisoned lock: a panic on another thread, re-raised there; the map holds
            // only complete entries.
            let lock = || self.did.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(did) = lock().get(&(agent, term.clone())) {
                or(did);
                continue;
            }
            let did = self.did_by(agent, term);
            or(&did);
            lock().insert((agent, term.clone()), did);
        }
        any.then_some(out)
    }

    /// The `did` propositions that action `term` of agent `agent` makes true.
    fn did_by(&self, agent: u8, term: &Term) -> Letter {
        let mut did: Letter = smallvec::smallvec![0; self.words];
        for (j, e) in self.evals.iter().enumerate() {
            if matches!(e, Eval::Did(k, a) if *k == agent && unifier(a, term).is_some()) {
                did[j / 64] |= 1 << (j % 64);
            }
        }
        did
    }
}

/// A formula without temporal operators, read on one state's letter.
pub(crate) struct OnState {
    /// The formula over local proposition numbers.
    formula: Ltl,
    /// The global number of each local proposition.
    map: Vec<u32>,
}

impl OnState {
    fn new(f: &Ltl) -> OnState {
        let mut map = Vec::new();
        let formula = localize(f, &mut map);
        OnState { formula, map }
    }

    /// Whether it holds where the propositions of `letter` do (LTL's semantics on the run
    /// that stays there).
    pub(crate) fn holds(&self, letter: &Letter) -> bool {
        self.formula
            .holds_on_lasso(&[], &[local(letter, &self.map)])
    }
}

/// The formulas of the `always` properties among `props` that read states only (no `did`,
/// no `explained`), one per instance, and the names of those that read steps, which no
/// state shows: how a drawing of the state graph marks the states they fail in.
pub(crate) fn always_on_states(
    props: &[RunProperty],
    atomics: &Atomics,
) -> (Vec<OnState>, Vec<String>) {
    let (mut formulas, mut skipped) = (Vec::new(), Vec::new());
    for p in props.iter().filter(|p| p.kind == PropertyKind::Always) {
        let steps = p.instances.iter().any(|i| {
            i.formula.named_props().iter().any(|&a| {
                matches!(
                    atomics.list[a as usize],
                    Atomic::Did(..) | Atomic::Explained(_)
                )
            })
        });
        if steps {
            skipped.push(p.name.clone());
        } else {
            formulas.extend(p.instances.iter().map(|i| OnState::new(&i.formula)));
        }
    }
    (formulas, skipped)
}

/// The formula of one instance over local proposition numbers, and the global number of
/// each local one.
fn localize(f: &Ltl, map: &mut Vec<u32>) -> Ltl {
    let b = |x: &Ltl, map: &mut Vec<u32>| Box::new(localize(x, map));
    match f {
        Ltl::True => Ltl::True,
        Ltl::False => Ltl::False,
        Ltl::Prop(p) => {
            let k = map.iter().position(|q| q == p).unwrap_or_else(|| {
                map.push(*p);
                map.len() - 1
            });
            Ltl::Prop(k as u32)
        }
        Ltl::Not(a) => Ltl::Not(b(a, map)),
        Ltl::Next(a) => Ltl::Next(b(a, map)),
        Ltl::And(x, y) => Ltl::And(b(x, map), b(y, map)),
        Ltl::Or(x, y) => Ltl::Or(b(x, map), b(y, map)),
        Ltl::Until(x, y) => Ltl::Until(b(x, map), b(y, map)),
        Ltl::Release(x, y) => Ltl::Release(b(x, map), b(y, map)),
    }
}

/// A global letter restricted to the propositions `map` names, renumbered.
fn local(letter: &[u64], map: &[u32]) -> u64 {
    map.iter().enumerate().fold(0, |acc, (k, &p)| {
        let set = letter
            .get(p as usize / 64)
            .is_some_and(|w| w >> (p % 64) & 1 == 1);
        acc | (u64::from(set) << k)
    })
}

/// A violation found in the product: graph states from an initial one, then either a loop
/// (graph states from its entry back to it), a run that ends and stays (`ends`), or
/// nothing (a bad prefix: every continuation violates).
pub(crate) struct Violation {
    pub(crate) path: Vec<u32>,
    /// For each step of `path`: its position among the transitions of the state it leaves,
    /// as exploration numbered them (a `did` tells transitions to one state apart).
    pub(crate) path_via: Vec<u32>,
    /// The loop, from its entry back to it (empty when there is none).
    pub(crate) cycle: Vec<u32>,
    /// As `path_via`, for `cycle`.
    pub(crate) cycle_via: Vec<u32>,
    /// The run ends at the last state of `path` and stays there.
    pub(crate) ends: bool,
    /// The assignment of the instance it violates (`C = cup1`; empty when none).
    pub(crate) binding: String,
}

impl Violation {
    /// The loop followed `rounds` times (under symmetry the loop of the reduced graph may
    /// come back to a renaming of its entry, and the real run goes round until the state
    /// itself comes back).
    pub(crate) fn unroll(&mut self, rounds: usize) {
        if self.cycle.len() < 2 || rounds < 2 {
            return;
        }
        let (cycle, via) = (self.cycle.clone(), self.cycle_via.clone());
        for _ in 1..rounds {
            self.cycle.extend_from_slice(&cycle[1..]);
            self.cycle_via.extend_from_slice(&via);
        }
    }
}

/// What the product reads of the explored graph, in the local numbering of one formula's
/// propositions.
pub(crate) trait RunGraph {
    /// How many states there are.
    fn len(&self) -> u32;
    /// How many states are initial (the first ones).
    fn initial(&self) -> u32;
    /// The successors of `i`, in transition order; `None` when it was not expanded.
    fn successors(&self, i: u32) -> Option<&[u32]>;
    /// Whether a run may end in `i` and stay there.
    fn may_end(&self, i: u32) -> bool;
    /// The propositions that hold in `i`.
    fn state_letter(&self, i: u32) -> u64;
    /// The propositions the `k`-th transition from `i` makes true (`did`).
    fn step_letter(&self, i: u32, k: u32) -> u64;
    /// Whether some transition from `i` may have a step letter (`false`: none has).
    fn steps_at(&self, _i: u32) -> bool {
        true
    }
    /// Whether some transition may have a step letter (`false`: a position's letter is its
    /// state's).
    fn any_steps(&self) -> bool {
        true
    }
    /// How many agents a loop must be weakly fair to (0: every loop is a run).
    fn fair_agents(&self) -> u8 {
        0
    }
    /// The agents that can take a step from `i`, one bit each.
    fn enabled(&self, _i: u32) -> u64 {
        0
    }
    /// The agent that takes the `k`-th transition from `i` (`None`: the user).
    fn mover(&self, _i: u32, _k: u32) -> Option<u8> {
        None
    }
}

/// What a search recorded for the run properties, on any explored graph (one agent's, or
/// every interleaving of several).
pub(crate) struct RunFacts<'a> {
    /// How many states; the first `initial` are initial.
    pub(crate) len: u32,
    pub(crate) initial: u32,
    /// A state's successors in transition order (`None`: not expanded).
    pub(crate) successors: &'a dyn Fn(u32) -> Option<&'a [u32]>,
    /// Whether a run may end in a state and stay there.
    pub(crate) may_end: &'a dyn Fn(u32) -> bool,
    /// Per state: an index into `letter_table`.
    pub(crate) letters: &'a Narrow,
    pub(crate) letter_table: &'a [Letter],
    /// Per transition (source, position) that did a `did` action: those propositions.
    pub(crate) steps: &'a StepLetters,
    /// With several agents and weak fairness of agents: how many agents, the agents that
    /// can move from a state (one bit each), and the agent of a transition.
    pub(crate) fairness: Option<Fairness<'a>>,
}

/// Weak fairness of agents, as [`RunFacts::fairness`] reads it.
pub(crate) struct Fairness<'a> {
    pub(crate) agents: u8,
    pub(crate) enabled: &'a dyn Fn(u32) -> u64,
    pub(crate) mover: &'a dyn Fn(u32, u32) -> Option<u8>,
}

/// Recorded facts read through one formula's propositions.
struct Explored<'f, 'a> {
    facts: &'f RunFacts<'a>,
    /// Per letter id of the search: the local letter.
    state_letters: Vec<u64>,
    /// The transitions whose `did` propositions this formula reads, with their local
    /// letter, and a bit per state that has one: most states have none, and every product
    /// edge asks.
    step_letters: HashMap<(u32, u32), u64, crate::semantics::compiled::Quick>,
    stepping: Vec<u64>,
}

impl RunGraph for Explored<'_, '_> {
    fn len(&self) -> u32 {
        self.facts.len
    }
    fn initial(&self) -> u32 {
        self.facts.initial
    }
    fn successors(&self, i: u32) -> Option<&[u32]> {
        (self.facts.successors)(i)
    }
    fn may_end(&self, i: u32) -> bool {
        (self.facts.may_end)(i)
    }
    // Read for every node a product meets: out of line (once `Narrow` made it longer) it
    // cost 5% more instructions than the products took inlined (cachegrind, 4 cups).
    #[inline(always)]
    fn state_letter(&self, i: u32) -> u64 {
        match (i as usize) < self.facts.letters.len() {
            true => self.state_letters[self.facts.letters.get(i as usize) as usize],
            false => 0,
        }
    }
    fn step_letter(&self, i: u32, k: u32) -> u64 {
        if !bit(&self.stepping, i) {
            return 0;
        }
        self.step_letters.get(&(i, k)).copied().unwrap_or(0)
    }
    fn steps_at(&self, i: u32) -> bool {
        bit(&self.stepping, i)
    }
    fn any_steps(&self) -> bool {
        !self.step_letters.is_empty()
    }
    fn fair_agents(&self) -> u8 {
        self.facts.fairness.as_ref().map_or(0, |f| f.agents)
    }
    fn enabled(&self, i: u32) -> u64 {
        self.facts.fairness.as_ref().map_or(0, |f| (f.enabled)(i))
    }
    fn mover(&self, i: u32, k: u32) -> Option<u8> {
        self.facts.fairness.as_ref().and_then(|f| (f.mover)(i, k))
    }
}

/// Most steps the tableau may take to translate one formula: the translation is
/// exponential in the formula's temporal operators, and a formula it cannot translate in
/// this many is left undecided (a dozen nested `U` reach it; the kitchen's take under 100).
pub(crate) const TABLEAU_BUDGET: usize = 200_000;

/// The product of a graph with the automaton of a formula's negation.
pub(crate) struct Product<'r, G: RunGraph> {
    buchi: Buchi,
    /// Per Büchi state: accepting, with a `true` edge back to itself.
    universal: Vec<bool>,
    /// Whether every accepting state is universal (the negation of a safety property):
    /// a violation is then a prefix, found as it is reached, and no cycle need be sought.
    prefixes_only: bool,
    graph: &'r G,
    /// Product states the last search reached.
    pub(crate) reached: std::cell::Cell<usize>,
}

/// A product state: graph state, Büchi state, and whether the run has ended (it stays in
/// its last state for ever from there).
type Node = (u32, u32, bool);

/// Product nodes in the order found: per node its graph state, `2 q + ended`, and the
/// node found before it of the same graph state (`u32::MAX` if none), which the search
/// reads with the key when it looks a node up ([`Scratch::head`]).
#[derive(Default)]
struct Nodes(Chunked<[u32; 3]>);

impl Nodes {
    fn get(&self, x: u32) -> Node {
        let [i, key, _] = self.0.get(x as usize);
        (i, key >> 1, key & 1 == 1)
    }

    /// Node `x`'s Büchi state and whether the run ended, as `2 q + ended`, and the node
    /// found before it of the same graph state.
    fn key_and_chain(&self, x: u32) -> (u32, u32) {
        let [_, key, chain] = self.0.get(x as usize);
        (key, chain)
    }

    fn push(&mut self, (i, q, ended): Node, chain: u32) -> Result<(), OutOfMemory> {
        self.0.push([i, q * 2 + u32::from(ended), chain])
    }

    fn len(&self) -> usize {
        self.0.len()
    }

    fn iter(&self) -> impl Iterator<Item = Node> + '_ {
        (0..self.0.len() as u32).map(|x| self.get(x))
    }
}

/// The memory a product search fills, kept for the next: the products of one graph are
/// searched one after the other, and fresh pages cost (the kernel clears them). Its
/// arrays grow by chunks that never move ([`Chunked`]): vectors that doubled copied
/// themselves into fresh pages, and clearing those was half of the 6-cup kitchen's
/// products (perf: 63 k of their 118 k samples). Chunks a search drops are the
/// allocator's to give the next one.
#[derive(Default)]
pub(crate) struct Scratch {
    nodes: Nodes,
    /// Per node: the node it was first reached from (`u32::MAX` for an initial one). The
    /// transition is found again for the nodes of a counterexample ([`Product::via`]):
    /// four bytes a node, of hundreds of millions at 6 cups.
    parent: Chunked<u32>,
    edges: Csr,
    /// Per graph state: the last node found of it, or `u32::MAX`, from which the nodes
    /// chain back ([`Nodes`]). A dense index per (graph state, Büchi state, ended) took 8
    /// bytes per Büchi state for every graph state, written whole at every search
    /// (gigabytes at 6 cups), for a few nodes per graph state. Made in the memory of the
    /// array by place a user's search on this thread just dropped, when there is one
    /// ([`fresh_head`]).
    head: Slots<u32>,
}

/// `head` made `n` entries, each `u32::MAX`, in the memory of the table this thread last
/// dropped and kept where it can ([`Slots::reused_or_fresh`]: the products run on a user's
/// search's thread after it, in the memory of its array by place). At 6 cups `head` is
/// 262 MB.
fn fresh_head(head: &mut Slots<u32>, n: usize) -> Result<(), OutOfMemory> {
    // The old one first: it may be the memory kept.
    *head = Slots::default();
    *head = Slots::reused_or_fresh(n, u32::MAX)?;
    Ok(())
}

/// What the product searches of one graph share: the product states they reached, and
/// their memory.
#[derive(Default)]
pub(crate) struct Products {
    /// Product states reached, over every search.
    pub(crate) reached: usize,
    scratch: Scratch,
}

/// The "transition" of a step where the run ends, or stays ended: its state repeats.
const STAYS: u32 = u32::MAX;

impl<'r, G: RunGraph> Product<'r, G> {
    /// The product of `graph` with the automaton of `not f` (`f` over the graph's local
    /// propositions).
    /// `None` when the automaton would take more than [`TABLEAU_BUDGET`] steps to build.
    pub(crate) fn new(graph: &'r G, f: &Ltl) -> Option<Self> {
        Product::new_within(graph, f, TABLEAU_BUDGET)
    }

    /// [`Product::new`], the automaton built in at most `budget` tableau steps.
    fn new_within(graph: &'r G, f: &Ltl, budget: usize) -> Option<Self> {
        let buchi = Buchi::from_ltl_within(&Ltl::not(f.clone()), budget)?;
        let universal = universal(&buchi);
        let prefixes_only = (buchi.states.iter().zip(&universal)).all(|(b, &u)| !b.accepting || u);
        Some(Product {
            universal,
            prefixes_only,
            buchi,
            graph,
            reached: std::cell::Cell::new(0),
        })
    }

    /// The successors of a product node.
    /// The successors of a product node, each with the graph transition taken (its
    /// position among the state's transitions; [`STAYS`] when the run ends or stays ended).
    fn successors(&self, (i, q, ended): Node, out: &mut Vec<(Node, u32)>) {
        out.clear();
        let b = &self.buchi.states[q as usize];
        let follow = |letter: u64, j: u32, end: bool, k: u32, out: &mut Vec<(Node, u32)>| {
            for (guard, q2) in &b.edges {
                if guard.matches(letter) {
                    out.push(((j, *q2, end), k));
                }
            }
        };
        if !ended {
            if let Some(succ) = self.graph.successors(i) {
                for (k, &j) in succ.iter().enumerate() {
                    let letter = self.graph.state_letter(j) | self.graph.step_letter(i, k as u32);
                    follow(letter, j, false, k as u32, out);
                }
            }
        }
        if ended || self.graph.may_end(i) {
            follow(self.graph.state_letter(i), i, true, STAYS, out);
        }
    }

    /// Breadth-first over the product; the first bad prefix, or the shortest accepting
    /// lasso found by the strongly connected components of the product.
    /// `Err` when memory ran out. The search fills `scratch`, left as it was by the last.
    pub(crate) fn search(&self, scratch: &mut Scratch) -> Result<Option<Violation>, OutOfMemory> {
        // Product nodes are numbered in the order found, breadth-first: node `x` is expanded
        // when `x` nodes were, so its edges go at the end of `edges` (one flat array).
        let Scratch {
            nodes,
            parent,
            edges,
            head,
        } = scratch;
        let (nodes, parent) = (&mut *nodes, &mut *parent);
        // The transitions of the product's edges are found again where a lasso reads them,
        // but for fairness of agents, which reads them on every node.
        let keep_via = self.graph.fair_agents() > 0;
        let states = self.graph.len() as usize;
        if head.len() == states {
            // Only what the last search set is reset.
            for (i, _, _) in nodes.iter() {
                head[i as usize] = u32::MAX;
            }
        } else {
            fresh_head(head, states)?;
        }
        nodes.0.clear();
        parent.clear();
        *edges = Csr::default();
        let mut add = |n: Node, from: u32, nodes: &mut Nodes, parent: &mut Chunked<u32>| {
            let (i, q, ended) = n;
            let key = q * 2 + u32::from(ended);
            let mut at = head[i as usize];
            while at != u32::MAX {
                let (k, before) = nodes.key_and_chain(at);
                if k == key {
                    return Ok((at, false));
                }
                at = before;
            }
            let x = u32::try_from(nodes.len()).map_err(|_| OutOfMemory)?;
            nodes.push(n, head[i as usize])?;
            parent.push(from)?;
            head[i as usize] = x;
            Ok((x, true))
        };
        let init = &self.buchi.states[self.buchi.initial as usize];
        for i in 0..self.graph.initial() {
            let letter = self.graph.state_letter(i);
            for (guard, q) in &init.edges {
                if guard.matches(letter) {
                    let (x, new) = add((i, *q, false), u32::MAX, nodes, parent)?;
                    if new && self.universal[*q as usize] {
                        self.reached.set(nodes.len());
                        return Ok(Some(self.prefix(nodes, parent, x)));
                    }
                }
            }
        }
        let mut succ = Vec::new();
        let mut x = 0u32;
        // Without a cycle to seek, the product's edges are not kept.
        let keep = !self.prefixes_only;
        while (x as usize) < nodes.len() {
            self.successors(nodes.get(x), &mut succ);
            if keep {
                edges.begin(succ.len(), keep_via)?;
            }
            for &(n, k) in &succ {
                let (y, new) = add(n, x, nodes, parent)?;
                if keep {
                    edges.push(y, k);
                }
                if new && self.universal[n.1 as usize] {
                    self.reached.set(nodes.len());
                    return Ok(Some(self.prefix(nodes, parent, y)));
                }
            }
            x += 1;
        }
        self.reached.set(nodes.len());
        let accepting = |n: &Node| self.buchi.states[n.1 as usize].accepting;
        if !keep || !nodes.iter().any(|n| accepting(&n)) {
            return Ok(None);
        }
        edges.begin(0, keep_via)?;
        Ok(self.lasso(nodes, parent, edges))
    }

    /// The graph states of the run to product node `x`, and the transition of each step
    /// (the steps where the run ends or stays ended are left out: the state repeats).
    fn run_to(&self, nodes: &Nodes, parent: &Chunked<u32>, x: u32) -> (Vec<u32>, Vec<u32>) {
        let (mut states, mut via) = (Vec::new(), Vec::new());
        let mut at = x;
        loop {
            let p = parent.get(at as usize);
            let k = match p {
                u32::MAX => STAYS,
                p => self.via(nodes, p, at),
            };
            if k != STAYS {
                via.push(k);
            }
            if k == STAYS || p == u32::MAX {
                if p == u32::MAX || nodes.get(p).0 != nodes.get(at).0 {
                    states.push(nodes.get(at).0);
                }
            } else {
                states.push(nodes.get(at).0);
            }
            if p == u32::MAX {
                break;
            }
            at = p;
        }
        states.reverse();
        via.reverse();
        (states, via)
    }

    /// The transition by which node `y` was first reached from node `x`: the first of
    /// `x`'s successors that is `y`'s node, as the search found it.
    fn via(&self, nodes: &Nodes, x: u32, y: u32) -> u32 {
        let mut out = Vec::new();
        self.successors(nodes.get(x), &mut out);
        let y = nodes.get(y);
        let first = out.iter().find(|(n, _)| *n == y);
        first.expect("a node is a successor of its parent").1
    }

    /// The transitions of node `x`'s edges in `edges`, in their order: as the search kept
    /// them, or found again (the search pushed an edge for every successor).
    fn vias<'e>(&self, nodes: &Nodes, edges: &'e Csr, x: u32) -> std::borrow::Cow<'e, [u32]> {
        if let Some(via) = &edges.via {
            return std::borrow::Cow::Borrowed(via.list(x as usize));
        }
        let mut out = Vec::new();
        self.successors(nodes.get(x), &mut out);
        debug_assert_eq!(out.len(), edges.of(x).len());
        std::borrow::Cow::Owned(out.into_iter().map(|(_, k)| k).collect())
    }

    fn prefix(&self, nodes: &Nodes, parent: &Chunked<u32>, x: u32) -> Violation {
        let (path, path_via) = self.run_to(nodes, parent, x);
        Violation {
            path,
            path_via,
            cycle: Vec::new(),
            cycle_via: Vec::new(),
            ends: false,
            binding: String::new(),
        }
    }

    /// The shallowest accepting node on a cycle of a fair component, and a shortest cycle
    /// through it (with fairness of agents, through a step of every agent that could move
    /// everywhere in the component).
    fn lasso(&self, nodes: &Nodes, parent: &Chunked<u32>, edges: &Csr) -> Option<Violation> {
        let comp = components(edges);
        let on_cycle = |x: u32| {
            let c = comp[x as usize];
            edges.of(x).iter().any(|&y| comp[y as usize] == c)
        };
        // Per component: the agents that can move in every one of its states, and those
        // that move inside it (weak fairness of agents: the first must be among the second).
        let agents = self.graph.fair_agents();
        let mut everywhere: HashMap<u32, u64> = HashMap::new();
        let mut moved: HashMap<u32, u64> = HashMap::new();
        if agents > 0 {
            for (x, (i, _, ended)) in nodes.iter().enumerate() {
                let c = comp[x];
                // A run that ended stays: no agent is owed a step there.
                let can = if ended { 0 } else { self.graph.enabled(i) };
                *everywhere.entry(c).or_insert(u64::MAX) &= can;
                for (&y, &k) in edges
                    .of(x as u32)
                    .iter()
                    .zip(&*self.vias(nodes, edges, x as u32))
                {
                    if comp[y as usize] == c && k != STAYS {
                        if let Some(a) = self.graph.mover(i, k) {
                            *moved.entry(c).or_insert(0) |= 1 << a;
                        }
                    }
                }
            }
        }
        let owed = |c: u32| everywhere.get(&c).copied().unwrap_or(0);
        let fair = |c: u32| owed(c) & !moved.get(&c).copied().unwrap_or(0) == 0;
        // Nodes are numbered breadth-first, so the first is the shallowest.
        let entry = (0..nodes.len() as u32).find(|&x| {
            self.buchi.states[nodes.get(x).1 as usize].accepting
                && on_cycle(x)
                && fair(comp[x as usize])
        })?;
        let c = comp[entry as usize];
        let (path, path_via) = self.run_to(nodes, parent, entry);
        if nodes.get(entry).2 {
            // The loop is the run staying in its last state.
            return Some(Violation {
                path,
                path_via,
                cycle: Vec::new(),
                cycle_via: Vec::new(),
                ends: true,
                binding: String::new(),
            });
        }
        // From the entry, for each agent, through a step of it when it can move everywhere
        // in the component, else through a state where it cannot (unless the entry is
        // one); then back to the entry. The loop is then fair to every agent.
        let mut cycle = vec![nodes.get(entry).0];
        let mut cycle_via = Vec::new();
        let mut at = entry;
        let disabled = |y: u32, a: u8| self.graph.enabled(nodes.get(y).0) >> a & 1 == 0;
        for a in 0..agents {
            let steps = if owed(c) >> a & 1 == 1 {
                self.path_within(nodes, edges, (&comp, c), at, |x, _, k| {
                    k != STAYS && self.graph.mover(nodes.get(x).0, k) == Some(a)
                })?
            } else if disabled(entry, a) {
                continue;
            } else {
                self.path_within(nodes, edges, (&comp, c), at, |_, y, _| disabled(y, a))?
            };
            for &(y, k) in &steps {
                cycle.push(nodes.get(y).0);
                cycle_via.push(k);
            }
            at = steps.last().map_or(at, |s| s.0);
        }
        for (y, k) in self.path_within(nodes, edges, (&comp, c), at, |_, y, _| y == entry)? {
            cycle.push(nodes.get(y).0);
            cycle_via.push(k);
        }
        Some(Violation {
            path,
            path_via,
            cycle,
            cycle_via,
            ends: false,
            binding: String::new(),
        })
    }

    /// A shortest run of product steps inside component `c` from node `from` whose last
    /// step `x -> y` (by transition `k`) satisfies `goal(x, y, k)`: the nodes entered, each
    /// with its transition.
    fn path_within(
        &self,
        nodes: &Nodes,
        edges: &Csr,
        (comp, c): (&[u32], u32),
        from: u32,
        goal: impl Fn(u32, u32, u32) -> bool,
    ) -> Option<Vec<(u32, u32)>> {
        let mut back: HashMap<u32, (u32, u32)> = HashMap::new();
        let mut queue = VecDeque::from([from]);
        let mut seen = std::collections::HashSet::from([from]);
        while let Some(x) = queue.pop_front() {
            for (&y, &k) in edges.of(x).iter().zip(&*self.vias(nodes, edges, x)) {
                if comp[y as usize] != c {
                    continue;
                }
                if goal(x, y, k) {
                    let mut steps = vec![(y, k)];
                    let mut at = x;
                    while at != from {
                        let (p, k) = back[&at];
                        steps.push((at, k));
                        at = p;
                    }
                    steps.reverse();
                    return Some(steps);
                }
                if seen.insert(y) {
                    back.insert(y, (x, k));
                    queue.push_back(y);
                }
            }
        }
        None
    }
}

/// Edges of nodes numbered `0..n`, in chunks that never move (as [`Scratch`]'s arrays),
/// and one list after the last.
#[derive(Default)]
struct Csr {
    to: Lists,
    /// Per edge, in lists of `to`'s shape: the graph transition it takes ([`STAYS`] when
    /// the run ends or stays). `None` unless kept ([`Product::vias`]).
    via: Option<Lists>,
}

impl Csr {
    fn len(&self) -> usize {
        self.to.len().saturating_sub(1)
    }

    /// Begins the next node's edges, with room for `n` of them (their transitions too
    /// with `via`); a node after the last ends the array.
    fn begin(&mut self, n: usize, via: bool) -> Result<(), OutOfMemory> {
        let lists = std::iter::once(&mut self.to).chain(match via {
            true => Some(self.via.get_or_insert_with(Lists::default)),
            false => None,
        });
        for l in lists {
            l.room(n)?;
            l.start(l.end())?;
        }
        Ok(())
    }

    /// Adds an edge to `y` by transition `k` to the node begun last, which has room.
    fn push(&mut self, y: u32, k: u32) {
        self.to.push(y);
        if let Some(v) = &mut self.via {
            v.push(k);
        }
    }

    fn of(&self, x: u32) -> &[u32] {
        self.to.list(x as usize)
    }
}

/// The strongly connected component of each node (Tarjan, iterative). Only the nodes that
/// may share a cycle with another ([`on_cycles`](super::liveness::on_cycles)) are
/// searched; every other node is a component of its own.
fn components(edges: &Csr) -> Vec<u32> {
    const UNSEEN: u32 = u32::MAX;
    let n = edges.len();
    let succ = |x: u32| edges.of(x);
    let Some(within) = super::liveness::on_cycles(n, &succ, false) else {
        return (0..n as u32).collect();
    };
    let mut index = vec![UNSEEN; n];
    let mut low = vec![0u32; n];
    let mut comp = vec![UNSEEN; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<u32> = Vec::new();
    let mut next = 0u32;
    let mut count = 0u32;
    let mut calls: Vec<(u32, usize)> = Vec::new();
    for root in 0..n as u32 {
        if index[root as usize] != UNSEEN || !bit(&within, root) {
            continue;
        }
        calls.push((root, 0));
        while let Some(&mut (v, ref mut pos)) = calls.last_mut() {
            let vi = v as usize;
            if *pos == 0 && index[vi] == UNSEEN {
                index[vi] = next;
                low[vi] = next;
                next += 1;
                stack.push(v);
                on_stack[vi] = true;
            }
            if let Some(&w) = edges.of(v).get(*pos) {
                *pos += 1;
                if !bit(&within, w) {
                    continue;
                }
                if index[w as usize] == UNSEEN {
                    calls.push((w, 0));
                } else if on_stack[w as usize] {
                    low[vi] = low[vi].min(index[w as usize]);
                }
                continue;
            }
            calls.pop();
            if let Some(&(u, _)) = calls.last() {
                low[u as usize] = low[u as usize].min(low[vi]);
            }
            if low[vi] == index[vi] {
                while let Some(w) = stack.pop() {
                    on_stack[w as usize] = false;
                    comp[w as usize] = count;
                    if w == v {
                        break;
                    }
                }
                count += 1;
            }
        }
    }
    for c in comp.iter_mut().filter(|c| **c == UNSEEN) {
        *c = count;
        count += 1;
    }
    comp
}

/// A Büchi state that accepts every continuation: accepting, with a `true` self-loop.
fn universal(b: &Buchi) -> Vec<bool> {
    b.states
        .iter()
        .enumerate()
        .map(|(q, s)| {
            s.accepting
                && s.edges
                    .iter()
                    .any(|(g, to)| *to as usize == q && g.pos == 0 && g.neg == 0)
        })
        .collect()
}

/// Why the product could not decide a formula.
enum Undecided {
    /// The formula could not be translated within [`TABLEAU_BUDGET`].
    TooLong,
    /// Memory ran out while the product was built.
    OutOfMemory,
}

/// Searches the product of the recorded graph with the automaton of `not f`; adds the
/// product states it reached to `reached`.
fn violation(
    facts: &RunFacts,
    f: &Ltl,
    products: &mut Products,
) -> Result<Option<Violation>, Undecided> {
    Ok(product_search(facts, f, products, false)?.flatten())
}

/// Whether `f` holds on every run, when one product over at most
/// [`MAX_PROPS`](crate::model::property::MAX_PROPS) propositions (a letter's bits) decides
/// it; `None` when `f` has more (each instance has at most that many), or its automaton
/// takes more than an eighth of [`TABLEAU_BUDGET`] (its instances one by one are then
/// cheaper), or memory ran out.
fn holds_at_once(facts: &RunFacts, f: &Ltl, products: &mut Products) -> Option<bool> {
    match product_search(facts, f, products, true) {
        Ok(Some(found)) => Some(found.is_none()),
        _ => None,
    }
}

/// [`violation`]; with `bounded`, `Ok(None)` instead of a search when `f` has more than
/// [`MAX_PROPS`](crate::model::property::MAX_PROPS) propositions (compiling a property
/// refuses an instance with more), and an eighth of the tableau's budget.
fn product_search(
    facts: &RunFacts,
    f: &Ltl,
    products: &mut Products,
    bounded: bool,
) -> Result<Option<Option<Violation>>, Undecided> {
    let mut map = Vec::new();
    let local_f = localize(f, &mut map);
    if bounded && map.len() > crate::model::property::MAX_PROPS {
        return Ok(None);
    }
    let state_letters = facts.letter_table.iter().map(|l| local(l, &map)).collect();
    let mut step_letters = HashMap::default();
    let mut stepping = Vec::new();
    for (&(i, k), l) in facts.steps {
        let letter = local(l, &map);
        if letter != 0 {
            step_letters.insert((i, k), letter);
            set_bit(&mut stepping, i, true);
        }
    }
    let g = Explored {
        facts,
        state_letters,
        step_letters,
        stepping,
    };
    // `[] b` with `b` about one position (`[] (did(wipe(L)) -> holding(none))`) is
    // decided by one pass over the graph, far cheaper than a product that has a node per
    // graph state; so is `[] (a -> <> q)` (`a ~> q`), and the conjunction of its
    // instances, on runs that need no fairness of agents: one pass per response, over the
    // states that may avoid `q` from where `a` holds without `q` (the product had 5.9 M
    // nodes at 4 cups, a quarter of the instructions after the agent's search). A
    // violation's shortest run is still the product's to find.
    let without_fairness = g.fair_agents() == 0;
    if let Some(pieces) = always_body(&local_f)
        .and_then(pieces)
        .filter(|ps| without_fairness || ps.iter().all(|p| matches!(p, Piece::At(_))))
    {
        let mut visited = 0;
        let held = holds_by_pieces(&g, &pieces, &mut products.scratch, &mut visited);
        if held {
            products.reached += visited;
            return Ok(Some(None));
        }
    }
    let p = match bounded {
        true => Product::new_within(&g, &local_f, TABLEAU_BUDGET / 8),
        false => Product::new(&g, &local_f),
    };
    let p = p.ok_or(Undecided::TooLong)?;
    let v = p.search(&mut products.scratch);
    products.reached += p.reached.get();
    v.map(Some).map_err(|OutOfMemory| Undecided::OutOfMemory)
}

/// What the runs say of one property: its status, message and run (a violation, or a
/// `reachable` property's witness). `complete`: every state was expanded. `runs` says
/// which runs a passing property held on.
pub(crate) fn decide(
    facts: &RunFacts,
    p: &RunProperty,
    (complete, runs): (bool, &str),
    products: &mut Products,
) -> (Status, String, Option<Violation>) {
    let undecided = |why: Undecided| {
        let message = match why {
            Undecided::TooLong => format!(
                "`{}`: its formula is too long to translate to an automaton (more than {TABLEAU_BUDGET} tableau steps); split it into several properties",
                p.name
            ),
            Undecided::OutOfMemory => format!(
                "`{}`: memory ran out while its product with the runs was built",
                p.name
            ),
        };
        (Status::Unknown, message, None)
    };
    let held = if complete {
        Status::Pass
    } else {
        Status::Unknown
    };
    if p.kind == PropertyKind::Reachable {
        let goal = p.instances.first().map_or(Ltl::True, |i| i.formula.clone());
        let found = match violation(facts, &formula_of(p.kind, &goal), products) {
            Ok(found) => found,
            Err(why) => return undecided(why),
        };
        return match found {
            Some(v) => (
                Status::Pass,
                format!(
                    "`{}` is reached after {} steps (witness run attached)",
                    p.name,
                    v.path.len().saturating_sub(1)
                ),
                Some(v),
            ),
            None if complete => (Status::Fail, format!("`{}` is never reached", p.name), None),
            None => (
                Status::Unknown,
                format!("`{}` is never reached", p.name),
                None,
            ),
        };
    }
    // The instances of a `[]` property (`[] (did(wipe(L)) -> holding(none))`, `used(C) ~>
    // cupAt(C, dishwasher)`, one per binding of their free variables) hold together exactly
    // when `[]` of their bodies' conjunction does: one product, whose automaton shares the
    // states where no instance has gone wrong yet, instead of one per instance. (Built as
    // the conjunction of the `[]` formulas instead, the automaton of 4 response instances
    // outgrew the tableau's budget.) A violation is then looked for instance by instance,
    // as without it, so that the run shown is the first instance's shortest.
    let together: Option<Ltl> = (p.instances.len() > 1)
        .then(|| {
            (p.instances.iter())
                .map(|i| always_body(&formula_of(p.kind, &i.formula)).cloned())
                .collect::<Option<Vec<Ltl>>>()
        })
        .flatten()
        .and_then(|b| b.into_iter().reduce(Ltl::and))
        .map(Ltl::always);
    if together.is_some_and(|f| holds_at_once(facts, &f, products) == Some(true)) {
        return passed(facts, p, held, runs);
    }
    for i in &p.instances {
        let found = match violation(facts, &formula_of(p.kind, &i.formula), products) {
            Ok(found) => found,
            Err(why) => return undecided(why),
        };
        let Some(mut v) = found else {
            continue;
        };
        v.binding = i.binding.clone();
        let message = failure(p, &v);
        return (Status::Fail, message, Some(v));
    }
    passed(facts, p, held, runs)
}

/// Whether `body`, a formula without temporal operators, holds at every position of every
/// run of `g`, which `[] body` says: in each initial state, after each transition (the
/// target's letter and the transition's), and in each state where a run may end (its
/// letter alone: the run stays there, doing nothing). Every state of `g` must be reachable,
/// as a search's are. Most transitions have no step letter and enter a state with its
/// letter alone: when every state's letter satisfies `body`, only the transitions that
/// have one are read.
fn holds_everywhere<G: RunGraph>(g: &G, body: &Ltl) -> bool {
    // Letters repeat: each is judged once, when the formula reads few propositions.
    let mut judge = Judge::new((body, &Ltl::False));
    let mut at = |letter: u64| judge.at(letter).0;
    let states = (0..g.len()).all(|i| at(g.state_letter(i)));
    for i in 0..g.len() {
        if states && !g.steps_at(i) {
            continue;
        }
        if let Some(succ) = g.successors(i) {
            for (k, &j) in succ.iter().enumerate() {
                if !at(g.state_letter(j) | g.step_letter(i, k as u32)) {
                    return false;
                }
            }
        }
        let stays = i < g.initial() || g.may_end(i);
        if !states && stays && !at(g.state_letter(i)) {
            return false;
        }
    }
    true
}

/// A conjunct of the body of a `[]` property that one pass over the graph decides.
enum Piece<'f> {
    /// `b`, about one position: it holds at every position.
    At(&'f Ltl),
    /// `a | <> q`, `a` and `q` about one position: every position where `a` does not hold
    /// is followed, then or later, by one where `q` does.
    Responds(&'f Ltl, &'f Ltl),
}

/// The conjuncts of `body` when each is a [`Piece`].
fn pieces(body: &Ltl) -> Option<Vec<Piece<'_>>> {
    let one = |f: &Ltl| f.at_letter(0).is_some();
    fn eventually(f: &Ltl) -> Option<&Ltl> {
        match f {
            Ltl::Until(t, q) if matches!(**t, Ltl::True) && q.at_letter(0).is_some() => Some(q),
            _ => None,
        }
    }
    match body {
        // A conjunction about one position is one piece: one pass.
        f if one(f) => Some(vec![Piece::At(f)]),
        Ltl::And(x, y) => {
            let mut out = pieces(x)?;
            out.extend(pieces(y)?);
            Some(out)
        }
        Ltl::Or(x, y) => match (eventually(x), eventually(y)) {
            (_, Some(q)) if one(x) => Some(vec![Piece::Responds(x, q)]),
            (Some(q), _) if one(y) => Some(vec![Piece::Responds(y, q)]),
            _ => None,
        },
        _ => None,
    }
}

/// Whether `[]` of the conjunction of `pieces` holds on every run of `g`, when no
/// fairness of agents is owed; adds the states it visited to `visited`.
fn holds_by_pieces<G: RunGraph>(
    g: &G,
    pieces: &[Piece],
    scratch: &mut Scratch,
    visited: &mut usize,
) -> bool {
    let mut responses = Vec::new();
    for piece in pieces {
        match piece {
            Piece::At(b) => {
                *visited += g.len() as usize;
                if !holds_everywhere(g, b) {
                    return false;
                }
            }
            Piece::Responds(a, q) => responses.push((*a, *q)),
        }
    }
    responses.is_empty() || responds(g, &responses, scratch, visited)
}

/// Whether each response `(a, q)`, `a | <> q`, holds at every position of every run of
/// `g` (runs are paths from an initial state, infinite or ended in a state where a run may
/// end, which then repeats), when no fairness of agents is owed; adds the states it
/// visited to `visited`.
///
/// A run violates one at a position where neither `a` nor `q` holds, followed by
/// positions where `q` never does. From a state `j`, a run may go on avoiding `q` exactly
/// when `j` reaches, by transitions whose position does not have `q` (quiet ones), a
/// state where the run may end without `q`, or a cycle of quiet transitions: Tarjan's
/// strongly connected components of those transitions, from the states a bad position
/// enters. A state that no run reaches may only make one look violated (the product then
/// decides).
fn responds<G: RunGraph>(
    g: &G,
    responses: &[(&Ltl, &Ltl)],
    scratch: &mut Scratch,
    visited: &mut usize,
) -> bool {
    let mut judges: Vec<Judge> = (responses.iter())
        .map(|&response| Judge::new(response))
        .collect();
    // Per response, the states entered by a position where neither holds (for an initial
    // state, its own position), all found in one pass over the letters. A run that ends
    // there stays without `q`: a violation.
    let mut entered: Vec<Vec<u32>> = vec![Vec::new(); responses.len()];
    // Without step letters a position's letter is the state it enters: each state is read
    // once instead of once per transition into it (every state but an initial one is
    // entered by one, in a search's graph; one that is not can only add a state to
    // look from).
    let states_only = !g.any_steps();
    for i in 0..g.len() {
        // The state's own letter: an initial state's position, a run that ends there, and
        // without step letters every transition into it.
        if states_only || i < g.initial() || g.may_end(i) {
            let letter = g.state_letter(i);
            for (judge, entered) in judges.iter_mut().zip(&mut entered) {
                if judge.bad(letter) {
                    if g.may_end(i) {
                        return false;
                    }
                    entered.push(i);
                }
            }
        }
        if states_only {
            continue;
        }
        for (k, &j) in g.successors(i).unwrap_or(&[]).iter().enumerate() {
            let letter = g.state_letter(j) | g.step_letter(i, k as u32);
            for (judge, entered) in judges.iter_mut().zip(&mut entered) {
                if judge.bad(letter) {
                    entered.push(j);
                }
            }
        }
    }
    let n = g.len() as usize;
    let Scratch {
        head: index, nodes, ..
    } = scratch;
    if index.len() != n {
        if fresh_head(index, n).is_err() {
            // The product decides, if it can have its memory.
            return false;
        }
    } else {
        // What the last product set (it resets it only when it next begins).
        for (i, _, _) in nodes.iter() {
            if let Some(x) = index.get_mut(i as usize) {
                *x = FREE;
            }
        }
    }
    for (judge, entered) in judges.iter_mut().zip(&entered) {
        let mut t = Tarjan::default();
        let mut avoids = false;
        for &root in entered {
            if index[root as usize] == FREE {
                t.components(g, judge, index, root);
            }
            if index[root as usize] == AVOIDS {
                avoids = true;
                break;
            }
        }
        *visited += t.touched.len();
        // Left as found, for the next response and the next user of `head`.
        for &v in &t.touched {
            index[v as usize] = FREE;
        }
        if avoids {
            return false;
        }
    }
    true
}

/// What [`responds`] (and [`holds_everywhere`], `q` false) reads of a letter: whether `a`
/// and `q` hold there, kept per value of the propositions they read when they read at
/// most [`JUDGED_PROPS`] (a letter holds all the propositions of a property's instances:
/// at 6 cups the kitchen's were past the 16th, and judging those letters anew was 4% of
/// the samples of the phase the `ltl` products run in).
struct Judge<'f> {
    a: &'f Ltl,
    q: &'f Ltl,
    /// The propositions `a` and `q` read, when few enough to be kept per value.
    read: Option<Vec<u32>>,
    /// Per value of `read` (bit `i` the `i`-th proposition's): 0 unknown, else 1 + (a) +
    /// 2 (q).
    judged: Vec<u8>,
}

/// The most propositions a [`Judge`] keeps its answers for, per value.
const JUDGED_PROPS: usize = 16;

impl<'f> Judge<'f> {
    /// The judge of `a` and `q`.
    fn new((a, q): (&'f Ltl, &'f Ltl)) -> Judge<'f> {
        let mut read = a.named_props();
        read.extend(q.named_props());
        read.sort_unstable();
        read.dedup();
        let read = (read.len() <= JUDGED_PROPS && read.iter().all(|&p| p < 64)).then_some(read);
        Judge {
            a,
            q,
            judged: vec![0; read.as_ref().map_or(0, |r| 1 << r.len())],
            read,
        }
    }

    fn at(&mut self, letter: u64) -> (bool, bool) {
        let (a, q) = (self.a, self.q);
        let eval = |l: u64| {
            let v = |f: &Ltl| f.at_letter(l).unwrap_or(false);
            (v(a), v(q))
        };
        let Some(read) = &self.read else {
            return eval(letter);
        };
        let value = (read.iter().enumerate())
            .fold(0usize, |v, (i, &p)| v | (((letter >> p) & 1) as usize) << i);
        let j = &mut self.judged[value];
        if *j != 0 {
            return ((*j - 1) & 1 == 1, (*j - 1) & 2 == 2);
        }
        let (x, y) = eval(letter);
        *j = 1 + u8::from(x) + 2 * u8::from(y);
        (x, y)
    }

    /// Whether a position of this letter is bad: neither `a` nor `q` holds there.
    fn bad(&mut self, letter: u64) -> bool {
        self.at(letter) == (false, false)
    }

    /// Whether the `k`-th transition of `i`, to `j`, is quiet: `q` does not hold at its
    /// position.
    fn quiet<G: RunGraph>(&mut self, g: &G, i: u32, k: u32, j: u32) -> bool {
        !self.at(g.state_letter(j) | g.step_letter(i, k)).1
    }
}

/// A state [`Tarjan`] has not visited.
const FREE: u32 = u32::MAX;
/// A state of a finished component from which a run may avoid `q` for ever.
const AVOIDS: u32 = u32::MAX - 1;
/// A state of a finished component from which every run meets `q`.
const MEETS: u32 = u32::MAX - 2;

/// Tarjan's algorithm, iterative, on the quiet transitions ([`Judge::quiet`]). A state's
/// `index` is its number in the visit while its component is open, then [`AVOIDS`] or
/// [`MEETS`].
#[derive(Default)]
struct Tarjan {
    /// Per visit number: the lowest number reachable.
    low: Vec<u32>,
    /// The states visited, in order.
    touched: Vec<u32>,
    stack: Vec<u32>,
    /// The states being visited, each with its next transition.
    calls: Vec<(u32, u32)>,
    component: Vec<u32>,
}

impl Tarjan {
    fn enter(&mut self, v: u32, index: &mut [u32]) {
        let number = self.touched.len() as u32;
        index[v as usize] = number;
        self.low.push(number);
        self.touched.push(v);
        self.stack.push(v);
        self.calls.push((v, 0));
    }

    /// Finishes the components of the states `root` reaches by quiet transitions.
    fn components<G: RunGraph>(&mut self, g: &G, judge: &mut Judge, index: &mut [u32], root: u32) {
        self.enter(root, index);
        while let Some(&(v, k)) = self.calls.last() {
            let succ = g.successors(v).unwrap_or(&[]);
            if let Some(&w) = succ.get(k as usize) {
                if let Some(c) = self.calls.last_mut() {
                    c.1 += 1;
                }
                if !judge.quiet(g, v, k, w) {
                    continue;
                }
                match index[w as usize] {
                    FREE => self.enter(w, index),
                    AVOIDS | MEETS => {}
                    x => {
                        let lv = &mut self.low[index[v as usize] as usize];
                        *lv = (*lv).min(x);
                    }
                }
                continue;
            }
            self.calls.pop();
            let iv = index[v as usize];
            let lv = self.low[iv as usize];
            if let Some(&(u, _)) = self.calls.last() {
                let lu = &mut self.low[index[u as usize] as usize];
                *lu = (*lu).min(lv);
            }
            if lv != iv {
                continue;
            }
            self.component.clear();
            while let Some(w) = self.stack.pop() {
                self.component.push(w);
                if w == v {
                    break;
                }
            }
            // A cycle of quiet transitions; or, for a state alone, a quiet way on to a
            // state that avoids `q`, or an end without `q`.
            let mut goes_on =
                self.component.len() > 1 || (g.may_end(v) && !judge.at(g.state_letter(v)).1);
            for (k, &w) in succ.iter().enumerate() {
                if goes_on {
                    break;
                }
                let on = w == v || index[w as usize] == AVOIDS;
                goes_on = on && judge.quiet(g, v, k as u32, w);
            }
            for &w in &self.component {
                index[w as usize] = if goes_on { AVOIDS } else { MEETS };
            }
        }
    }
}

/// `f` of `[] f` (`false R f`).
fn always_body(f: &Ltl) -> Option<&Ltl> {
    match f {
        Ltl::Release(a, body) if matches!(**a, Ltl::False) => Some(body),
        _ => None,
    }
}

/// The verdict of a property that no run violates.
fn passed(
    facts: &RunFacts,
    p: &RunProperty,
    held: Status,
    runs: &str,
) -> (Status, String, Option<Violation>) {
    // The state kinds say what their checks on states say (check/safety.rs, liveness.rs).
    let message = match p.kind {
        PropertyKind::Always => format!("`{}` holds in all {} reached states", p.name, facts.len),
        PropertyKind::Eventually => format!("`{}` eventually holds on {runs}", p.name),
        _ => format!("`{}` holds on {runs}", p.name),
    };
    (held, message, None)
}

/// What a violation of the property `p` is (for `always` and `eventually`, as their checks
/// on states say it).
fn failure(p: &RunProperty, v: &Violation) -> String {
    let (name, steps) = (&p.name, v.path.len().saturating_sub(1));
    let who = if v.binding.is_empty() {
        String::new()
    } else {
        format!(" for {}", v.binding)
    };
    match p.kind {
        PropertyKind::Always => {
            format!("`{name}` does not always hold: it is false after {steps} steps")
        }
        PropertyKind::Eventually if v.ends => {
            format!("`{name}` may never hold: a run ends without it")
        }
        PropertyKind::Eventually if !v.cycle.is_empty() => {
            format!("`{name}` may never hold: a run loops forever without it")
        }
        _ if !v.cycle.is_empty() => format!(
            "`{name}` does not hold{who}: a run of {steps} steps enters a loop of {} steps on which it is violated",
            v.cycle.len() - 1
        ),
        _ if v.ends => format!(
            "`{name}` does not hold{who}: a run ends after {steps} steps, and staying there violates it"
        ),
        _ => format!("`{name}` does not hold{who}: it is violated after {steps} steps, whatever happens next"),
    }
}

/// One finding per property from the findings of its instances decided on several
/// searches (each numbered by its property): a violation if any, else undecided if any,
/// else the first.
pub(crate) fn merge(mut found: Vec<(usize, Finding)>) -> Vec<Finding> {
    let rank = |f: &Finding| match f.status {
        Status::Fail => 0,
        Status::Unknown => 1,
        _ => 2,
    };
    // Stable: the first of equal rank stays first.
    found.sort_by_key(|(k, f)| (*k, rank(f)));
    found.dedup_by_key(|(k, _)| *k);
    found.into_iter().map(|(_, f)| f).collect()
}

/// The formula of one instance as the property's kind reads it (`always f` is `[] f`).
fn formula_of(kind: PropertyKind, f: &Ltl) -> Ltl {
    match kind {
        PropertyKind::Always => Ltl::always(f.clone()),
        PropertyKind::Eventually => Ltl::eventually(f.clone()),
        PropertyKind::Reachable => Ltl::always(Ltl::not(f.clone())),
        _ => f.clone(),
    }
}

/// On the run whose positions have the letters `letters` (each state's propositions with
/// its step's), repeating from position `loop_at` for ever: the first instance of `p` it
/// violates (its binding), if any. This is the reference semantics
/// ([`Ltl::holds_on_lasso`]), independent of the automaton the search used: `replay`
/// decides with it.
pub(crate) fn violated_on(p: &RunProperty, letters: &[Letter], loop_at: usize) -> Option<String> {
    p.instances.iter().find_map(|i| {
        let mut map = Vec::new();
        let f = localize(&formula_of(p.kind, &i.formula), &mut map);
        let word: Vec<u64> = letters.iter().map(|l| local(l, &map)).collect();
        let (prefix, cycle) = word.split_at(loop_at.min(word.len().saturating_sub(1)));
        (!f.holds_on_lasso(prefix, cycle)).then(|| i.binding.clone())
    })
}

impl Checker<'_> {
    /// One finding per property decided on runs; returns the product states searched.
    pub(super) fn runs_numbered(
        &self,
        out: &mut Vec<(usize, Finding)>,
        props: &[(usize, RunProperty)],
    ) -> usize {
        let (found, reached) = self.runs_taken(&std::sync::atomic::AtomicUsize::new(0), props);
        out.extend(found);
        reached
    }

    /// [`Checker::runs_numbered`] for the properties of `props` that this thread takes,
    /// each the next of `next` (shared with the threads that decide the others).
    pub(super) fn runs_taken(
        &self,
        next: &std::sync::atomic::AtomicUsize,
        props: &[(usize, RunProperty)],
    ) -> (Vec<(usize, Finding)>, usize) {
        let mut products = Products::default();
        let mut out = Vec::new();
        let take = || next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        while let Some((k, p)) = props.get(take()) {
            // Those about explanations are decided on their user's search (`verify_with`).
            if p.user.is_none() {
                out.push((*k, self.run_property(p, &mut products)));
            }
        }
        (out, products.reached)
    }

    /// The run of a violation, each step the transition the product took.
    /// The run of a violation, and how many times it goes round the loop.
    fn counterexample_of(&self, v: &Violation) -> (crate::findings::Counterexample, usize) {
        // The transition taken makes the `did` propositions the product read true.
        let want = |src: u32, k: u32, notes: &Vec<Note>| {
            self.conditions.runs.is_none_or(|r| {
                r.step_letter(0, notes.iter()) == self.facts.steps.get(&(src, k)).cloned()
            })
        };
        super::trace::counterexample_via(
            self.project,
            self.agent,
            self.graph,
            (&v.path, &v.path_via),
            (&v.cycle, &v.cycle_via),
            &want,
        )
    }

    fn run_property(&self, p: &RunProperty, products: &mut Products) -> Finding {
        let graph = self.graph;
        let succ = |i: u32| graph.successors(i);
        let may_end =
            |i: u32| bit(&self.facts.idle, i) || graph.successors(i).is_some_and(|e| e.is_empty());
        let facts = RunFacts {
            len: graph.len() as u32,
            initial: graph.initial as u32,
            successors: &succ,
            may_end: &may_end,
            letters: &self.facts.letters.ids,
            letter_table: &self.facts.letters.table,
            steps: &self.facts.steps,
            fairness: None,
        };
        let runs = ONE_AGENT_RUNS;
        let (status, message, v) = decide(&facts, p, (graph.complete(), runs), products);
        let mut f = self.finding("property", &p.name, p.span, status, String::new());
        // Undecided with every state expanded is the property's own doing (a formula too
        // long, memory out in its product), not the search's: no caveat then, nor for a
        // formula too long on a search cut short.
        let cut_short = !graph.complete() && !message.contains("too long");
        f.message = if status == Status::Unknown && cut_short {
            self.finding("property", &p.name, p.span, status, message)
                .message
        } else {
            message
        };
        if let Some(mut v) = v {
            let (cx, rounds) = self.counterexample_of(&v);
            if rounds > 1 {
                // The message counts the steps of the run shown.
                v.unroll(rounds);
                f.message = failure(p, &v);
            }
            f.counterexample = Some(cx);
        }
        f
    }
}

#[cfg(test)]
mod tests {
    //! The product search against a brute-force check of every lasso up to a bound, on
    //! random small graphs and formulas, with LTL's own semantics as the judge.
    use super::*;

    /// Each state's letter is found again through its index, whether it repeats the
    /// last one stored, an earlier one, or is new.
    #[test]
    fn product_edges_keep_each_nodes_list_across_chunks() {
        for via in [false, true] {
            let mut e = Csr::default();
            // Lists of 0 to 6 edges, and one longer than the first chunks.
            let len = |x: u32| match x {
                700 => 5000,
                x => (x % 7) as usize,
            };
            let edge = |x: u32, j: usize| x.wrapping_mul(31) ^ j as u32;
            let n = 3 * super::super::chunked::LIST_CHUNK as u32 / 4;
            for x in 0..n {
                e.begin(len(x), via).unwrap();
                for j in 0..len(x) {
                    e.push(edge(x, j), j as u32 + x);
                }
            }
            e.begin(0, via).unwrap();
            assert_eq!(e.len(), n as usize);
            assert!(e.to.chunks() > 3, "{} chunks", e.to.chunks());
            for x in 0..n {
                let want: Vec<u32> = (0..len(x)).map(|j| edge(x, j)).collect();
                assert_eq!(e.of(x), &want[..], "node {x}");
                if via {
                    let want: Vec<u32> = (0..len(x)).map(|j| j as u32 + x).collect();
                    assert_eq!(
                        e.via.as_ref().map(|v| v.list(x as usize)),
                        Some(&want[..]),
                        "node {x}"
                    );
                }
            }
            assert_eq!(e.via.is_some(), via);
        }
    }

    #[test]
    fn letters_keep_each_states_letter() {
        let mut letters = Letters::default();
        let pushed: Vec<u64> = vec![3, 3, 5, 3, 5, 5, 7, 0, 3, 7, 7];
        for &w in &pushed {
            letters.push(smallvec::smallvec![w]);
        }
        let got: Vec<u64> = (0..letters.ids.len())
            .map(|i| letters.table[letters.ids.get(i) as usize][0])
            .collect();
        assert_eq!(got, pushed);
        assert_eq!(letters.table.len(), 4, "each distinct letter once");
        // Letters of two words, and one-word letters that share a slot of the recent
        // ones, keep theirs too.
        let mut letters = Letters::default();
        let wide = |a: u64, b: u64| -> Letter { smallvec::smallvec![a, b] };
        let mut pushed: Vec<Letter> = Vec::new();
        for k in 0..5000u64 {
            pushed.push(match k % 3 {
                0 => wide(k % 7, 1),
                _ => smallvec::smallvec![k % 1500],
            });
        }
        for l in &pushed {
            letters.push(l.clone());
        }
        for (i, l) in pushed.iter().enumerate() {
            assert_eq!(&letters.table[letters.ids.get(i) as usize], l, "state {i}");
        }
        let distinct: std::collections::HashSet<&Letter> = pushed.iter().collect();
        assert_eq!(
            letters.table.len(),
            distinct.len(),
            "each distinct letter once"
        );
    }

    /// The `did` propositions a transition makes true are those its actions unify with,
    /// as found afresh, whether or not the memo of actions met them before; another
    /// agent's actions make none true.
    #[test]
    fn step_letters_are_the_did_patterns_unified_afresh() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
        let project = crate::model::project::load_project(&root).expect("the kitchen loads");
        let sem = crate::semantics::Semantics::new(&project).expect("the semantics");
        let (_, atomics) = crate::model::property::compile(&project).expect("the properties");
        let atoms = RunAtoms::new(&atomics, &sem);
        let afresh = |notes: &[Note]| {
            let mut out: Letter = smallvec::smallvec![0; atoms.words];
            for term in notes.iter().filter_map(|n| match n {
                Note::Action { term, .. } => Some(term),
                _ => None,
            }) {
                for (j, e) in atoms.evals.iter().enumerate() {
                    if matches!(e, Eval::Did(0, a) if unifier(a, term).is_some()) {
                        out[j / 64] |= 1 << (j % 64);
                    }
                }
            }
            out.iter().any(|&w| w != 0).then_some(out)
        };
        let mut states: Vec<crate::semantics::State> =
            sem.initial_states().into_iter().take(20).collect();
        let (mut k, mut did) = (0, 0);
        while k < states.len() && states.len() < 3_000 {
            for t in sem.successors(&states[k]) {
                let want = afresh(&t.notes);
                did += usize::from(want.is_some());
                for _ in 0..2 {
                    assert_eq!(atoms.step_letter(0, t.notes.iter()), want);
                }
                assert_eq!(atoms.step_letter(1, t.notes.iter()), None);
                states.push(t.next);
            }
            k += 1;
        }
        assert!(
            did > 10,
            "{did} transitions did something the properties name"
        );
    }

    struct Toy {
        initial: u32,
        succ: Vec<Vec<u32>>,
        ends: Vec<bool>,
        letters: Vec<u64>,
        /// Per state, per transition: the step letter.
        steps: Vec<Vec<u64>>,
        /// Per state, per transition: its agent, when loops must be fair to 2 agents.
        movers: Option<Vec<Vec<Option<u8>>>>,
    }

    impl Toy {
        fn enabled_at(&self, i: u32) -> u64 {
            self.movers.as_ref().map_or(0, |m| {
                m[i as usize].iter().flatten().fold(0, |b, &a| b | 1 << a)
            })
        }
    }

    impl RunGraph for Toy {
        fn len(&self) -> u32 {
            self.succ.len() as u32
        }
        fn initial(&self) -> u32 {
            self.initial
        }
        fn successors(&self, i: u32) -> Option<&[u32]> {
            Some(&self.succ[i as usize])
        }
        fn may_end(&self, i: u32) -> bool {
            self.ends[i as usize]
        }
        fn state_letter(&self, i: u32) -> u64 {
            self.letters[i as usize]
        }
        fn step_letter(&self, i: u32, k: u32) -> u64 {
            self.steps[i as usize][k as usize]
        }
        fn any_steps(&self) -> bool {
            self.steps.iter().flatten().any(|&l| l != 0)
        }
        fn fair_agents(&self) -> u8 {
            if self.movers.is_some() {
                2
            } else {
                0
            }
        }
        fn enabled(&self, i: u32) -> u64 {
            self.enabled_at(i)
        }
        fn mover(&self, i: u32, k: u32) -> Option<u8> {
            self.movers.as_ref().and_then(|m| m[i as usize][k as usize])
        }
    }

    struct Rng(u64);
    impl Rng {
        fn next(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n
        }
    }

    fn toy(r: &mut Rng) -> Toy {
        toy_of(r, 4)
    }

    /// A random toy graph of 1 to `max` states.
    fn toy_of(r: &mut Rng, max: u64) -> Toy {
        let n = 1 + r.next(max) as usize;
        let mut succ = Vec::new();
        let mut ends = Vec::new();
        let mut steps = Vec::new();
        for _ in 0..n {
            // Targets may repeat: two transitions to one state that differ in `did`.
            let s: Vec<u32> = (0..r.next(4)).map(|_| r.next(n as u64) as u32).collect();
            ends.push(s.is_empty() || r.next(4) == 0);
            // Propositions 0 and 1 are about states, 2 about steps (`did`).
            steps.push(s.iter().map(|_| r.next(2) << 2).collect());
            succ.push(s);
        }
        // Half the graphs are of two agents whose loops must be fair to both.
        let movers = (r.next(2) == 0).then(|| {
            succ.iter()
                .map(|s| {
                    s.iter()
                        .map(|_| match r.next(3) {
                            2 => None,
                            a => Some(a as u8),
                        })
                        .collect()
                })
                .collect()
        });
        Toy {
            initial: 1 + r.next(n as u64) as u32 % n as u32,
            letters: (0..n).map(|_| r.next(4)).collect(),
            succ,
            ends,
            steps,
            movers,
        }
    }

    fn formula(r: &mut Rng, depth: u32) -> Ltl {
        random_formula(r, depth, true)
    }

    /// A formula without temporal operators.
    fn proposition(r: &mut Rng, depth: u32) -> Ltl {
        random_formula(r, depth, false)
    }

    /// A random formula over propositions 0 to 2, with temporal operators or without.
    fn random_formula(r: &mut Rng, depth: u32, temporal: bool) -> Ltl {
        if depth == 0 || r.next(4) == 0 {
            return Ltl::Prop(r.next(3) as u32);
        }
        let a = random_formula(r, depth - 1, temporal);
        type Unary = fn(Ltl) -> Ltl;
        type Binary = fn(Ltl, Ltl) -> Ltl;
        let (unary, binary): (&[Unary], &[Binary]) = match temporal {
            true => (
                &[Ltl::not, Ltl::next, Ltl::always, Ltl::eventually],
                &[
                    Ltl::and,
                    Ltl::or,
                    Ltl::until,
                    Ltl::release,
                    Ltl::weak_until,
                    Ltl::leads_to,
                    Ltl::implies,
                ],
            ),
            false => (&[Ltl::not], &[Ltl::and, Ltl::or, Ltl::implies, Ltl::iff]),
        };
        let k = r.next((unary.len() + binary.len()) as u64) as usize;
        match unary.get(k) {
            Some(f) => f(a),
            None => binary[k - unary.len()](a, random_formula(r, depth - 1, temporal)),
        }
    }

    /// Whether every state of the toy is reachable from an initial one, as every state of
    /// a search's graph is.
    fn all_reachable(g: &Toy) -> bool {
        let mut seen: Vec<bool> = (0..g.len()).map(|i| i < g.initial).collect();
        let mut todo: Vec<u32> = (0..g.initial).collect();
        while let Some(i) = todo.pop() {
            for &j in &g.succ[i as usize] {
                if !std::mem::replace(&mut seen[j as usize], true) {
                    todo.push(j);
                }
            }
        }
        seen.iter().all(|&s| s)
    }

    #[test]
    fn one_pass_decides_an_invariant_as_the_product_does() {
        let mut r = Rng(0x2545_f491_4f6c_dd1d);
        let (mut held, mut failed) = (0, 0);
        let mut scratch = Scratch::default();
        for case in 0..4000 {
            let g = toy(&mut r);
            if !all_reachable(&g) {
                continue;
            }
            let body = proposition(&mut r, 3);
            let product = Product::new(&g, &Ltl::always(body.clone()))
                .and_then(|p| p.search(&mut scratch).expect("memory"))
                .is_none();
            assert_eq!(
                holds_everywhere(&g, &body),
                product,
                "case {case}: {body:?}"
            );
            match product {
                true => held += 1,
                false => failed += 1,
            }
        }
        assert!(held > 300 && failed > 300, "{held} held, {failed} failed");
    }

    #[test]
    fn leads_to_and_its_instances_together_are_responses() {
        let (p, q) = (Ltl::Prop(0), Ltl::Prop(1));
        let responds = |f: &Ltl| {
            let body = always_body(f).expect("a [] formula");
            pieces(body)
                .is_some_and(|ps| ps.iter().all(|piece| matches!(piece, Piece::Responds(..))))
        };
        // `a ~> q`, `[] (a -> <> q)` as the manifest writes it, and the conjunction of two
        // instances as `decide` builds it.
        assert!(responds(&Ltl::leads_to(p.clone(), q.clone())));
        let written = Ltl::always(Ltl::implies(p.clone(), Ltl::eventually(q.clone())));
        assert!(responds(&written));
        let body = |a: u32, b: u32| {
            always_body(&Ltl::leads_to(Ltl::Prop(a), Ltl::Prop(b)))
                .expect("a [] formula")
                .clone()
        };
        assert!(responds(&Ltl::always(Ltl::and(body(0, 1), body(2, 3)))));
        // A conjunction about one position is one piece, read in one pass.
        let both = Ltl::and(Ltl::Prop(0), Ltl::Prop(1));
        assert!(matches!(pieces(&both).as_deref(), Some([Piece::At(_)])));
        // Not a response: `<>` under `X`, or `U` with another left side.
        let next = Ltl::always(Ltl::or(p.clone(), Ltl::next(Ltl::eventually(q.clone()))));
        assert!(pieces(always_body(&next).expect("a [] formula")).is_none());
        let until = Ltl::always(Ltl::or(p, Ltl::until(Ltl::Prop(2), q)));
        assert!(pieces(always_body(&until).expect("a [] formula")).is_none());
    }

    /// A judge answers as the formulas do at every letter: kept per value of the
    /// propositions it reads (here past the 16th, where letters are past the table of
    /// every letter), or judged anew when it reads more than it keeps.
    #[test]
    fn a_judge_answers_as_its_formulas_do() {
        let mut r = Rng(0x2545_f491_4f6c_dd1d);
        let few = |r: &mut Rng| {
            let (a, b) = (
                Ltl::Prop(17 + r.next(40) as u32),
                Ltl::Prop(r.next(64) as u32),
            );
            match r.next(3) {
                0 => Ltl::and(a, Ltl::not(b)),
                1 => Ltl::or(a, b),
                _ => a,
            }
        };
        let many = (0..20).map(Ltl::Prop).reduce(Ltl::and).expect("a conjunct");
        for case in 0..200 {
            let (a, q) = match case % 4 {
                0 => (many.clone(), few(&mut r)),
                _ => (few(&mut r), few(&mut r)),
            };
            let mut judge = Judge::new((&a, &q));
            assert_eq!(judge.read.is_none(), case % 4 == 0, "case {case}");
            for _ in 0..64 {
                // Letters of few and of many propositions, each judged twice.
                let letter = match r.next(2) {
                    0 => r.0 ^ (r.0 << 7),
                    _ => ((1u64 << 20) - 1) | (r.0 & (1u64 << 63)),
                };
                r.next(2);
                let want = (a.at_letter(letter), q.at_letter(letter));
                let want = (want.0.expect("no temporal operator"), want.1.expect("none"));
                assert_eq!(judge.at(letter), want, "case {case}, letter {letter:#x}");
                assert_eq!(
                    judge.at(letter),
                    want,
                    "case {case}, letter {letter:#x}, again"
                );
            }
        }
    }

    #[test]
    fn one_pass_per_response_decides_as_the_product_does() {
        let mut r = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut held, mut failed, mut unreachable) = (0, 0, 0);
        let mut scratch = Scratch::default();
        for case in 0..6000 {
            let mut g = toy_of(&mut r, if case % 2 == 0 { 4 } else { 10 });
            // The pass is taken only where no fairness of agents is owed.
            g.movers = None;
            // A third of the graphs without step letters.
            if r.next(3) == 0 {
                g.steps.iter_mut().flatten().for_each(|l| *l = 0);
            }
            // One to three conjuncts, as the instances of a property are: responses, in
            // both forms, and now and then a formula about one position.
            let conjuncts = 1 + r.next(3);
            let body = (0..conjuncts)
                .map(|_| {
                    let (a, q) = (proposition(&mut r, 2), proposition(&mut r, 2));
                    match r.next(5) {
                        0 => a,
                        1 => Ltl::or(Ltl::eventually(q), a),
                        _ => always_body(&Ltl::leads_to(a, q))
                            .expect("a [] formula")
                            .clone(),
                    }
                })
                .reduce(Ltl::and)
                .expect("a conjunct");
            let Some(pieces) = pieces(&body) else {
                continue;
            };
            let product = Product::new(&g, &Ltl::always(body.clone()))
                .and_then(|p| p.search(&mut scratch).expect("memory"))
                .is_none();
            let mut visited = 0;
            let pass = holds_by_pieces(&g, &pieces, &mut scratch, &mut visited);
            if all_reachable(&g) {
                assert_eq!(pass, product, "case {case}: {body:?}");
            } else {
                // A state no run reaches may only make the property look violated.
                assert!(!pass || product, "case {case}: {body:?}");
                unreachable += 1;
                continue;
            }
            match product {
                true => held += 1,
                false => failed += 1,
            }
        }
        assert!(
            held > 500 && failed > 500 && unreachable > 100,
            "{held} held, {failed} failed, {unreachable} with unreachable states"
        );
    }

    /// Every lasso of the toy with at most `bound` transitions before it closes: the
    /// letters of its positions and where the repetition starts.
    fn lassos(g: &Toy, bound: usize) -> Vec<(Vec<u64>, usize)> {
        let mut out = Vec::new();
        // (states, letters)
        // (states, letters, transitions taken)
        type Walked = (Vec<u32>, Vec<u64>, Vec<u32>);
        let mut stack: Vec<Walked> = (0..g.initial)
            .map(|i| (vec![i], vec![g.letters[i as usize]], Vec::new()))
            .collect();
        // A loop over positions e..m (transitions e..m-1) is fair when every agent that can
        // move in each of its states moves in it.
        let fair = |states: &[u32], ks: &[u32], e: usize| {
            let owed = states[e..states.len() - 1]
                .iter()
                .fold(u64::MAX, |b, &i| b & g.enabled_at(i));
            let moved = states[e..states.len() - 1]
                .iter()
                .zip(&ks[e..])
                .filter_map(|(&i, &k)| g.mover(i, k))
                .fold(0u64, |b, a| b | 1 << a);
            g.movers.is_none() || owed & !moved == 0
        };
        while let Some((states, letters, ks)) = stack.pop() {
            let last = *states.last().unwrap_or(&0);
            if g.ends[last as usize] {
                let mut l = letters.clone();
                l.push(g.letters[last as usize]);
                let at = l.len() - 1;
                out.push((l, at));
            }
            if states.len() > bound {
                continue;
            }
            for (k, &j) in g.succ[last as usize].iter().enumerate() {
                let mut s2 = states.clone();
                let mut l2 = letters.clone();
                let mut k2 = ks.clone();
                s2.push(j);
                l2.push(g.letters[j as usize] | g.steps[last as usize][k]);
                k2.push(k as u32);
                let m = s2.len() - 1;
                for (e, _) in s2[..m].iter().enumerate().filter(|(_, &x)| x == j) {
                    if fair(&s2, &k2, e) {
                        out.push((l2.clone(), e + 1));
                    }
                }
                stack.push((s2, l2, k2));
            }
        }
        out
    }

    /// The word of a violation the product reported (a bad prefix is continued by first
    /// successors until it closes).
    fn word_of(g: &Toy, v: &Violation) -> (Vec<u64>, usize) {
        // The step's letter by the transition the product says it took.
        let by = |i: u32, j: u32, k: u32| {
            assert_eq!(g.succ[i as usize][k as usize], j, "transition {k} of {i}");
            g.letters[j as usize] | g.steps[i as usize][k as usize]
        };
        let letter = |i: u32, j: u32| {
            let k = g.succ[i as usize].iter().position(|&x| x == j).unwrap_or(0);
            by(i, j, k as u32)
        };
        let mut states = v.path.clone();
        let mut letters = vec![g.letters[states[0] as usize]];
        assert_eq!(v.path_via.len() + 1, v.path.len());
        for (w, &k) in states.windows(2).zip(&v.path_via) {
            letters.push(by(w[0], w[1], k));
        }
        if !v.cycle.is_empty() {
            let start = letters.len();
            assert_eq!(v.cycle_via.len() + 1, v.cycle.len());
            for (w, &k) in v.cycle.windows(2).zip(&v.cycle_via) {
                letters.push(by(w[0], w[1], k));
            }
            return (letters, start);
        }
        loop {
            let last = *states.last().unwrap_or(&0);
            if v.ends || g.ends[last as usize] {
                letters.push(g.letters[last as usize]);
                let at = letters.len() - 1;
                return (letters, at);
            }
            let j = g.succ[last as usize][0];
            letters.push(letter(last, j));
            if let Some(e) = states.iter().position(|&x| x == j) {
                return (letters, e + 1);
            }
            states.push(j);
        }
    }

    #[test]
    fn the_product_finds_a_violation_exactly_when_some_lasso_violates() {
        let mut r = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut found, mut held) = (0, 0);
        // One scratch for every search, as the products of one graph share it.
        let mut scratch = Scratch::default();
        for case in 0..3000 {
            let g = toy(&mut r);
            let f = formula(&mut r, 3);
            let v = Product::new(&g, &f).and_then(|p| p.search(&mut scratch).expect("memory"));
            let brute = lassos(&g, 5)
                .into_iter()
                .find(|(w, at)| !f.holds_on_lasso(&w[..*at], &w[*at..]));
            match (&v, &brute) {
                (Some(v), _) => {
                    if !v.cycle.is_empty() {
                        // The reported loop is fair.
                        let sources = &v.cycle[..v.cycle.len() - 1];
                        let owed = sources.iter().fold(u64::MAX, |b, &i| b & g.enabled_at(i));
                        let moved = sources
                            .iter()
                            .zip(&v.cycle_via)
                            .filter_map(|(&i, &k)| g.mover(i, k))
                            .fold(0u64, |b, a| b | 1 << a);
                        assert!(
                            g.movers.is_none() || owed & !moved == 0,
                            "case {case}: an unfair loop {:?}",
                            v.cycle
                        );
                    }
                    let (w, at) = word_of(&g, v);
                    assert!(
                        !f.holds_on_lasso(&w[..at], &w[at..]),
                        "case {case}: {f:?}: the reported run {:?} / {:?} satisfies it",
                        v.path,
                        v.cycle
                    );
                    found += 1;
                }
                (None, Some((w, at))) => {
                    panic!("case {case}: {f:?}: missed the violating lasso {w:?} from {at}")
                }
                (None, None) => held += 1,
            }
        }
        // Both outcomes are exercised.
        assert!(found > 300 && held > 300, "{found} violated, {held} held");
    }
}

/// On a project rather than random graphs: `verify`'s verdict on each `ltl` property equals
/// a check of every lasso of the agent's runs, each judged by LTL's own semantics (the
/// project is small enough to enumerate every run up to its loops).
#[cfg(test)]
mod on_a_project {
    use super::*;
    use crate::semantics::State;

    const FORMULAS: &[&str] = &[
        "[] .count(robotAt(_), 1)",
        "[] robotAt(table)",
        "<> not dirty(table)",
        "requested(wipeTable) ~> not dirty(table)",
        "requested(rest) ~> not dirty(table)",
        "dirty(table) U did(wipe(table))",
        "dirty(table) W did(wipe(table))",
        "did(wipe(table)) R dirty(table)",
        "X robotAt(table)",
        "[] (did(navigateTo(table)) -> X robotAt(cupboard))",
        "[] (intends(wipeTable) -> requested(wipeTable))",
        "<> intends(rest)",
        "[] not desires(rest)",
        "<> [] (robotAt(table) | robotAt(cupboard))",
        // An instance per place: decided together when they all hold.
        "[] not robotAt(L)",
        "[] (did(wipe(L)) -> robotAt(L))",
        "[] (did(navigateTo(L)) -> robotAt(L))",
        "[] (dirty(L) -> robotAt(L))",
        "requested(wipeTable) ~> robotAt(L)",
        "dirty(L) ~> not dirty(L)",
    ];

    /// A patrol that never ends: its runs loop.
    const LOOPING: &[&str] = &[
        "<> [] robotAt(table)",
        "[] <> robotAt(dishwasher)",
        "[] (did(navigateTo(table)) -> X did(navigateTo(dishwasher)))",
        "[] (robotAt(table) -> <> robotAt(dishwasher))",
        "requested(patrol) U did(navigateTo(dishwasher))",
        "<> not requested(patrol)",
        "[] (intends(patrol) | not requested(patrol))",
    ];

    #[test]
    fn verify_agrees_with_every_lasso_of_a_projects_runs() {
        // Runs that end, and runs that loop for ever.
        assert!(lassos_agree("tests/verify/ltl_table", FORMULAS) >= 3);
        assert!(lassos_agree("tests/verify/livelock", LOOPING) >= 2);
    }

    /// Checks `formulas` on the project `base` both ways; the lassos enumerated.
    fn lassos_agree(base: &str, formulas: &[&str]) -> usize {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let dir = std::env::temp_dir().join(format!(
            "bdi-check-runs-lassos-{}-{}",
            std::process::id(),
            base.replace('/', "-")
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let base = root.join(base);
        std::fs::copy(base.join("agent.asl"), dir.join("agent.asl")).unwrap();
        let manifest = std::fs::read_to_string(base.join("bdi-check.toml"))
            .unwrap()
            .replace("\"../../../specs/", &format!("\"{}/specs/", root.display()));
        let props: String = formulas
            .iter()
            .enumerate()
            .map(|(i, f)| format!("[[property]]\nname = \"p{i}\"\nltl = \"{f}\"\n"))
            .collect();
        std::fs::write(dir.join("bdi-check.toml"), format!("{manifest}\n{props}")).unwrap();
        let project = crate::model::project::load_project(&dir).unwrap_or_else(|e| panic!("{e:?}"));
        let limits = super::super::explore::Limits {
            max_states: 100_000,
            max_depth: 1_000,
            timeout: None,
        };
        let v =
            super::super::verify_with(&project, limits, &Default::default(), |_, _, _, _| {}, &[])
                .unwrap_or_else(|e| panic!("{e:?}"));
        let sem = crate::semantics::Semantics::new(&project).unwrap_or_else(|e| panic!("{e:?}"));
        let (props, atomics) = crate::model::property::compile(&project).unwrap();
        let atoms = RunAtoms::new(&atomics, &sem);
        let mut violated = vec![false; props.len()];
        let mut judge = |letters: &[Letter], at: usize| {
            for (j, p) in props.iter().enumerate() {
                if violated_on(p, letters, at).is_some() {
                    violated[j] = true;
                }
            }
        };
        // Depth first over runs; a run closes where it may end (it stays) or where a state
        // repeats (the path since repeats).
        let mut stack: Vec<(Vec<State>, Vec<Letter>)> = sem
            .initial_states()
            .into_iter()
            .map(|s| {
                let l = atoms.state_letter(&s);
                (vec![s], vec![l])
            })
            .collect();
        let mut lassos = 0;
        while let Some((states, letters)) = stack.pop() {
            let last = states.last().expect("a state");
            let succ = sem.successors(last);
            if last.is_idle() || succ.is_empty() {
                let mut l = letters.clone();
                l.push(atoms.state_letter(last));
                let at = l.len() - 1;
                judge(&l, at);
                lassos += 1;
            }
            assert!(states.len() < 64, "runs this long: the project has grown");
            for t in succ {
                let mut l = letters.clone();
                let mut x = atoms.state_letter(&t.next);
                if let Some(d) = atoms.step_letter(0, t.notes.iter()) {
                    x.iter_mut().zip(d).for_each(|(w, y)| *w |= y);
                }
                l.push(x);
                if let Some(e) = states.iter().position(|s| *s == t.next) {
                    judge(&l, e + 1);
                    lassos += 1;
                    continue;
                }
                let mut s2 = states.clone();
                s2.push(t.next);
                stack.push((s2, l));
            }
        }
        for (j, p) in props.iter().enumerate() {
            let f = v
                .findings
                .iter()
                .find(|f| f.id == format!("property:{}", p.name))
                .expect("a finding per property");
            assert_eq!(
                f.status == Status::Fail,
                violated[j],
                "{}: verify says {}",
                formulas[j],
                f.message
            );
        }
        assert!(violated.iter().any(|&x| x) && violated.iter().any(|&x| !x));
        let _ = std::fs::remove_dir_all(&dir);
        lassos
    }
}
