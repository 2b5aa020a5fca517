//! Breadth-first exploration of every reachable state, with parent links so that the path
//! to any state is a shortest one.
//!
//! The search is level-synchronous: the states of one depth (the frontier) go in jobs to
//! `threads - 1` worker threads, which compute their summaries and successors, while this
//! thread merges the finished jobs' successors into the [`Store`] one by one, in frontier
//! order and successor order, a few jobs behind the workers, and expands a queued job
//! itself whenever the next result is not ready. The merge alone decides the
//! numbering, so the graph, the first transition seen for each check, and therefore every
//! verdict and counterexample, are the same for any number of threads.
//!
//! States are identified by a 64-bit fingerprint ([`Model::fingerprint`]: foldhash's
//! quality hash with a fixed seed, of the state or of its canonical member under symmetry,
//! through [`part_hash`](crate::semantics::state::part_hash)). Two distinct
//! states with one fingerprint would be merged; with `n` states the probability of that is
//! about `n² / 2⁶⁵`, printed with the statistics. Only fingerprints, parent links and (when
//! asked) edges are kept, never whole states beyond the frontier: [`Graph::state`] and
//! [`Walk`] rebuild them by replaying transitions.

use super::chunked::Lists;
use super::model::Model;
use super::store::{OutOfMemory, Store};
use crate::semantics::State;
use std::hash::Hash;
use std::marker::PhantomData;
use std::time::Instant;

/// A state's fingerprint.
pub fn fingerprint<S: Hash>(s: &S) -> u64 {
    crate::semantics::state::part_hash(s)
}

/// Bit `i` of the bit set `v` (clear past its end).
pub(super) fn bit(v: &[u64], i: u32) -> bool {
    v.get(i as usize / 64)
        .is_some_and(|w| w >> (i % 64) & 1 == 1)
}

/// Grows the bit set `v` to hold bit `i`, and sets that bit if `value`.
pub(super) fn set_bit(v: &mut Vec<u64>, i: u32, value: bool) {
    let w = i as usize / 64;
    if v.len() <= w {
        v.resize(w + 1, 0);
    }
    if value {
        v[w] |= 1 << (i % 64);
    }
}

/// Why exploration stopped before covering everything.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// `max_states` reached.
    States,
    /// `max_depth` reached (states deeper were not expanded).
    Depth,
    /// `--timeout` reached.
    Time,
    /// The memory bound reached (or memory ran out).
    Memory,
    /// A run left the finite model ([`crate::semantics::Note::Beyond`]).
    Beyond,
    /// Random runs were followed (`simulate`): some states reached were not expanded.
    Sampled,
    /// The project has more initial states than its bound allows: the search started from
    /// the first ones only.
    Initial,
}

/// Limits of one search.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Most distinct states.
    pub max_states: u64,
    /// Deepest state expanded.
    pub max_depth: u64,
    /// Wall-clock limit in seconds.
    pub timeout: Option<f64>,
}

/// How to search, beyond the limits.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Threads that expand states (at least 1), the merging one included.
    pub threads: usize,
    /// Keep every state's successors (liveness checks need them).
    pub keep_edges: bool,
    /// Stop, as incomplete, once the process holds this many bytes (resident).
    pub max_memory: Option<u64>,
    /// `(k, n)`: explore from the `k`-th of `n` parts of the initial states only (1-based).
    pub shard: Option<(u32, u32)>,
    /// Follow random runs only ([`super::sample`]): at each depth, expand this many states.
    pub sample: Option<super::sample::Sample>,
    /// States the store's table makes room for at the start, instead of doubling, and
    /// moving every state, on its way there. A guess: with too few the table grows as it
    /// would have; too many cost about 7 bytes each.
    pub room_for: usize,
    /// Keep each state's fingerprint and parent by number, so that a run to it can be
    /// rebuilt ([`Graph::path_to`], [`Walk`]). Without them (and without edges) the store
    /// keeps the fingerprints alone ([`Store::fingerprints_only`]): a search whose runs
    /// are not read (a user's search that finds nothing to report) in half the memory.
    pub numbered: bool,
    /// When not 0, the fingerprints are of pairs whose place is below this (a user's states
    /// on the agent's stored graph: [`Store::fingerprints_by_place`]). Read by a store of
    /// fingerprints only.
    pub places: usize,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            threads: 1,
            keep_edges: true,
            max_memory: None,
            shard: None,
            sample: None,
            room_for: 0,
            numbered: true,
            places: 0,
        }
    }
}

/// The successors of the expanded states, as adjacency lists in chunks that never move
/// ([`Lists`]: growing one array by copying had the kernel clear its fresh pages, a tenth
/// of the merging thread).
#[derive(Default)]
struct Edges {
    /// Per state, its successors.
    lists: Lists,
    /// Bit `i`: state `i` was expanded completely.
    expanded: Vec<u64>,
    /// Bit `i`: some edge enters state `i` from a state numbered no lower (recorded as the
    /// merge meets it, so that the liveness checks begin from these rather than find them
    /// in a pass over every edge: [`Graph::entered_back`]).
    back: Vec<u64>,
}

impl Edges {
    /// Appends an edge from `source` to `target` ([`Lists::push`]).
    fn push(&mut self, source: u32, target: u32) {
        self.lists.push(target);
        if target <= source {
            set_bit(&mut self.back, target, true);
        }
    }

    /// State `i`'s list.
    fn list(&self, i: u32) -> &[u32] {
        self.lists.list(i as usize)
    }

    fn bytes(&self) -> usize {
        self.lists.bytes() + (self.expanded.capacity() + self.back.capacity()) * 8
    }
}

/// The explored graph of a model (by default, the agent's).
pub struct Graph<S = State> {
    store: Store,
    /// `levels[d]`: the number of the first state at depth `d` (numbers follow depth).
    levels: Vec<u32>,
    edges: Option<Edges>,
    /// How many states are initial (the first ones).
    pub initial: usize,
    /// How many of the model's initial states this search covers: under symmetry one
    /// stored initial state stands for several.
    pub initial_covered: usize,
    /// Transitions taken.
    pub transitions: usize,
    /// States expanded through an ample set only ([`Model::ample`]).
    pub reduced: usize,
    /// The bound that stopped the search, if any.
    pub bound: Option<Bound>,
    /// Where the first run that left the model left it, and why ([`Bound::Beyond`]).
    pub beyond: Option<(crate::syntax::Span, String)>,
    /// Seconds spent.
    pub seconds: f64,
    /// Peak resident memory of the process during the search, in bytes (0 if unknown).
    pub peak_memory: u64,
    /// Bytes the store held when the search ended, its hash table included.
    store_bytes: usize,
    state: PhantomData<fn() -> S>,
}

