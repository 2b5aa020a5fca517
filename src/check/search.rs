//! What the search records as it goes, for the checks that run after it: per state, which
//! of the checked conditions hold, its pending requests and whether it is idle (computed
//! in the exploring threads, since no state is kept); per transition, the failures it shows.

use super::explore::{explore_with, Graph, Limits, Options, Successors};
use super::failures::Failures;
use super::model::{AgentState, CycleNotes, Model};
use super::recent::{recently, Recently};
use super::runs::{Letter, RunAtoms};
use crate::model::cond::Cond;
use crate::semantics::compiled::{Annex, Annexed};
use std::collections::hash_map::Entry;
use std::collections::HashMap;

/// What the search keeps of every state ([`search_agent`]): a number for each label, and
/// where each state goes with the numbers of its transitions' labels.
pub(super) type Keep<'a, M> = (
    &'a (dyn Fn(&<M as Model>::Label) -> u32 + Sync),
    &'a mut dyn FnMut(<M as Model>::State, smallvec::SmallVec<[u32; 4]>),
);

/// Plans, by index.
pub(super) type Plans = smallvec::SmallVec<[u32; 4]>;

/// What the search records about one state, computed where the state is found.
struct Summary {
    holds: Holds,
    pending: u64,
    idle: bool,
    /// The atomic propositions of the run properties that hold ([`RunAtoms`]).
    letter: Letter,
}

/// The state conditions evaluated on every state, in one numbering: invariants, then
/// properties, then the plan pairs whose overlap lint asks about.
pub(super) struct Conditions<'a> {
    pub(super) invariants: Vec<&'a Cond>,
    pub(super) props: Vec<&'a Cond>,
    pub(super) overlaps: Vec<(u32, u32)>,
    /// The atomic propositions of the properties decided on runs, if any.
    pub(super) runs: Option<&'a RunAtoms>,
}

impl Conditions<'_> {
    pub(super) fn len(&self) -> usize {
        self.invariants.len() + self.props.len() + self.overlaps.len()
    }

    /// Which invariants and properties hold on `beliefs` (bit `j` for condition `j`), and
    /// which propositions of the run properties about beliefs alone.
    fn on_beliefs(&self, beliefs: &crate::model::atoms::AtomSet) -> (Holds, Letter) {
        let mut holds = Holds::from_elem(0u64, self.len().div_ceil(64).max(1));
        let conds = self.invariants.iter().chain(&self.props);
        for (j, c) in conds.enumerate() {
            if c.eval(beliefs) {
                holds[j / 64] |= 1 << (j % 64);
            }
        }
        let letter = (self.runs)
            .map(|r| r.beliefs_letter(beliefs))
            .unwrap_or_default();
        (holds, letter)
    }

    /// `applicable`: the plans applicable to the first event of a state; `memo`: the
    /// conditions' values per belief base, of this search's states.
    fn summarize<S: AgentState>(
        &self,
        s: &S,
        applicable: &impl Fn(&S) -> Plans,
        memo: &ByBeliefs,
    ) -> Summary {
        let (mut holds, on_beliefs) = match s.beliefs_key() {
            Some(key) => memo.get((key, s.beliefs_annex()), || self.on_beliefs(s.beliefs())),
            None => self.on_beliefs(s.beliefs()),
        };
        let mut set = |j: usize| holds[j / 64] |= 1 << (j % 64);
        if !self.overlaps.is_empty() {
            let applicable = applicable(s);
            let base = self.invariants.len() + self.props.len();
            for (k, (a, b)) in self.overlaps.iter().enumerate() {
                if applicable.contains(a) && applicable.contains(b) {
                    set(base + k);
                }
            }
        }
        Summary {
            holds,
            pending: s.pending_requests(),
            idle: s.is_idle(),
            letter: (self.runs)
                .map(|r| r.state_letter_on(on_beliefs, s))
                .unwrap_or_default(),
        }
    }
}

/// Bit `j`: condition `j` of [`Conditions`] holds.
type Holds = smallvec::SmallVec<[u64; 2]>;

/// One shard of [`ByBeliefs`]: per belief base (by address), the conditions' values and
/// the propositions about beliefs.
type OnBeliefs = HashMap<usize, (Holds, Letter), crate::semantics::compiled::Quick>;

/// Shards of [`ByBeliefs`], each behind its own lock.
const SHARDS: usize = 64;