/// A state's successors as the search has them: each with its transition's label.
pub type Successors<M> = [(<M as Model>::Label, <M as Model>::State)];

/// What expanding one frontier state produced (in a worker thread). Small: the merging
/// thread reads each from the memory the worker wrote it in, and copying a larger one (with
/// the successors' fingerprints in it) was a twelfth of the 5-cup search.
struct Expanded<T> {
    summary: T,
    /// How many successors it has, the next ones in its job's [`Found`]; `None` when the
    /// state was not expanded (depth bound).
    successors: Option<u32>,
    /// The ample set among them ([`Model::ample`]), if the model reduces here.
    ample: Option<std::ops::Range<u32>>,
}

/// A job's successors, state after state, each with its transition's label, and their
/// fingerprints in the same order. One pair of vectors per job, which the merge hands back
/// with a later job: a vector per state, made on a worker and freed by the merging thread,
/// cost the agent's search at 6 cups a tenth of its time in the allocator (frees from
/// another thread, fresh pages).
struct Found<L, S> {
    successors: Vec<(L, S)>,
    /// Beside the successors rather than in them, so that they are handed on as the model
    /// made them; the merge prefetches their slots in the store from here.
    fps: Vec<u64>,
}

impl<L, S> Default for Found<L, S> {
    fn default() -> Self {
        Found {
            successors: Vec::new(),
            fps: Vec::new(),
        }
    }
}

/// How many successors ahead of the one it looks up the merge asks for a store slot.
const MERGE_AHEAD: usize = 64;

/// About how many states a growing table re-places while a worker expands a job.
const REPLACED_PER_JOB: usize = 30_000;

/// States per job handed to a worker: enough to make a job worth its hand-over, few
/// enough to spread a level over the workers.
const JOB: usize = 1024;

/// Frontier states, each with its number.
type Batch<S> = Vec<(u32, S)>;

/// A batch and, in its order, what expanding each state produced, and all their
/// successors.
type Expansion<S, T, L> = (Batch<S>, Vec<Expanded<T>>, Found<L, S>);

/// Appends `x` to the last chunk of `chunks`, or to a new chunk (a buffer from `pool` if
/// there is one) when that one holds `JOB` states.
fn push_chunked<S>(chunks: &mut Vec<Batch<S>>, pool: &mut Vec<Batch<S>>, x: (u32, S)) {
    match chunks.last_mut() {
        Some(c) if c.len() < JOB => c.push(x),
        _ => {
            let mut c = pool.pop().unwrap_or_else(|| Vec::with_capacity(JOB));
            c.push(x);
            chunks.push(c);
        }
    }
}

/// Jobs smaller than this are expanded by the merging thread itself.
const SMALL_JOB: usize = 64;

/// How many jobs may be out (being expanded, or expanded and waiting for the merge) per
/// worker: enough to keep the workers busy while the merge catches up.
const AHEAD: usize = 4;

/// Expands frontier states in jobs and hands the results back in the order the jobs were
/// submitted: in this thread, or on worker threads while this one merges.
trait Expander<S, T, L> {
    /// How many jobs may be out at once.
    fn ahead(&self) -> usize;
    /// Queues `states` (each with its number): their summaries, and their successors if
    /// `expand`, put in `found` (empty).
    fn submit(&mut self, states: Batch<S>, expand: bool, found: Found<L, S>);
    /// The oldest submitted job, expanded.
    fn take(&mut self) -> Expansion<S, T, L>;
}

/// Expands each job in this thread, when it is taken.
struct Inline<'a, M: Model, F> {
    model: &'a M,
    summarize: F,
    queue: std::collections::VecDeque<Queued<M>>,
}

/// A job of [`Inline`]: its states, whether to expand them, where their successors go.
type Queued<M> = (
    Batch<<M as Model>::State>,
    bool,
    Found<<M as Model>::Label, <M as Model>::State>,
);

impl<M: Model, T, F: Fn(&M::State, Option<&Successors<M>>) -> T> Expander<M::State, T, M::Label>
    for Inline<'_, M, F>
{
    fn ahead(&self) -> usize {
        1
    }

    fn submit(&mut self, states: Batch<M::State>, expand: bool, found: Found<M::Label, M::State>) {
        self.queue.push_back((states, expand, found));
    }

    fn take(&mut self) -> Expansion<M::State, T, M::Label> {
        let (states, expand, mut found) = self.queue.pop_front().expect("a job was submitted");
        let out = expand_batch(self.model, &states, expand, &self.summarize, &mut found);
        (states, out, found)
    }
}

/// A job's result from a worker: its states and their expansions, or the worker's panic.
type Done<S, T, L> = std::thread::Result<Expansion<S, T, L>>;

/// A job for a worker: its number, its states, whether to expand them, and where their
/// successors go.
type Job<S, L> = (u64, Batch<S>, bool, Found<L, S>);

/// Expands jobs on worker threads; results are put back in submission order.
struct Workers<'q, S, T, L, F> {
    threads: usize,
    /// Expands a job in this thread: small jobs are not worth a hand-over, and a job still
    /// queued when the oldest result is not ready is expanded here rather than waited for.
    local: F,
    jobs: Option<std::sync::mpsc::Sender<Job<S, L>>>,
    /// The workers' end of `jobs`, from which this thread takes a job while it waits.
    queue: &'q std::sync::Mutex<std::sync::mpsc::Receiver<Job<S, L>>>,
    done: std::sync::mpsc::Receiver<(u64, Done<S, T, L>)>,
    submitted: u64,
    taken: u64,
    early: std::collections::BTreeMap<u64, Done<S, T, L>>,
}