/// The invariants' and properties' values per belief base ([`AgentState::beliefs_key`]),
/// for one search, and the run properties' propositions about beliefs: far fewer belief
/// bases than states occur. Evaluating the conditions on every state took a third of the
/// exploring threads' time, and the propositions of the kitchen's four `ltl` properties
/// another quarter of the search. The first search of a compiled cycle keeps them with
/// the belief bases themselves ([`AgentState::beliefs_annex`]); reading them from the
/// shared map (behind the threads' caches) was 8% of the 6-cup kitchen's search, most of
/// it a probe that missed the processor's cache. Another search keeps them in the map.
struct ByBeliefs {
    /// Keyed by address with the quick hasher: SipHash on every state was a tenth of
    /// summarizing it.
    shards: Vec<std::sync::Mutex<OnBeliefs>>,
    /// Tells this memo's entries from another's in the threads' [`RECENT_BELIEFS`].
    serial: u64,
}

/// How many entries of a [`ByBeliefs`] each thread keeps at hand (a power of two).
const RECENT: usize = 1 << 12;

thread_local! {
    /// The entries of a [`ByBeliefs`] this thread read last: a job's states are mostly
    /// successors of a few states, and share their belief bases. 87% of the reads of the
    /// 5-cup search (236 k bases) are answered here, without the shard's lock and the
    /// probe's cache miss, a third of summarizing a state.
    static RECENT_BELIEFS: Recently<usize, (Holds, Letter)> =
        const { std::cell::RefCell::new(Vec::new()) };
}

impl ByBeliefs {
    fn new() -> ByBeliefs {
        ByBeliefs {
            shards: (0..SHARDS).map(|_| Default::default()).collect(),
            serial: super::recent::serial(),
        }
    }

    /// The values for the belief base `key`: kept in its `annex` when this memo owns it
    /// (or is the first to ask), else in the shared map.
    fn get(
        &self,
        (key, annex): (usize, Option<&Annex>),
        compute: impl FnOnce() -> (Holds, Letter),
    ) -> (Holds, Letter) {
        match annex.map(|a| (a, a.read(self.serial))) {
            Some((_, Annexed::Mine(words))) => {
                let (holds, letter) = words[1..].split_at(words[0] as usize);
                return (Holds::from_slice(holds), Letter::from_slice(letter));
            }
            Some((a, Annexed::Empty)) => {
                let (holds, letter) = compute();
                let words = std::iter::once(holds.len() as u64)
                    .chain(holds.iter().copied())
                    .chain(letter.iter().copied())
                    .collect();
                a.set(self.serial, words);
                return (holds, letter);
            }
            Some((_, Annexed::Other)) | None => {}
        }
        recently(
            &RECENT_BELIEFS,
            RECENT,
            (self.serial, key),
            || self.shared(key, compute),
            // Copied as slices: SmallVec's `clone` goes through a generic `extend`, which
            // cost more than the lookup.
            |(holds, letter)| (Holds::from_slice(holds), Letter::from_slice(letter)),
        )
    }

    /// [`ByBeliefs::get`] from the shared map.
    fn shared(&self, key: usize, compute: impl FnOnce() -> (Holds, Letter)) -> (Holds, Letter) {
        // Keys are addresses: their low bits are alignment, their middle bits vary.
        let shard = &self.shards[(key >> 6) % SHARDS];
        // A panicking search thread is re-raised by the explorer; the map it left is
        // consistent (every insertion is one call).
        let lock = || shard.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((holds, letter)) = lock().get(&key) {
            return (Holds::from_slice(holds), Letter::from_slice(letter));
        }
        let h = compute();
        lock().insert(key, h.clone());
        h
    }
}

/// Per-state facts kept for the checks after the search.
#[derive(Default)]
pub(super) struct Facts {
    /// For each condition: the first state where it holds and the first where it does not.
    pub(super) first_holds: Vec<Option<u32>>,
    pub(super) first_fails: Vec<Option<u32>>,
    /// Bit per state: idle.
    pub(super) idle: Vec<u64>,
    /// Per state: an index into `masks` (the requests pending there), in as few bytes as
    /// the indices need ([`super::chunked::Narrow`]), in chunks that never move: a vector
    /// of millions would be copied at each doubling.
    pub(super) pending: super::chunked::Narrow,
    pub(super) masks: Vec<u64>,
    /// Keyed with the quick hasher: the merging thread looks a mask up for most states
    /// (their parent's seldom has the same), and SipHash made that 3% of the search.
    pub(super) mask_ids: HashMap<u64, u32, crate::semantics::compiled::Quick>,
    /// The last mask recorded and its index: most states have their parent's.
    pub(super) last_mask: Option<(u64, u32)>,
    /// Per `eventually` property: bit per state, set when the property does not hold.
    pub(super) bad: Vec<Vec<u64>>,
    /// Per state: the run properties' propositions that hold there; empty when no property
    /// is decided on runs.
    pub(super) letters: super::runs::Letters,
    /// Per transition (source, position) that did an action some `did` names: those
    /// propositions.
    pub(super) steps: super::runs::StepLetters,
    /// Bit per condition: whether its first state where it holds (`[0]`) and where it
    /// fails (`[1]`) are still to be found. Most conditions hold in every state, so most
    /// states have nothing to record: looking at every condition of every state was a
    /// third of the merging thread's instructions (4-cup kitchen).
    pub(super) unknown: Option<[Vec<u64>; 2]>,
}