impl<S, T, L, F> Expander<S, T, L> for Workers<'_, S, T, L, F>
where
    F: FnMut(Batch<S>, bool, Found<L, S>) -> Expansion<S, T, L>,
{
    fn ahead(&self) -> usize {
        AHEAD * self.threads
    }

    fn submit(&mut self, states: Batch<S>, expand: bool, found: Found<L, S>) {
        if states.len() < SMALL_JOB {
            // Narrow levels (a deep, thin graph) would otherwise wait on a hand-over each.
            let r = (self.local)(states, expand, found);
            self.early.insert(self.submitted, Ok(r));
            self.submitted += 1;
            return;
        }
        let jobs = self
            .jobs
            .as_ref()
            .expect("workers run until the search ends");
        // A send fails only when every worker has stopped, which `take` reports.
        let _ = jobs.send((self.submitted, states, expand, found));
        self.submitted += 1;
    }

    fn take(&mut self) -> Expansion<S, T, L> {
        let result = loop {
            if let Some(r) = self.early.remove(&self.taken) {
                break r;
            }
            if let Ok((seq, r)) = self.done.try_recv() {
                self.early.insert(seq, r);
                continue;
            }
            // Waiting idles a core (this thread merges while `threads - 1` workers expand):
            // a job that no worker has taken yet is expanded here instead. A worker that
            // holds the lock is taking one itself.
            let queued = (self.queue.try_lock().ok()).and_then(|q| q.try_recv().ok());
            if let Some((seq, states, expand, found)) = queued {
                let r = (self.local)(states, expand, found);
                self.early.insert(seq, Ok(r));
                continue;
            }
            match self.done.recv() {
                Ok((seq, r)) => {
                    self.early.insert(seq, r);
                }
                Err(_) => panic!("every search worker stopped"),
            }
        };
        self.taken += 1;
        result.unwrap_or_else(|e| std::panic::resume_unwind(e))
    }
}

/// Explores a model from every initial state, breadth first, on one thread, keeping the
/// edges. `on_transition` sees every transition (source index, its position among the
/// source's transitions, its label) in a fixed order, so checks need not regenerate them.
pub fn explore<M: Model>(
    model: &M,
    limits: Limits,
    mut on_transition: impl FnMut(u32, u32, &M::Label),
    progress: impl FnMut(usize, u32, f64),
) -> Graph<M::State> {
    let mut inline = Inline {
        model,
        summarize: |_: &M::State, _: Option<&Successors<M>>| (),
        queue: Default::default(),
    };
    search(
        model,
        limits,
        &Options::default(),
        &mut inline,
        |_, _, ()| {},
        |src, k, label, _| on_transition(src, k, label),
        progress,
    )
}

/// Explores a model with `opts.threads` threads expanding states, this one among them: it
/// merges their successors into the store, and expands while no result is ready (two
/// workers and a merging thread on two cores left a fifth of them idle at 5 cups).
/// `summarize` runs on every stored state (in an expanding thread), with its successors
/// when it was expanded; `on_state` then receives its summary, in state number order;
/// `on_transition` sees every transition with the fingerprint of its target, in a fixed
/// order.
pub fn explore_with<M, T>(
    model: &M,
    limits: Limits,
    opts: &Options,
    summarize: impl Fn(&M::State, Option<&Successors<M>>) -> T + Sync,
    on_state: impl FnMut(u32, &M::State, T),
    on_transition: impl FnMut(u32, u32, &M::Label, u64),
    progress: impl FnMut(usize, u32, f64),
) -> Graph<M::State>
where
    M: Model + Sync,
    M::State: Send + Sync,
    M::Label: Send,
    T: Send,
{
    let threads = opts.threads.max(1);
    if threads == 1 {
        let mut inline = Inline {
            model,
            summarize,
            queue: Default::default(),
        };
        return search(
            model,
            limits,
            opts,
            &mut inline,
            on_state,
            on_transition,
            progress,
        );
    }
    let (jobs, queue) = std::sync::mpsc::channel::<Job<M::State, M::Label>>();
    let queue = std::sync::Mutex::new(queue);
    let (results, done) = std::sync::mpsc::channel();
    std::thread::scope(|scope| {
        // This thread expands too while it waits for a result (`Workers::take`).
        for _ in 0..threads - 1 {
            let (queue, results, summarize) = (&queue, results.clone(), &summarize);
            scope.spawn(move || loop {
                let job = queue.lock().unwrap_or_else(|e| e.into_inner()).recv();
                let Ok((seq, states, expand, mut found)) = job else {
                    return;
                };
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    let out = expand_batch(model, &states, expand, summarize, &mut found);
                    (states, out, found)
                }));
                let failed = r.is_err();
                if results.send((seq, r)).is_err() || failed {
                    return;
                }
            });
        }
        drop(results);
        let mut workers = Workers {
            threads,
            local: |states: Batch<M::State>, expand, mut found| {
                let out = expand_batch(model, &states, expand, &summarize, &mut found);
                (states, out, found)
            },
            jobs: Some(jobs),
            queue: &queue,
            done,
            submitted: 0,
            taken: 0,
            early: Default::default(),
        };
        let g = search(
            model,
            limits,
            opts,
            &mut workers,
            on_state,
            on_transition,
            progress,
        );
        // Closing the queue ends the workers.
        workers.jobs = None;
        g
    })
}

/// How many states ahead of the one it expands a search asks for the memory of each
/// stage of [`Model::prefetch`]: far enough for a read from memory to arrive.
const PREFETCH: [usize; 3] = [9, 6, 3];

/// Expands the states of a batch in order ([`expand_one`]), each some after the model
/// was asked to prefetch what it reads ([`Model::prefetch`]), their successors appended
/// to `found`.
fn expand_batch<M: Model, T>(
    model: &M,
    states: &Batch<M::State>,
    expand: bool,
    summarize: &impl Fn(&M::State, Option<&Successors<M>>) -> T,
    found: &mut Found<M::Label, M::State>,
) -> Vec<Expanded<T>> {
    (0..states.len())
        .map(|i| {
            if expand {
                for (stage, ahead) in PREFETCH.into_iter().enumerate() {
                    if let Some((_, s)) = states.get(i + ahead) {
                        model.prefetch(s, stage);
                    }
                }
            }
            expand_one(model, &states[i].1, expand, summarize, found)
        })
        .collect()
}

fn expand_one<M: Model, T>(
    model: &M,
    s: &M::State,
    expand: bool,
    summarize: &impl Fn(&M::State, Option<&Successors<M>>) -> T,
    found: &mut Found<M::Label, M::State>,
) -> Expanded<T> {
    if !expand {
        return Expanded {
            summary: summarize(s, None),
            successors: None,
            ample: None,
        };
    }
    let from = found.successors.len();
    model.next_states_into(s, &mut found.successors);
    let succ = &mut found.successors[from..];
    let ample = model.ample(s, succ);
    (found.fps).extend((succ.iter_mut()).map(|(l, t)| model.fingerprint_labelled(l, t)));
    let n = u32::try_from(succ.len()).expect("fewer than 2^32 successors of a state");
    Expanded {
        summary: summarize(s, Some(succ)),
        successors: Some(n),
        ample: ample.map(|a| a.start as u32..a.end as u32),
    }
}