pub(super) use super::explore::{bit, set_bit};

impl Facts {
    fn record(&mut self, i: u32, s: Summary, eventually: &[usize]) {
        let n = self.first_holds.len();
        let [holds_unknown, fails_unknown] = self
            .unknown
            .get_or_insert_with(|| [super::liveness::all_of(n), super::liveness::all_of(n)]);
        for (w, (h, f)) in holds_unknown.iter_mut().zip(fails_unknown).enumerate() {
            let holds = s.holds.get(w).copied().unwrap_or(0);
            for (bits, unknown, first) in [
                (holds & *h, h, &mut self.first_holds),
                (!holds & *f, f, &mut self.first_fails),
            ] {
                *unknown &= !bits;
                let mut bits = bits;
                while bits != 0 {
                    first[w * 64 + bits.trailing_zeros() as usize] = Some(i);
                    bits &= bits - 1;
                }
            }
        }
        set_bit(&mut self.idle, i, s.idle);
        let id = match self.last_mask {
            Some((mask, id)) if mask == s.pending => id,
            _ => {
                let next = self.masks.len() as u32;
                let id = *self.mask_ids.entry(s.pending).or_insert(next);
                if id == next {
                    self.masks.push(s.pending);
                }
                self.last_mask = Some((s.pending, id));
                id
            }
        };
        if self.pending.push(id).is_err() {
            // As a vector that cannot grow does.
            std::alloc::handle_alloc_error(std::alloc::Layout::new::<u32>());
        }
        for (b, &j) in self.bad.iter_mut().zip(eventually) {
            set_bit(b, i, !bit(&s.holds, j as u32));
        }
        if !s.letter.is_empty() {
            self.letters.push(s.letter);
        }
    }

    pub(super) fn pending(&self, i: u32) -> u64 {
        self.masks[self.pending.get(i as usize) as usize]
    }
}