/// How often a search compares the resident memory with its bound, in seconds: the
/// search grows by a few MiB in that time at most.
const MEMORY_CHECK_SECONDS: f64 = 0.005;

/// The process's resident memory, in bytes, where `/proc` tells it: the second field of
/// `/proc/self/statm`, in pages (what `VmRSS` of `/proc/self/status` gives, without the
/// kernel writing out every other figure of that file).
pub fn resident_memory() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    // SAFETY: sysconf reads a constant of the system and has no preconditions.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    Some(pages * u64::try_from(page).ok().filter(|&p| p > 0)?)
}

/// The process's peak resident memory so far, in bytes (`VmHWM`).
pub fn peak_memory() -> Option<u64> {
    proc_status_kb("VmHWM:").map(|kb| kb * 1024)
}

fn proc_status_kb(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line[key.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()
}

/// The default memory bound: nine tenths of what the process holds now plus what the
/// machine (or its cgroup) has available.
pub fn default_max_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let available: u64 = meminfo
        .lines()
        .find(|l| l.starts_with("MemAvailable:"))?
        .trim_start_matches("MemAvailable:")
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse::<u64>()
        .ok()?
        * 1024;
    let now = resident_memory().unwrap_or(0);
    let mut limit = (now + available) / 10 * 9;
    if let Some(cg) = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok())
    {
        limit = limit.min(cg / 10 * 9);
    }
    // `ulimit -v` bounds the address space, which runs ahead of what is resident
    // (allocator arenas, thread stacks): six tenths of it.
    if let Some(virt) = address_space_limit() {
        limit = limit.min(virt / 10 * 6);
    }
    Some(limit)
}

/// The process's soft limit on its address space (`RLIMIT_AS`), if it has one.
fn address_space_limit() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// The level-synchronous search; `expander` gives frontier states their summaries and
/// successors, in order. States are expanded ahead of the merge; what the merge decides
/// not to expand (the depth bound, a stop) has its successors dropped, so the graph is the
/// one a search expanding on demand would build.
#[allow(clippy::too_many_arguments)]
fn search<M: Model, T>(
    model: &M,
    limits: Limits,
    opts: &Options,
    expander: &mut impl Expander<M::State, T, M::Label>,
    mut on_state: impl FnMut(u32, &M::State, T),
    mut on_transition: impl FnMut(u32, u32, &M::Label, u64),
    mut progress: impl FnMut(usize, u32, f64),
) -> Graph<M::State> {
    let start = Instant::now();
    let mut g = Graph {
        store: match opts.numbered || opts.keep_edges {
            true => Store::with_room(opts.room_for),
            false => Store::fingerprints_by_place(opts.room_for, opts.places),
        },
        levels: vec![0],
        edges: opts.keep_edges.then(Edges::default),
        initial: 0,
        initial_covered: 0,
        transitions: 0,
        reduced: 0,
        bound: None,
        beyond: None,
        seconds: 0.0,
        peak_memory: 0,
        store_bytes: 0,
        state: PhantomData,
    };
    // The states of the depth to expand, in chunks of at most `JOB`.
    let mut frontier: Vec<Batch<M::State>> = Vec::new();
    // Chunks' buffers, back from the merge.
    let mut pool: Vec<Batch<M::State>> = Vec::new();
    // Jobs' successor vectors, back from the merge.
    let mut founds: Vec<Found<M::Label, M::State>> = Vec::new();
    // Canonical fingerprint -> whether this shard explores it.
    let mut seen: std::collections::HashMap<u64, bool> = std::collections::HashMap::new();
    for (taken, s) in model.init_states().enumerate() {
        // The initial states are made as they are taken: a bound stops taking them.
        if g.bound.is_some() {
            break;
        }
        if taken % 1024 == 1023 {
            let elapsed = start.elapsed().as_secs_f64();
            progress(g.store.len(), 0, elapsed);
            if limits.timeout.is_some_and(|t| elapsed > t) {
                g.bound = Some(Bound::Time);
                break;
            }
            if let (Some(m), Some(rss)) = (opts.max_memory, resident_memory()) {
                g.peak_memory = g.peak_memory.max(rss);
                if rss > m {
                    g.bound = Some(Bound::Memory);
                    break;
                }
            }
        }
        let fp = model.fingerprint(&s);
        let nth = seen.len() as u32;
        // Shards split the distinct initial states round-robin.
        let mine = *seen.entry(fp).or_insert_with(|| {
            opts.shard
                .is_none_or(|(k, n)| nth % n.max(1) == k.saturating_sub(1))
        });
        if !mine {
            continue;
        }
        if g.store.contains(fp) {
            g.initial_covered += 1;
            continue;
        }
        if g.store.len() as u64 >= limits.max_states {
            g.bound = Some(Bound::States);
            continue;
        }
        g.initial_covered += 1;
        match g.store.insert(fp, None) {
            Ok((i, true)) => push_chunked(&mut frontier, &mut pool, (i, s)),
            Ok(_) => {}
            Err(OutOfMemory) => g.bound = Some(Bound::Memory),
        }
    }
    g.initial = g.store.len();
    if !model.init_complete() {
        g.bound.get_or_insert(Bound::Initial);
    }
    let mut depth = 0u32;
    // A stop while the initial states were taken: those taken are only summarized.
    let mut stopped = matches!(g.bound, Some(Bound::Time | Bound::Memory));
    // When the resident memory was last compared with the bound: at the first merge, then
    // every `MEMORY_CHECK_SECONDS`.
    let mut memory_checked = f64::NEG_INFINITY;
    let mut rng = opts.sample.map(|s| super::sample::SplitMix64::new(s.seed));
    while let Some(&(first, _)) = frontier.first().and_then(|c| c.first()) {
        if depth > 0 {
            g.levels.push(first);
        }
        let expand = u64::from(depth) < limits.max_depth;
        if !expand && !stopped {
            g.bound.get_or_insert(Bound::Depth);
        }
        let width = frontier.iter().map(Vec::len).sum::<usize>();
        // Following random runs: the states of this depth to expand (the others are
        // summarized only, as states beyond a bound).
        let chosen: Option<Vec<bool>> = match (opts.sample, &mut rng) {
            (Some(s), Some(rng)) if width > s.runs as usize => {
                g.bound.get_or_insert(Bound::Sampled);
                Some(rng.choose(width, s.runs as usize))
            }
            _ => None,
        };
        // The next depth, in chunks whose buffers come back from the merge: one growing
        // vector per depth had the kernel clear fresh pages each time it doubled (a third
        // of the merging thread at 5 cups), and chunks are the jobs, handed over whole.
        let mut next: Vec<Batch<M::State>> = Vec::new();
        // The number of the first state of the next depth.
        let next_level = g.store.len() as u32;
        // Jobs: consecutive states that are all expanded or all not.
        let mut jobs: std::collections::VecDeque<(Batch<M::State>, bool)> = match &chosen {
            None => std::mem::take(&mut frontier)
                .into_iter()
                .map(|c| (c, true))
                .collect(),
            Some(chosen) => {
                let mut jobs: std::collections::VecDeque<(Batch<M::State>, bool)> =
                    std::collections::VecDeque::new();
                let states = std::mem::take(&mut frontier).into_iter().flatten();
                for (x, &expand_it) in states.zip(chosen) {
                    match jobs.back_mut() {
                        Some((job, e)) if *e == expand_it && job.len() < JOB => job.push(x),
                        _ => jobs.push_back((vec![x], expand_it)),
                    }
                }
                jobs
            }
        };
        let mut out = 0;
        loop {
            // A growing table stops the merge (at 5 cups its last growth took 0.1 s) while
            // the workers, their few jobs done, waited: before one, they get jobs to last it.
            let (room, held) = g.store.room();
            let extra = match expander.ahead() > 1 && room < JOB * expander.ahead() {
                true => held / REPLACED_PER_JOB,
                false => 0,
            };
            while out < expander.ahead() + extra {
                let Some((job, expand_job)) = jobs.pop_front() else {
                    break;
                };
                // After a stop, only summaries: the merge drops successors anyway.
                let found = founds.pop().unwrap_or_default();
                expander.submit(job, expand && expand_job && !stopped, found);
                out += 1;
            }
            if out == 0 {
                break;
            }
            let (mut states, results, mut found) = expander.take();
            out -= 1;
            let elapsed = start.elapsed().as_secs_f64();
            progress(g.store.len(), depth, elapsed);
            if !stopped && limits.timeout.is_some_and(|t| elapsed > t) {
                g.bound = Some(Bound::Time);
                stopped = true;
            }
            // Reading the resident memory costs a system call and the kernel's count of
            // the process's pages: once per job it was 1-2% of a user's search.
            if !stopped && elapsed - memory_checked >= MEMORY_CHECK_SECONDS {
                memory_checked = elapsed;
                if let Some(rss) = resident_memory() {
                    g.peak_memory = g.peak_memory.max(rss);
                    if opts.max_memory.is_some_and(|m| rss > m) {
                        g.bound = Some(Bound::Memory);
                        stopped = true;
                    }
                }
            }
            // A job merged after a stop counts as not expanded, as if it had not been.
            let expanded = !stopped;
            // Each successor's slot is asked for `MERGE_AHEAD` successors before it is
            // looked up: asked for all at once, most had left the cache again, or were
            // still on their way, when their turn came.
            let Found { successors, fps } = &mut found;
            let ahead = match expanded {
                true => &fps[..],
                false => &[],
            };
            for &fp in ahead.iter().take(MERGE_AHEAD) {
                g.store.prefetch(fp);
            }
            let mut next_ahead = ahead.iter().skip(MERGE_AHEAD);
            let mut late_ahead = ahead.iter().skip(MERGE_AHEAD / 2);
            let mut all = successors.drain(..);
            // Where the next state's fingerprints begin in `fps`.
            let mut at = 0;
            for ((src, s), r) in states.iter().zip(results) {
                on_state(*src, s, r.summary);
                // This state's successors: each path below takes them all.
                let n = r.successors.unwrap_or(0) as usize;
                let succ = all.by_ref().take(n);
                let my_fps = &fps[at..at + n];
                at += n;
                if r.successors.is_none() || !expanded {
                    succ.for_each(drop);
                    g.mark(*src, g.edges.as_ref().map_or(0, |e| e.lists.end()), false);
                    continue;
                };
                if let Some(e) = &mut g.edges {
                    if e.lists.room(n).is_err() {
                        succ.for_each(drop);
                        let end = e.lists.end();
                        g.bound = Some(Bound::Memory);
                        stopped = true;
                        g.mark(*src, end, false);
                        continue;
                    }
                }
                let edge_start = g.edges.as_ref().map_or(0, |e| e.lists.end());
                // The cycle proviso: a reduced state's followed successors are all deeper,
                // so no cycle of the reduced graph is reduced everywhere and no transition
                // is put off forever.
                // (Without numbers, a stored successor might be of either depth: none may be.)
                let ample = r.ample.filter(|a| {
                    my_fps[a.start as usize..a.end as usize].iter().all(|fp| {
                        match g.store.numbered() {
                            true => g.store.find(*fp).is_none_or(|i| i >= next_level),
                            false => !g.store.contains(*fp),
                        }
                    })
                });
                if ample.is_some() {
                    g.reduced += 1;
                }
                let mut cut = false;
                for (k, ((label, t), &fp)) in succ.zip(my_fps).enumerate() {
                    if let Some(&next) = next_ahead.next() {
                        g.store.prefetch(next);
                    }
                    if let Some(&late) = late_ahead.next() {
                        g.store.prefetch_late(late);
                    }
                    if ample.as_ref().is_some_and(|a| !a.contains(&(k as u32))) {
                        continue;
                    }
                    if let Some(why) = model.beyond(&label) {
                        g.bound.get_or_insert(Bound::Beyond);
                        g.beyond.get_or_insert(why);
                        cut = true;
                        continue;
                    }
                    on_transition(*src, k as u32, &label, fp);
                    g.transitions += 1;
                    let target = match g.store.lookup(fp) {
                        Ok(i) => i,
                        Err(_) if stopped => {
                            cut = true;
                            continue;
                        }
                        Err(_) if g.store.len() as u64 >= limits.max_states => {
                            g.bound = Some(Bound::States);
                            cut = true;
                            continue;
                        }
                        Err(vacant) => match g.store.insert_vacant(vacant, fp, Some(*src)) {
                            Ok(i) => {
                                push_chunked(&mut next, &mut pool, (i, t));
                                i
                            }
                            Err(OutOfMemory) => {
                                g.bound = Some(Bound::Memory);
                                stopped = true;
                                cut = true;
                                continue;
                            }
                        },
                    };
                    if let Some(e) = &mut g.edges {
                        e.push(*src, target);
                    }
                }
                // A state some of whose successors were cut off counts as not expanded: it
                // must not look like a state with no successors (a deadlock) or a finished
                // run.
                g.mark(*src, edge_start, !cut);
            }
            drop(all);
            fps.clear();
            // As many as the jobs usually out: those handed out to last a growth are freed.
            if founds.len() < expander.ahead() {
                founds.push(found);
            }
            states.clear();
            pool.push(states);
        }
        frontier = next;
        depth += 1;
    }
    g.seconds = start.elapsed().as_secs_f64();
    if let Some(p) = peak_memory() {
        g.peak_memory = g.peak_memory.max(p);
    }
    // No state is looked up once the search is over: its hash table (6.7 to 13.3 bytes a
    // state) goes to the searches and products after it, which took fresh memory while
    // the searches before them held theirs (6-cup kitchen: 2.5 GB for the products).
    g.store_bytes = g.store.bytes();
    g.store.drop_index();
    g
}