/// The agent's search (on the reference or the compiled model: they have the same
/// fingerprints), recording each state's facts and each transition's failures. Returns
/// the graph, the first equivariance violation `equivariance` reports, and whether a
/// complete search left states unchecked (stored after `--timeout` passed). With `keep`,
/// every stored state is handed to its sink in state number order, with the numbers its
/// function gives the labels of its transitions, in transition order (none when it was
/// not expanded).
#[allow(clippy::too_many_arguments)]
pub(super) fn search_agent<M>(
    model: &M,
    (conditions, applicable): (&Conditions, impl Fn(&M::State) -> Plans + Sync),
    equivariance: impl Fn(&M::State, Option<&Successors<M>>) -> Option<String> + Sync,
    (limits, opts): (Limits, &Options),
    (facts, eventually, failures): (&mut Facts, &[usize], &mut Failures),
    keep: Option<Keep<M>>,
    progress: impl FnMut(usize, u32, f64),
) -> (Graph, Option<String>, bool)
where
    M: Model + Sync,
    M::State: AgentState + Send + Sync,
    M::Label: CycleNotes + Send,
{
    let (number, mut sink) = keep.unzip();
    let mut not_equivariant = None;
    // Past `--timeout` the search stops, and the states it still stores are not checked
    // for equivariance (the check costs more than the state): a search that completes
    // all the same says the check was not made everywhere.
    let deadline = limits
        .timeout
        .and_then(|t| std::time::Duration::try_from_secs_f64(t).ok())
        .and_then(|d| std::time::Instant::now().checked_add(d));
    let unchecked = std::sync::atomic::AtomicBool::new(false);
    let mut steps = super::runs::StepLetters::default();
    // The `did` propositions per notes (by identity), kept whether or not there are run
    // properties (the notes met): the merging thread reads them on every transition, and
    // finding them anew (a lock and a term hashed per action) was 4% of the 5-cup
    // kitchen's search with its `ltl` properties.
    let mut did: HashMap<[usize; 4], Option<Letter>, crate::semantics::compiled::Quick> =
        HashMap::default();
    let by_beliefs = ByBeliefs::new();
    let graph = explore_with(
        model,
        limits,
        opts,
        |s, succ| {
            let late = deadline.is_some_and(|d| std::time::Instant::now() > d);
            if late {
                unchecked.store(true, std::sync::atomic::Ordering::Relaxed);
            }
            // Boxed: the summary crosses to the merging thread, a rare message in it.
            let unequal = if late { None } else { equivariance(s, succ) }.map(Box::new);
            // Numbered in the exploring threads: the merging one bounds the search. The
            // state is kept from the merge's own copy, and does not cross with them.
            let labels = number.map(|number| {
                (succ.iter())
                    .flat_map(|v| v.iter().map(|(l, _)| number(l)))
                    .collect()
            });
            (
                conditions.summarize(s, &applicable, &by_beliefs),
                unequal,
                labels,
            )
        },
        |i, s: &M::State, (sum, unequal, labels)| {
            if not_equivariant.is_none() {
                not_equivariant = unequal.map(|m| *m);
            }
            if let (Some(sink), Some(labels)) = (sink.as_mut(), labels) {
                sink(s.clone(), labels);
            }
            facts.record(i, sum, eventually)
        },
        |src, k, label: &M::Label, fp| {
            let step_letter = || {
                conditions
                    .runs
                    .and_then(|r| r.step_letter(0, label.notes()))
            };
            // Failures keep the first transition that shows each, and `applied` is a set:
            // notes met before (by identity) add nothing to them, and reading them again on
            // every transition was 4% of the merging thread at 6 cups.
            let (letter, new) = match label.identity() {
                Some(key) => match did.entry(key) {
                    Entry::Occupied(e) => (e.get().clone(), false),
                    Entry::Vacant(e) => (e.insert(step_letter()).clone(), true),
                },
                None => (step_letter(), true),
            };
            if new {
                failures.record(src, k, fp, label.notes());
            }
            if let Some(l) = letter {
                steps.insert((src, k), l);
            }
        },
        progress,
    );
    facts.steps = steps;
    let unchecked = unchecked.into_inner() && graph.complete();
    (graph.cast(), not_equivariant, unchecked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beliefs_read_recently_are_the_same_memos_and_keys() {
        // Two searches' memos with the same keys and different values, read in turns on
        // one thread, over more keys than a thread keeps at hand.
        let (a, b) = (ByBeliefs::new(), ByBeliefs::new());
        let value = |memo: u64, key: usize| {
            let holds = Holds::from_slice(&[memo, key as u64]);
            (holds, Letter::from_slice(&[key as u64 * 3 + memo]))
        };
        let computed = std::cell::Cell::new(0);
        for round in 0..3 {
            for key in (0..3 * RECENT).chain((0..3 * RECENT).rev()) {
                for (memo, m) in [(1, &a), (2, &b)] {
                    let got = m.get((key, None), || {
                        computed.set(computed.get() + 1);
                        value(memo, key)
                    });
                    assert_eq!(got, value(memo, key), "round {round}, key {key}");
                }
            }
        }
        // Each value computed once, whatever the thread kept.
        assert_eq!(computed.get(), 2 * 3 * RECENT);
    }

    #[test]
    fn beliefs_annexed_are_the_first_memos_and_the_others_keep_theirs() {
        // Two searches' memos over the same belief bases, each base with its annex: the
        // first to ask keeps its values there, the other in its map; each value is
        // computed once, and neither reads the other's.
        let (a, b) = (ByBeliefs::new(), ByBeliefs::new());
        let annexes: Vec<Annex> = (0..100).map(|_| Annex::default()).collect();
        let value = |memo: u64, key: usize| {
            let holds = Holds::from_slice(&vec![memo; key % 3]);
            (holds, Letter::from_slice(&vec![key as u64; key % 2]))
        };
        let computed = std::cell::Cell::new(0);
        for round in 0..3 {
            for (key, annex) in annexes.iter().enumerate() {
                // `b` asks first for odd bases.
                let order = match key % 2 {
                    0 => [(1, &a), (2, &b)],
                    _ => [(2, &b), (1, &a)],
                };
                for (memo, m) in order {
                    let got = m.get((key, Some(annex)), || {
                        computed.set(computed.get() + 1);
                        value(memo, key)
                    });
                    assert_eq!(got, value(memo, key), "round {round}, key {key}");
                }
                let first = if key % 2 == 0 { &a } else { &b };
                assert!(matches!(annex.read(first.serial), Annexed::Mine(_)));
            }
        }
        assert_eq!(computed.get(), 2 * annexes.len());
    }
}