impl<S> Graph<S> {
    /// The same graph, for another model of the same transition system with the same
    /// fingerprints: the compiled search's graph, read with the reference model.
    pub fn cast<T>(self) -> Graph<T> {
        Graph {
            store: self.store,
            levels: self.levels,
            edges: self.edges,
            initial: self.initial,
            initial_covered: self.initial_covered,
            transitions: self.transitions,
            reduced: self.reduced,
            bound: self.bound,
            beyond: self.beyond,
            seconds: self.seconds,
            peak_memory: self.peak_memory,
            store_bytes: self.store_bytes,
            state: PhantomData,
        }
    }

    /// Records state `i`'s edges (from `edge_start` on) as complete or not. States are
    /// recorded in number order.
    fn mark(&mut self, i: u32, edge_start: u64, complete: bool) {
        let Some(e) = &mut self.edges else { return };
        debug_assert_eq!(e.lists.len(), i as usize);
        if !complete {
            e.lists.truncate(edge_start);
        }
        if e.lists.start(edge_start).is_err() {
            // Out of memory: the state counts as not expanded (its bit stays clear), and
            // so does every later one, whose lists are not kept either.
            self.edges = None;
            self.bound = Some(Bound::Memory);
            return;
        }
        set_bit(&mut e.expanded, i, complete);
    }

    /// Number of states reached.
    pub fn len(&self) -> usize {
        self.store.len()
    }

    /// Whether no state was reached.
    pub fn is_empty(&self) -> bool {
        self.store.is_empty()
    }

    /// The fingerprint of state `i`.
    pub fn fingerprint(&self, i: u32) -> u64 {
        self.store.fingerprint(i)
    }

    /// Frees the fingerprints kept by number once the search is over, if `derived` gives
    /// them alike ([`Store::derive_fingerprints`]); whether it did.
    pub fn derive_fingerprints(&mut self, derived: super::store::Derived) -> bool {
        self.store.derive_fingerprints(derived)
    }

    /// Whether the fingerprints are derived rather than kept
    /// ([`Graph::derive_fingerprints`]).
    pub fn fingerprints_derived(&self) -> bool {
        self.store.derived()
    }

    /// The state `i` was first reached from.
    pub fn parent(&self, i: u32) -> Option<u32> {
        self.store.parent(i)
    }

    /// The depth of state `i` (the length of a shortest run to it).
    pub fn depth(&self, i: u32) -> u32 {
        (self.levels.partition_point(|&start| start <= i) - 1) as u32
    }

    /// The successors of state `i`, in transition order (duplicates and all), or `None`
    /// when it was not expanded completely (or edges were not kept).
    pub fn successors(&self, i: u32) -> Option<&[u32]> {
        let e = self.edges.as_ref()?;
        bit(&e.expanded, i).then(|| e.list(i))
    }

    /// The number of state `i`'s first transition among all kept transitions, numbered
    /// state by state in the order [`Graph::successors`] gives them (`None` when edges
    /// were not kept). Read once the search is over.
    pub fn first_transition(&self, i: u32) -> Option<u64> {
        let e = self.edges.as_ref()?;
        ((i as usize) < e.lists.len()).then(|| e.lists.first_item(i as usize))
    }

    /// How many transitions the kept edges hold (`None` when edges were not kept).
    pub fn kept_transitions(&self) -> Option<u64> {
        self.edges.as_ref().map(|e| e.lists.items())
    }

    /// Prefetches where state `i`'s successors begin in the edges, or (`near`) the
    /// successors themselves ([`Model::prefetch`]).
    pub fn prefetch_successors(&self, i: u32, near: bool) {
        if let Some(e) = &self.edges {
            e.lists.prefetch(i as usize, near);
        }
    }

    /// The successors of state `i` as [`Graph::successors`] gives them, without checking
    /// that it was expanded: for prefetching only (any list, maybe empty, when it was not).
    pub fn successors_unchecked(&self, i: u32) -> &[u32] {
        match &self.edges {
            Some(e) if (i as usize) < e.lists.len() => e.list(i),
            _ => &[],
        }
    }

    /// The states some kept edge enters from a state numbered no lower (itself included),
    /// as a bit set (shorter than the states when the last ones are not among them);
    /// `None` when edges were not kept. Every cycle has such an edge. An edge dropped
    /// since (a state cut off by a bound) may have left its target in the set.
    pub fn entered_back(&self) -> Option<&[u64]> {
        self.edges.as_ref().map(|e| &e.back[..])
    }

    /// The shortest path from an initial state to `target`: state indices, initial first.
    pub fn path_to(&self, target: u32) -> Vec<u32> {
        let mut path = vec![target];
        let mut at = target;
        while let Some(p) = self.store.parent(at) {
            path.push(p);
            at = p;
        }
        path.reverse();
        path
    }

    /// The deepest depth reached.
    pub fn max_depth(&self) -> u32 {
        self.levels.len().saturating_sub(1) as u32
    }

    /// Whether every reachable state was expanded.
    pub fn complete(&self) -> bool {
        self.bound.is_none()
    }

    /// Bytes the visited-state store held when the search ended (its hash table, freed
    /// since, included).
    pub fn store_bytes(&self) -> usize {
        self.store_bytes
    }

    /// Bytes held by the edges (zero when not kept).
    pub fn edge_bytes(&self) -> usize {
        self.edges.as_ref().map_or(0, Edges::bytes)
    }

    /// State `i`, rebuilt by replaying the run to it (a member of its class under
    /// symmetry, the one that run reaches).
    pub fn state<M: Model<State = S>>(&self, model: &M, i: u32) -> Option<S> {
        let path = self.path_to(i);
        let mut w = Walk::start(model, self, path[0])?;
        for &j in &path[1..] {
            w.step_to(j)?;
        }
        Some(w.state)
    }
}

/// A concrete run through the graph, rebuilt by replaying: at each step, the first
/// successor of the current state whose fingerprint is the next state's.
pub struct Walk<'a, M: Model> {
    model: &'a M,
    graph: &'a Graph<M::State>,
    /// The state the run is in.
    pub state: M::State,
}

impl<'a, M: Model> Walk<'a, M> {
    /// A run starting in the initial state numbered `i`.
    pub fn start(model: &'a M, graph: &'a Graph<M::State>, i: u32) -> Option<Walk<'a, M>> {
        let want = graph.fingerprint(i);
        let state = model
            .init_states()
            .into_iter()
            .find(|s| model.fingerprint(s) == want)?;
        Some(Walk {
            model,
            graph,
            state,
        })
    }

    /// Takes a transition to state `j`, returning its label.
    pub fn step_to(&mut self, j: u32) -> Option<M::Label> {
        let want = self.graph.fingerprint(j);
        let (label, next) = self
            .model
            .next_states(&self.state)
            .into_iter()
            .find(|(_, t)| self.model.fingerprint(t) == want)?;
        self.state = next;
        Some(label)
    }

    /// Takes the transition whose target has fingerprint `fp` and whose label satisfies
    /// `want` (the `k`-th transition first, as exploration numbered them), returning its
    /// label.
    pub fn step_by(
        &mut self,
        k: u32,
        fp: u64,
        want: impl Fn(&M::Label) -> bool,
    ) -> Option<M::Label> {
        let mut succ = self.model.next_states(&self.state);
        let fits = |(l, t): &(M::Label, M::State)| self.model.fingerprint(t) == fp && want(l);
        let pos = if succ.get(k as usize).is_some_and(&fits) {
            k as usize
        } else {
            succ.iter().position(fits)?
        };
        let (label, next) = succ.swap_remove(pos);
        self.state = next;
        Some(label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resident_memory_is_what_proc_status_says() {
        // The two files are read one after the other: other tests' threads may take or
        // give back pages in between, so a reading counts where status agreed with
        // itself around it. Readings are spread over up to a second: a test filling
        // megabytes of fresh pages beside this one kept all of 100 readings in a row
        // apart (once, in CI).
        let agreed = (0..2000).any(|k| {
            if k > 0 {
                std::thread::sleep(std::time::Duration::from_micros(500));
            }
            let before = proc_status_kb("VmRSS:");
            let statm = resident_memory();
            let after = proc_status_kb("VmRSS:");
            matches!((before, statm, after), (Some(b), Some(m), Some(a)) if b == a && m == b * 1024)
        });
        assert!(agreed || proc_status_kb("VmRSS:").is_none());
    }

    /// Counting modulo `n` by +1 or +2: every residue is reachable, and the shortest path
    /// to `k` takes `ceil(k / 2)` steps.
    struct Counter(u32);

    impl Model for Counter {
        type State = u32;
        type Label = u32;
        fn init_states(&self) -> Box<dyn Iterator<Item = u32> + '_> {
            Box::new(std::iter::once(0))
        }
        fn next_states(&self, s: &u32) -> Vec<(u32, u32)> {
            vec![(1, (s + 1) % self.0), (2, (s + 2) % self.0)]
        }
    }

    /// A binary tree over `0..n`, with an edge across: levels wide enough for many jobs.
    struct Tree(u32);

    impl Model for Tree {
        type State = u32;
        type Label = u32;
        fn init_states(&self) -> Box<dyn Iterator<Item = u32> + '_> {
            Box::new(std::iter::once(0))
        }
        fn next_states(&self, s: &u32) -> Vec<(u32, u32)> {
            let n = u64::from(self.0);
            [
                2 * u64::from(*s) + 1,
                2 * u64::from(*s) + 2,
                u64::from(*s) * 7 + 3,
            ]
            .into_iter()
            .enumerate()
            .map(|(k, t)| (k as u32, (t % n) as u32))
            .collect()
        }
    }

    /// A search with no checks.
    fn bare<M>(m: &M, limits: Limits, opts: Options) -> Graph<M::State>
    where
        M: Model + Sync,
        M::State: Send + Sync,
        M::Label: Send,
    {
        explore_with(
            m,
            limits,
            &opts,
            |_, _| (),
            |_, _, ()| {},
            |_, _, _, _| {},
            |_, _, _| {},
        )
    }

    fn unbounded() -> Limits {
        Limits {
            max_states: u64::MAX,
            max_depth: u64::MAX,
            timeout: None,
        }
    }

    /// Two processes: `a` counts modulo 3 for ever, `b` moves once, from 0 to 10. An ample
    /// set of `a` alone is offered everywhere (wrongly: that alone would put `b` off for
    /// ever around `a`'s cycle); the cycle proviso must still take `b` somewhere.
    struct Ignoring;

    impl Model for Ignoring {
        type State = (u32, u32);
        type Label = char;
        fn init_states(&self) -> Box<dyn Iterator<Item = (u32, u32)> + '_> {
            Box::new(std::iter::once((0, 0)))
        }
        fn next_states(&self, s: &(u32, u32)) -> Vec<(char, (u32, u32))> {
            let mut v = vec![('a', ((s.0 + 1) % 3, s.1))];
            if s.1 == 0 {
                v.push(('b', (s.0, 10)));
            }
            v
        }
        fn ample(
            &self,
            _s: &(u32, u32),
            succ: &[(char, (u32, u32))],
        ) -> Option<std::ops::Range<usize>> {
            (succ.len() > 1).then_some(0..1)
        }
    }

    #[test]
    fn the_cycle_proviso_takes_every_transition_on_a_cycle() {
        for threads in [1, 2] {
            let opts = Options {
                threads,
                ..Options::default()
            };
            let g = bare(&Ignoring, unbounded(), opts);
            // (1,0) and (2,0) through the ample set, then (0,0) again: closing the cycle
            // fails the proviso, so (2,0) takes `b` too, and all of `b`'s states follow.
            assert_eq!(g.len(), 6, "threads {threads}");
            assert!(g.reduced >= 1);
        }
    }

    #[test]
    fn any_model_is_explored_breadth_first_with_shortest_paths() {
        let mut labels = 0;
        let m = Counter(10);
        let g = explore(&m, unbounded(), |_, _, _| labels += 1, |_, _, _| {});
        assert!(g.complete());
        assert_eq!(g.len(), 10);
        assert_eq!((g.transitions, labels), (20, 20));
        for i in 0..10u32 {
            let s = g.state(&m, i).expect("replays");
            let path = g.path_to(i);
            assert_eq!(path.len() - 1, s.div_ceil(2) as usize, "state {s}");
            assert_eq!(g.depth(i) as usize, path.len() - 1);
            assert_eq!(g.successors(i).map(|e| e.len()), Some(2));
        }
    }

    /// Counting modulo `n` by 1 to `s % 7`: from zero to six successors per state.
    struct Uneven(u32);

    impl Model for Uneven {
        type State = u32;
        type Label = u32;
        fn init_states(&self) -> Box<dyn Iterator<Item = u32> + '_> {
            Box::new(std::iter::once(1))
        }
        fn next_states(&self, s: &u32) -> Vec<(u32, u32)> {
            (1..=s % 7).map(|k| (k, (s + k) % self.0)).collect()
        }
    }

    #[test]
    fn every_state_keeps_its_successors_across_the_edge_chunks() {
        let m = Uneven(800_000);
        let g = bare(&m, unbounded(), Options::default());
        assert!(g.complete());
        let fp: std::collections::HashMap<u64, u32> =
            (0..g.len() as u32).map(|i| (g.fingerprint(i), i)).collect();
        assert!(
            g.transitions > 2 * super::super::chunked::LIST_CHUNK,
            "{} edges",
            g.transitions
        );
        // The state of each number, through the fingerprints (replaying runs this long to
        // each state would take minutes).
        let state: std::collections::HashMap<u64, u32> =
            (0..m.0).map(|s| (m.fingerprint(&s), s)).collect();
        for i in 0..g.len() as u32 {
            let s = state[&g.fingerprint(i)];
            let want: Vec<u32> = m
                .next_states(&s)
                .iter()
                .map(|(_, t)| fp[&m.fingerprint(t)])
                .collect();
            assert_eq!(g.successors(i), Some(&want[..]), "state {s}");
            // What prefetching reads is the same list.
            assert_eq!(g.successors_unchecked(i), &want[..], "state {s}");
            g.prefetch_successors(i, false);
            g.prefetch_successors(i, true);
        }
        for past in [g.len() as u32, u32::MAX] {
            assert!(g.successors_unchecked(past).is_empty());
            g.prefetch_successors(past, true);
        }
        // The states entered backwards are those of the edges to a state numbered no
        // higher than their source.
        let mut entered = vec![0u64; g.len().div_ceil(64)];
        for i in 0..g.len() as u32 {
            for &w in g.successors(i).into_iter().flatten().filter(|&&w| w <= i) {
                entered[w as usize / 64] |= 1 << (w % 64);
            }
        }
        let recorded = g.entered_back().expect("edges were kept");
        assert!(entered.iter().any(|&w| w != 0));
        assert_eq!(recorded, &entered[..recorded.len()]);
        assert!(entered[recorded.len()..].iter().all(|&w| w == 0));
    }

    #[test]
    fn threads_do_not_change_the_graph() {
        threads_do_not_change(&Counter(50_000));
        // Levels of thousands of states: jobs go to workers, and the merging thread
        // expands those still queued when it waits.
        threads_do_not_change(&Tree(50_000));
    }

    fn threads_do_not_change<M: Model<State = u32> + Sync>(m: &M)
    where
        M::Label: Send,
    {
        let run = |threads| {
            let opts = Options {
                threads,
                ..Options::default()
            };
            let mut seen = Vec::new();
            let g = explore_with(
                m,
                unbounded(),
                &opts,
                |s, succ: Option<&Successors<M>>| (*s, succ.map(|v| v.len())),
                |i, _, s| seen.push((i, s)),
                |_, _, _, _| {},
                |_, _, _| {},
            );
            let fps: Vec<u64> = (0..g.len() as u32).map(|i| g.fingerprint(i)).collect();
            let parents: Vec<Option<u32>> = (0..g.len() as u32).map(|i| g.parent(i)).collect();
            (fps, parents, seen)
        };
        let one = run(1);
        assert_eq!(one.0.len(), 50_000);
        for threads in 2..=4 {
            assert_eq!(one, run(threads), "threads {threads}");
        }
    }

    #[test]
    fn bounds_leave_the_graph_incomplete() {
        let limits = Limits {
            max_states: 4,
            ..unbounded()
        };
        let g = explore(&Counter(10), limits, |_, _, _| {}, |_, _, _| {});
        assert_eq!(g.len(), 4);
        assert_eq!(g.bound, Some(Bound::States));
        // A state whose successors were cut off is not taken as expanded.
        assert!((0..4).any(|i| g.successors(i).is_none()));
        let limits = Limits {
            max_depth: 1,
            ..unbounded()
        };
        let g = explore(&Counter(10), limits, |_, _, _| {}, |_, _, _| {});
        assert_eq!(g.len(), 3);
        assert_eq!(g.bound, Some(Bound::Depth));
        for threads in [1, 2] {
            let opts = Options {
                max_memory: Some(1),
                threads,
                ..Options::default()
            };
            let g = bare(&Counter(10), unbounded(), opts);
            if resident_memory().is_some() {
                assert_eq!(g.bound, Some(Bound::Memory));
                assert!(!g.complete());
                // Stopped before the first merge: the initial state is stored, unexpanded.
                assert_eq!((g.len(), g.successors(0)), (1, None));
            }
        }
        // A state bound cuts the same graph whatever the thread count.
        let cut = |threads| {
            let opts = Options {
                threads,
                ..Options::default()
            };
            let limits = Limits {
                max_states: 5_000,
                ..unbounded()
            };
            let g = bare(&Counter(50_000), limits, opts);
            assert_eq!(g.bound, Some(Bound::States));
            let expanded = (0..g.len() as u32)
                .filter(|&i| g.successors(i).is_some())
                .count();
            let fps: Vec<u64> = (0..g.len() as u32).map(|i| g.fingerprint(i)).collect();
            (fps, expanded)
        };
        assert_eq!(cut(1), cut(2));
    }

    /// Panics when it expands `self.0`.
    struct Faulty(u32);

    impl Model for Faulty {
        type State = u32;
        type Label = ();
        fn init_states(&self) -> Box<dyn Iterator<Item = u32> + '_> {
            Box::new(std::iter::once(0))
        }
        fn next_states(&self, s: &u32) -> Vec<((), u32)> {
            assert_ne!(*s, self.0, "the faulty state");
            vec![((), s + 1), ((), s + 2)]
        }
    }

    #[test]
    #[should_panic(expected = "the faulty state")]
    fn a_panicking_worker_fails_the_search_instead_of_hanging_it() {
        let opts = Options {
            threads: 2,
            ..Options::default()
        };
        bare(&Faulty(5_000), unbounded(), opts);
    }
}
