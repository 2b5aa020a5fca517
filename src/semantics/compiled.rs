//! The reasoning cycle compiled for search: states made of shared, interned parts, and the
//! two phases of a cycle memoized on the beliefs they read.
//!
//! [`Semantics::successors`] clones a whole [`State`] (terms, substitutions, stacks) for
//! every successor and re-runs plan selection and body steps from scratch each time. Yet a
//! cycle looks at little: deliberation at the first event and the atoms its relevant plans'
//! contexts query, acting at the first intention and the atoms its next step (and the
//! `while` conditions around it) query, when the library
//! [`is_local`](Semantics::is_local). So [`Compiled`] keeps each distinct belief set, event
//! and intention once ([`Part`], with its hash and the atoms it reads), a state as a
//! [`Packed`] list of parts, and each phase's outcome per part and *read* beliefs: the
//! same step of the same intention, with the same atoms around, is computed once however
//! many states it occurs in. A phase is computed by the reference functions of
//! [`Semantics`] on a state holding only that part and the read beliefs, and an act phase
//! is kept as the change it makes to the beliefs; `tests/suite/compiled.rs` checks that the two
//! transition systems agree on every reachable state of every example project, notes and
//! fingerprints included.
//!
//! Tables are sharded behind mutexes, so that the search threads share them. Parts and
//! memoized outcomes are boxed and never freed before the [`Compiled`] that holds them, so
//! states and notes refer to them by plain references (no reference counting between
//! threads).

use super::cycle::{Note, Semantics};
use super::recent::{recently, Recently};
use super::state::{hash_parts, part_hash, requests_of, Event, Intention, Pending, State};
use crate::model::atoms::{AtomId, AtomSet};

/// The belief base of a state: its atoms and [`State::order`].
pub type Base = (AtomSet, Vec<AtomId>);
use smallvec::SmallVec;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hash, Hasher};
use std::ops::Deref;
use std::ptr::NonNull;
use std::sync::{Mutex, MutexGuard};

/// A part of states (a belief set, an event, an intention), kept once: its value, its
/// [`part_hash`], and the atoms the phase that takes it reads.
#[derive(Debug)]
pub struct Part<T> {
    hash: u64,
    reads: AtomSet,
    value: T,
    /// What a client derived from the part, kept with it ([`Annex`]).
    annex: Annex,
}

/// Words that one client (a memo, by its serial) derived from a part, kept with the part:
/// read where the part is, which the state being summarized has just read, instead of
/// in a table of its own (at 6 cups, a million belief bases: a lock and a probe that
/// missed the cache on most states). The first client to set it owns it; any other keeps
/// what it derives elsewhere.
#[derive(Debug, Default)]
pub struct Annex(std::sync::OnceLock<(u64, Box<[u64]>)>);

/// What [`Annex::read`] finds.
#[derive(Debug, PartialEq, Eq)]
pub enum Annexed<'a> {
    /// Nothing yet.
    Empty,
    /// The words the client asking set.
    Mine(&'a [u64]),
    /// Another client's words.
    Other,
}

impl Annex {
    /// What the client `serial` finds.
    pub fn read(&self, serial: u64) -> Annexed<'_> {
        match self.0.get() {
            None => Annexed::Empty,
            Some((owner, words)) if *owner == serial => Annexed::Mine(words),
            Some(_) => Annexed::Other,
        }
    }

    /// Keeps `words` for the client `serial`, unless a client set some first.
    pub fn set(&self, serial: u64, words: Box<[u64]>) {
        let _ = self.0.set((serial, words));
    }
}

impl<T> Deref for Part<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

impl<T: PartialEq> PartialEq for Part<T> {
    fn eq(&self, other: &Part<T>) -> bool {
        std::ptr::eq(self, other) || (self.hash == other.hash && self.value == other.value)
    }
}

impl<T: Eq> Eq for Part<T> {}

impl<T> Hash for Part<T> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u64(self.hash);
    }
}

/// A hasher for keys that are already well-mixed hashes: it keeps the last `u64` written.
#[derive(Default)]
struct PassThrough(u64);

impl Hasher for PassThrough {
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = x;
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

type Fast = BuildHasherDefault<PassThrough>;

/// Tables are split in this many shards, each behind its own lock.
const SHARDS: usize = 64;

/// The shard of a hash: bits the hash tables themselves use little (they take the low
/// bits for the bucket and the top seven as a tag).
fn shard_of(hash: u64) -> usize {
    (hash >> 40) as usize % SHARDS
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // A panic in another search thread is re-raised by the explorer; the tables it left
    // are consistent (every insertion is a single call).
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// A reference to something boxed in a table of a [`Compiled`], valid as long as it.
/// Transparent, so that a slice of them reads as a slice of references ([`Agenda`]).
#[repr(transparent)]
struct Held<T: ?Sized>(NonNull<T>);

impl<T: ?Sized> Clone for Held<T> {
    fn clone(&self) -> Held<T> {
        *self
    }
}

impl<T: ?Sized> Copy for Held<T> {}

// SAFETY: a `Held` is only read through shared references, and what it points to is
// `Sync` (parts and notes are plain data).
unsafe impl<T: ?Sized + Sync> Send for Held<T> {}
// SAFETY: as above.
unsafe impl<T: ?Sized + Sync> Sync for Held<T> {}

impl<T: ?Sized> Held<T> {
    fn new(r: &T) -> Held<T> {
        Held(NonNull::from(r))
    }

    /// The referent, for as long as its owner is borrowed.
    ///
    /// SAFETY: the caller's `_owner` must be the [`Compiled`] whose tables hold the box this
    /// points into. Boxes in those tables are never moved out, replaced or dropped before
    /// the tables are, so the referent lives (unchanged) as long as `_owner`.
    unsafe fn get<'c>(self, _owner: &'c Compiled) -> &'c T {
        // SAFETY: see above.
        unsafe { self.0.as_ref() }
    }
}

/// Each distinct value once.
struct Interner<T> {
    shards: Vec<Mutex<HashSet<Box<Part<T>>, Fast>>>,
}

impl<T: Hash + Eq> Interner<T> {
    fn new() -> Interner<T> {
        Interner {
            shards: (0..SHARDS).map(|_| Mutex::default()).collect(),
        }
    }

    /// The part holding `value`, its read atoms computed by `reads` when it is new.
    fn intern(&self, value: T, reads: impl FnOnce(&T) -> AtomSet) -> Held<Part<T>> {
        self.intern_hashed(part_hash(&value), value, reads)
    }

    /// [`Interner::intern`] for a `value` whose hash is already known.
    fn intern_hashed(
        &self,
        hash: u64,
        value: T,
        reads: impl FnOnce(&T) -> AtomSet,
    ) -> Held<Part<T>> {
        let probe = Part {
            hash,
            reads: AtomSet::default(),
            value,
            annex: Annex::default(),
        };
        let mut shard = lock(&self.shards[shard_of(probe.hash)]);
        if let Some(p) = shard.get(&probe) {
            return Held::new(&**p);
        }
        let part = Box::new(Part {
            reads: reads(&probe.value),
            ..probe
        });
        let held = Held::new(&*part);
        shard.insert(part);
        held
    }

    fn len(&self) -> usize {
        self.shards.iter().map(|s| lock(s).len()).sum()
    }
}

/// A memo key: a part (by address: parts are unique) and the beliefs it reads.
#[derive(PartialEq, Eq)]
struct Key {
    part: usize,
    read: SmallVec<[u64; 4]>,
    hash: u64,
}

impl Hash for Key {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u64(self.hash);
    }
}

impl Key {
    /// The key of `part` in a state with belief base `base`; `extra` is anything else the
    /// phase depends on.
    fn new<T>(part: &Part<T>, base: &Base, extra: u64) -> Key {
        // Pushed one by one: collecting and extending through iterators was most of
        // making a key (a third of the memo's lookups' instructions).
        let mut read: SmallVec<[u64; 4]> = SmallVec::new();
        let mut h = QuickHasher(part.hash);
        let mut add = |w: u64| {
            h.word(w);
            read.push(w);
        };
        for (b, r) in base.0.words().iter().zip(part.reads.words()) {
            add(b & r);
        }
        // The order of the read beliefs, where it is kept.
        for a in &base.1 {
            if part.reads.contains(*a) {
                add(u64::from(a.0));
            }
        }
        add(extra);
        Key {
            part: part as *const Part<T> as usize,
            read,
            hash: h.finish(),
        }
    }
}

/// splitmix64's finalizer: every bit of `h` reaches the shard and bucket bits.
pub(crate) fn mix(mut h: u64) -> u64 {
    h ^= h >> 30;
    h = h.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h ^= h >> 27;
    h = h.wrapping_mul(0x94d0_49bb_1331_11eb);
    h ^ (h >> 31)
}

/// A hasher for the search's own tables, whose keys are a few addresses, counts and flags:
/// a multiply and rotate per word mixes them well enough (with splitmix64's finalizer, so
/// that shard and bucket bits see every bit), where SipHash cost a tenth of a user's
/// search. No input chooses these keys to collide.
pub(crate) type Quick = BuildHasherDefault<QuickHasher>;

/// See [`Quick`].
#[derive(Default)]
pub(crate) struct QuickHasher(u64);

impl QuickHasher {
    fn word(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl Hasher for QuickHasher {
    fn write(&mut self, bytes: &[u8]) {
        for c in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..c.len()].copy_from_slice(c);
            self.word(u64::from_le_bytes(w));
        }
    }

    fn write_u8(&mut self, x: u8) {
        self.word(u64::from(x));
    }

    fn write_u32(&mut self, x: u32) {
        self.word(u64::from(x));
    }

    fn write_u64(&mut self, x: u64) {
        self.word(x);
    }

    fn write_usize(&mut self, x: usize) {
        self.word(x as u64);
    }

    fn finish(&self) -> u64 {
        mix(self.0)
    }
}

/// Outcomes per key, computed once (or, when two threads race, twice alike).
struct Memo<V> {
    shards: Vec<Mutex<HashMap<Key, Box<V>, Fast>>>,
}

impl<V> Memo<V> {
    fn new() -> Memo<V> {
        Memo {
            shards: (0..SHARDS).map(|_| Mutex::default()).collect(),
        }
    }

    fn get(&self, key: Key, compute: impl FnOnce() -> V) -> Held<V> {
        let shard = &self.shards[shard_of(key.hash)];
        if let Some(v) = lock(shard).get(&key) {
            return Held::new(&**v);
        }
        // Computed without the lock: computing interns parts, which takes other locks.
        let v = Box::new(compute());
        Held::new(&**lock(shard).entry(key).or_insert(v))
    }

    fn len(&self) -> usize {
        self.shards.iter().map(|s| lock(s).len()).sum()
    }
}

/// What a state holds besides its beliefs and requests: its events, its intentions and the
/// intention waiting for its action's feedback, as parts. Interned whole, so that a
/// [`Packed`] state is three words: frontiers of millions of states stay small.
struct Agenda {
    events: SmallVec<[Held<Part<Event>>; 4]>,
    intentions: SmallVec<[Held<Part<Intention>>; 4]>,
    pending: Option<Held<Part<Pending>>>,
}

/// `parts` as references, living as long as the borrow of what holds them.
///
/// SAFETY: the caller's `parts` must point to what lives at least as long as that borrow.
/// (`Held` is a transparent non-null pointer, laid out as a reference.)
unsafe fn refs<T>(parts: &[Held<T>]) -> &[&T] {
    // SAFETY: same layout; the referents live long enough (see above).
    unsafe { std::slice::from_raw_parts(parts.as_ptr().cast::<&T>(), parts.len()) }
}

/// References as parts held: copied as a slice (collecting through an iterator, SmallVec's
/// generic `extend`, cost several times the copy on every transition).
fn helds<'a, T>(parts: &'a [&'a T]) -> &'a [Held<T>] {
    // SAFETY: same layout (`Held` is a transparent non-null pointer), and a reference is
    // a valid non-null pointer.
    unsafe { std::slice::from_raw_parts(parts.as_ptr().cast::<Held<T>>(), parts.len()) }
}

// SAFETY (every method): an agenda's parts are in the tables of the [`Compiled`] whose table
// holds the agenda, so they live at least as long as it.
impl Agenda {
    fn events(&self) -> &[&Part<Event>] {
        // SAFETY: see above.
        unsafe { refs(&self.events) }
    }

    fn intentions(&self) -> &[&Part<Intention>] {
        // SAFETY: see above.
        unsafe { refs(&self.intentions) }
    }

    fn pending(&self) -> Option<&Part<Pending>> {
        // SAFETY: see above.
        self.pending.map(|p| unsafe { p.0.as_ref() })
    }

    /// A hash of the parts' own hashes, cheaper than hashing them again one by one: an
    /// agenda is interned at every transition.
    fn mixed(&self) -> u64 {
        let mut h = QuickHasher(self.events.len() as u64);
        let words = self.events().iter().map(|e| e.hash);
        let words = words.chain(self.intentions().iter().map(|i| i.hash));
        words
            .chain(self.pending().map(|p| p.hash))
            .for_each(|w| h.word(w));
        h.finish()
    }
}

// Parts are interned: the same part is the same address, so an agenda is equal to another
// when it holds the same addresses, and hashes as the parts' own hashes.
impl PartialEq for Agenda {
    fn eq(&self, o: &Agenda) -> bool {
        fn same<T>(a: &[&Part<T>], b: &[&Part<T>]) -> bool {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| std::ptr::eq(*x, *y))
        }
        same(self.events(), o.events())
            && same(self.intentions(), o.intentions())
            && self.pending.map(|p| p.0) == o.pending.map(|p| p.0)
    }
}

impl Eq for Agenda {}

impl Hash for Agenda {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u64(self.mixed());
    }
}

impl std::fmt::Debug for Agenda {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Agenda")
            .field("events", &self.events())
            .field("intentions", &self.intentions())
            .field("pending", &self.pending())
            .finish()
    }
}

/// Per part (by address) and a key: a value computed once, without the shard's lock held
/// (computing interns parts, which takes other locks). Two kinds: [`Images`], and what a
/// client derives from a part ([`Compiled::derived`]).
struct PerPart<V> {
    shards: Vec<Mutex<PerPartShard<V>>>,
}

/// One shard of [`PerPart`]: per part address and key, the value.
type PerPartShard<V> = HashMap<(usize, u64), V, Quick>;

impl<V> PerPart<V> {
    fn new() -> PerPart<V> {
        PerPart {
            shards: (0..SHARDS).map(|_| Mutex::default()).collect(),
        }
    }

    /// `read` of the value for the part at `address` (whose hash is `hash`) and `key`,
    /// made by `compute` the first time.
    fn get<R>(
        &self,
        (address, hash): (usize, u64),
        key: u64,
        read: impl Fn(&V) -> R,
        compute: impl FnOnce() -> V,
    ) -> R {
        let shard = &self.shards[shard_of(mix(hash ^ key.rotate_left(32)))];
        if let Some(v) = lock(shard).get(&(address, key)) {
            return read(v);
        }
        let v = compute();
        read(lock(shard).entry((address, key)).or_insert(v))
    }
}

/// The image of each part under each map (by the part's address and the map's id), computed
/// once: a symmetric search maps every state it meets by several renamings, and a memo
/// [`Key`] (which gathers beliefs read) costs more than this lookup.
type Images<T> = PerPart<Held<Part<T>>>;

/// Per part and a client's tag: numbers the client derived from it, each list boxed so
/// that it stays where it is while the table grows.
type Derived<T> = PerPart<Box<[T]>>;

/// Per thread, the images [`Compiled::map`] met, by the address of the part (or the
/// requests made) and the map id: a symmetric search maps every successor by several
/// renamings, and two threads taking the shared tables' locks for the same few entries
/// spent most of `map`'s time passing those locks' cache lines between cores.
#[derive(Default)]
struct LocalImages {
    /// The [`Compiled::serial`] these images are of.
    serial: u64,
    parts: HashMap<(usize, u64), usize, Quick>,
    requests: HashMap<(u64, u64), u64, Quick>,
}

thread_local! {
    static LOCAL_IMAGES: std::cell::RefCell<LocalImages> = Default::default();
}

/// How many entries each of a thread's tables of parts made lately has ([`LOCAL_BASES`],
/// [`LOCAL_AGENDAS`], [`LOCAL_MEMOS`]).
const LOCAL_PARTS: usize = 1 << 12;

/// Which memo an entry of [`LOCAL_MEMOS`] is of.
#[derive(Clone, Copy)]
enum Memoized {
    Deliberation = 1,
    ProcAct = 2,
    Act = 3,
}

// Per thread, the parts a transition made last (`recently`, tagged with the system's
// serial): a job's states are mostly successors of a few states and make the same parts
// again. Found there, a part costs no shard's lock (whose cache line the threads passed
// back and forth) and no probe of a shared table far larger than the cache.
thread_local! {
    /// By the addresses of a belief base and of an act phase's outcome that changes it:
    /// the belief base it makes, by address.
    static LOCAL_BASES: Recently<(usize, usize), usize> = const { std::cell::RefCell::new(Vec::new()) };
    /// By an agenda's hash ([`Agenda::mixed`]): an agenda interned with it, by address.
    static LOCAL_AGENDAS: Recently<u64, usize> = const { std::cell::RefCell::new(Vec::new()) };
    /// By the address of a part, of a belief base and the memo ([`Memoized`]): what the
    /// memo holds for them, by address (the belief base decides the beliefs the part reads,
    /// so the memo's [`Key`] need not be made).
    static LOCAL_MEMOS: Recently<(usize, usize, usize), usize> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The bit that marks a map id as a caller's own code rather than one of
/// [`Compiled::map_id`]'s.
pub const MAP_CODE: u64 = 1 << 63;

/// A state of the compiled search: [`State`]'s parts, shared. Hashed exactly as the
/// [`State`] it stands for, so that its fingerprint is that state's.
#[derive(Clone, Copy, Debug)]
pub struct Packed<'c> {
    beliefs: &'c Part<Base>,
    agenda: &'c Part<Agenda>,
    requested: u64,
}

impl PartialEq for Packed<'_> {
    fn eq(&self, o: &Packed<'_>) -> bool {
        // Parts are interned: equal parts are the same part.
        self.requested == o.requested
            && std::ptr::eq(self.beliefs, o.beliefs)
            && std::ptr::eq(self.agenda, o.agenda)
    }
}

impl Eq for Packed<'_> {}

impl Hash for Packed<'_> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        let a = &self.agenda.value;
        hash_parts(
            h,
            self.beliefs.hash,
            a.events().iter().map(|e| e.hash),
            a.intentions().iter().map(|i| i.hash),
            a.pending().map(|p| p.hash),
            // Agents that `.wait` are not compiled (their library is not local).
            std::iter::empty(),
            self.requested,
            // An agent that changes its plan library is not local, so never compiled.
            None,
            // Nor is one of several agents.
            None,
            // Nor one with atomic plans.
            false,
        );
    }
}

/// A [`Packed`] state opened for a transition to change: its agenda as lists of parts.
struct Open<'c> {
    beliefs: &'c Part<Base>,
    events: SmallVec<[&'c Part<Event>; 4]>,
    intentions: SmallVec<[&'c Part<Intention>; 4]>,
    pending: Option<&'c Part<Pending>>,
    requested: u64,
}

impl<'c> Packed<'c> {
    /// The beliefs.
    pub fn beliefs(&self) -> &AtomSet {
        &self.beliefs.value.0
    }

    /// A hash of the state's identity (its parts' addresses and its requests): cheap, and
    /// equal for equal states, which are made of the same interned parts.
    pub fn address_hash(&self) -> u64 {
        let mut h = QuickHasher::default();
        h.write_usize(self.beliefs as *const Part<Base> as usize);
        h.write_usize(self.agenda as *const Part<Agenda> as usize);
        h.write_u64(self.requested);
        h.finish()
    }

    /// What a client derived from the belief base ([`Annex`]): the same for every state
    /// with equal beliefs and order.
    pub fn beliefs_annex(&self) -> &'c Annex {
        &self.beliefs.annex
    }

    /// An identity of the beliefs and their order: equal for equal ones (belief bases are
    /// interned).
    pub fn beliefs_key(&self) -> usize {
        self.beliefs as *const Part<Base> as usize
    }

    /// An identity of the agenda (events, intentions, the pending action): equal for equal
    /// agendas (they are interned), so for the same intentions in the same places too.
    pub fn agenda_key(&self) -> usize {
        self.agenda as *const Part<Agenda> as usize
    }

    /// An identity of every intention (see [`Packed::all_intentions`]): equal for the same
    /// intentions in the same places (intentions, events and pending actions are interned).
    pub fn intentions_key(&self) -> SmallVec<[usize; 8]> {
        let a = &self.agenda.value;
        let mut key: SmallVec<[usize; 8]> = a
            .intentions()
            .iter()
            .map(|i| *i as *const Part<Intention> as usize)
            .collect();
        key.push(
            a.pending()
                .map_or(0, |p| p as *const Part<Pending> as usize),
        );
        key.extend(
            a.events()
                .iter()
                .filter(|e| e.value.intention.is_some())
                .map(|e| *e as *const Part<Event> as usize),
        );
        key
    }

    /// Their order (see [`State::order`]).
    pub fn order(&self) -> &[AtomId] {
        &self.beliefs.value.1
    }

    /// The events, first in first out.
    pub fn events(&self) -> impl Iterator<Item = &'c Event> {
        self.agenda.value.events().iter().map(|e| &e.value)
    }

    /// The requests made, a bit each (see [`State::requested`]).
    pub fn requested(&self) -> u64 {
        self.requested
    }

    /// The running intentions, in the order they take turns.
    pub fn intentions(&self) -> impl Iterator<Item = &'c Intention> {
        self.agenda.value.intentions().iter().map(|i| &i.value)
    }

    /// The intention that waits for its action's feedback, if any.
    pub fn pending(&self) -> Option<&'c Pending> {
        self.agenda.value.pending().map(|p| &p.value)
    }

    /// The first event of the queue.
    pub fn first_event(&self) -> Option<&'c Event> {
        self.agenda.value.events().first().map(|e| &e.value)
    }

    /// Whether the agent has nothing to do (see [`State::is_idle`]).
    pub fn is_idle(&self) -> bool {
        let a = &self.agenda.value;
        a.events.is_empty() && a.intentions.is_empty() && a.pending.is_none()
    }

    /// Every intention: running, waiting for its action's feedback, suspended in an event
    /// (see [`State::all_intentions`]).
    pub fn all_intentions(&self) -> impl Iterator<Item = &'c Intention> {
        let a = &self.agenda.value;
        a.intentions()
            .iter()
            .map(|i| &i.value)
            .chain(a.pending().map(|p| &p.value.intention))
            .chain(a.events().iter().filter_map(|e| e.value.intention.as_ref()))
    }

    /// The requests still being served (see [`State::pending_requests`]).
    pub fn pending_requests(&self) -> u64 {
        let a = &self.agenda.value;
        requests_of(
            a.intentions()
                .iter()
                .map(|i| &i.value)
                .chain(a.pending().map(|p| &p.value.intention)),
            a.events().iter().map(|e| &e.value),
        )
    }
}

/// [`Packed`] states as one word each, for a graph that keeps every state (the users'
/// searches read the agent's: `check::explanation::Stored`): a third of a [`Packed`]'s 24
/// bytes, a gigabyte less at 6 cups, whose fresh pages the kernel (and this project's
/// virtual machines' hosts) must clear. A word holds the belief base's address (shifted:
/// parts are aligned to 8 bytes) in its low 44 bits, and in the other 20 the
/// number of the state's agenda and requests, numbered in the order they are met: a state
/// read back needs no table for its beliefs, which most of what reads it uses.
#[derive(Default)]
pub struct Words<'c> {
    /// The agendas and requests, by number.
    rest: Vec<(&'c Part<Agenda>, u64)>,
    /// Their numbers, by the agenda's address and the requests.
    numbers: HashMap<(usize, u64), u32, Quick>,
    /// Direct-mapped: the agendas' addresses, requests and numbers (plus one; 0 when
    /// empty) met lately, before `numbers` is probed: a graph has millions of states to
    /// thousands of numbers.
    recent: Vec<(usize, u64, u32)>,
}

/// The bits of a [`Words`] word that hold the belief base's address divided by 8: every
/// address below 2^47, which user space on x86-64 and on aarch64 with 47 or 48-bit
/// addresses gives unless asked for more (a larger one is refused: [`Words::word`]).
const ADDRESS_BITS: u32 = 44;

/// How many agendas and requests [`Words`] keeps at hand (a power of two): the kitchen
/// has thousands (7,007 at 5 cups). At 6 cups perf put [`Words::word`] at about 1 s of the
/// merging thread with 1,024 slots and 0.8 s with these; a map alone was not measured.
const RECENT_REST: usize = 1 << 13;

impl<'c> Words<'c> {
    /// `p` as one word; `None` when its belief base's address does not fit
    /// (below 2^47) or 2^20 agendas and requests have numbers already.
    pub fn word(&mut self, p: &Packed<'c>) -> Option<u64> {
        let address = (p.beliefs as *const Part<Base>).expose_provenance();
        if address & 7 != 0 || address >> (ADDRESS_BITS + 3) != 0 {
            return None;
        }
        let rest = self.number(p.agenda, p.requested)?;
        Some((address >> 3) as u64 | u64::from(rest) << ADDRESS_BITS)
    }

    /// The number of `agenda` with `requested`, given when first met.
    fn number(&mut self, agenda: &'c Part<Agenda>, requested: u64) -> Option<u32> {
        let key = (agenda as *const Part<Agenda> as usize, requested);
        if self.recent.is_empty() {
            self.recent = vec![(0, 0, 0); RECENT_REST];
        }
        let slot = mix(key.0 as u64 ^ requested.rotate_left(29)) as usize & (RECENT_REST - 1);
        let (a, r, n) = self.recent[slot];
        if n != 0 && (a, r) == key {
            return Some(n - 1);
        }
        let n = match self.numbers.get(&key) {
            Some(&n) => n,
            None => {
                let n = u32::try_from(self.rest.len())
                    .ok()
                    .filter(|n| u64::from(*n) < 1 << (64 - ADDRESS_BITS))?;
                self.rest.push((agenda, requested));
                self.numbers.insert(key, n);
                n
            }
        };
        self.recent[slot] = (key.0, key.1, n + 1);
        Some(n)
    }

    /// The belief base of `word`, and the number of its agenda and requests
    /// ([`Words::packed`] makes the state of both).
    ///
    /// # Safety
    ///
    /// `word` must be one that [`Words::word`] of this value returned: its belief base is
    /// then a part of the compiled cycle, which lives for `'c`.
    pub unsafe fn split(&self, word: u64) -> (&'c Part<Base>, u32) {
        let address = ((word & ((1 << ADDRESS_BITS) - 1)) << 3) as usize;
        // SAFETY: `address` is that of a belief base of the compiled cycle whose address was
        // exposed by `Words::word` (see above), which lives and stays put for `'c`.
        let beliefs = unsafe { &*std::ptr::with_exposed_provenance::<Part<Base>>(address) };
        (beliefs, (word >> ADDRESS_BITS) as u32)
    }

    /// The state of belief base `beliefs` whose agenda and requests are numbered `rest`
    /// (panics on a number this value did not give).
    pub fn packed(&self, beliefs: &'c Part<Base>, rest: u32) -> Packed<'c> {
        let (agenda, requested) = self.rest[rest as usize];
        Packed {
            beliefs,
            agenda,
            requested,
        }
    }

    /// The agenda's identity ([`Packed::agenda_key`]) of the agenda and requests
    /// numbered `rest`, without making the state.
    pub fn agenda_key(&self, rest: u32) -> usize {
        self.rest[rest as usize].0 as *const Part<Agenda> as usize
    }

    /// How many agendas and requests have numbers.
    pub fn numbered(&self) -> usize {
        self.rest.len()
    }

    /// The fingerprints of the states this value made words of, from the words alone
    /// ([`WordHashes`]), `compiled` being the cycle whose parts they hold.
    pub fn hashes(&self, compiled: &Compiled<'_, '_>) -> WordHashes {
        let mut bases = Vec::with_capacity(compiled.beliefs.len());
        for shard in &compiled.beliefs.shards {
            let shard = lock(shard);
            bases.extend(shard.iter().map(|b| {
                let address = (&**b as *const Part<Base>).addr() as u64;
                (address >> 3, b.hash)
            }));
        }
        bases.sort_unstable();
        let rest = (self.rest.iter())
            .map(|(agenda, requested)| {
                let a = &agenda.value;
                RestHashes {
                    events: a.events().iter().map(|e| e.hash).collect(),
                    intentions: a.intentions().iter().map(|i| i.hash).collect(),
                    pending: a.pending().map(|p| p.hash),
                    requested: *requested,
                }
            })
            .collect();
        WordHashes { bases, rest }
    }
}

/// [`Words`] words in 48 bits, for a graph that keeps one per state: the belief base's
/// address as its distance from an origin near the first met (within 16 GiB either side),
/// and the agenda's number below 2^16. The kitchen's belief bases lie within a few
/// gigabytes of one another and it has thousands of agendas (7,007 at 5 cups): 2 bytes a
/// state less than a whole word, 131 MB at 6 cups.
#[derive(Clone, Copy, Debug)]
pub struct ShortWords {
    /// The address part of a word, 2^31 below the first one's.
    origin: u64,
}

impl ShortWords {
    /// Words short around `first`'s belief base.
    pub fn around(first: u64) -> ShortWords {
        let address = first & ((1 << ADDRESS_BITS) - 1);
        ShortWords {
            origin: address.saturating_sub(1 << 31),
        }
    }

    /// `word` in 48 bits, if it fits.
    #[inline]
    pub fn short(&self, word: u64) -> Option<u64> {
        let distance = (word & ((1 << ADDRESS_BITS) - 1)).checked_sub(self.origin)?;
        let rest = word >> ADDRESS_BITS;
        (distance >> 32 == 0 && rest >> 16 == 0).then_some(distance | rest << 32)
    }

    /// The word `short` stands for ([`ShortWords::short`]'s inverse).
    #[inline]
    pub fn long(&self, short: u64) -> u64 {
        (self.origin + (short & 0xffff_ffff)) | (short >> 32) << ADDRESS_BITS
    }
}

/// The fingerprints of [`Words`] words, with nothing borrowed: the belief bases' hashes
/// by address and the hashes of the agendas' parts by number. A graph whose states are
/// held as words need not keep 8 bytes a state of fingerprints too (525 MB at 6 cups):
/// the few it reads after its search (to replay a run) come from here.
pub struct WordHashes {
    /// Every belief base's address (shifted as in a word) and hash, by address.
    bases: Vec<(u64, u64)>,
    /// By number, the hashes of the agenda's parts, and the requests.
    rest: Vec<RestHashes>,
}

/// What a state's fingerprint reads of its agenda and requests ([`WordHashes`]).
struct RestHashes {
    events: Box<[u64]>,
    intentions: Box<[u64]>,
    pending: Option<u64>,
    requested: u64,
}

impl WordHashes {
    /// The fingerprint of the state whose word is `word` (as [`part_hash`] of its
    /// [`Packed`] state), or `None` for a word of no state of the [`Words`] this came from.
    pub fn fingerprint(&self, word: u64) -> Option<u64> {
        let address = word & ((1 << ADDRESS_BITS) - 1);
        let at = (self.bases).binary_search_by_key(&address, |b| b.0).ok()?;
        let rest = self.rest.get(usize::try_from(word >> ADDRESS_BITS).ok()?)?;
        Some(part_hash(&Reborn(self.bases[at].1, rest)))
    }
}

/// A state's hash from its belief base's hash and its agenda's ([`WordHashes`]): fed as
/// [`Packed`]'s `Hash` feeds it.
struct Reborn<'a>(u64, &'a RestHashes);

impl Hash for Reborn<'_> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        let r = self.1;
        hash_parts(
            h,
            self.0,
            r.events.iter().copied(),
            r.intentions.iter().copied(),
            r.pending,
            std::iter::empty(),
            r.requested,
            None,
            None,
            false,
        );
    }
}

/// What a transition of the compiled search did: the notes of its phases, shared with
/// every transition that took the same phase.
#[derive(Clone, Debug, Default)]
pub struct Notes<'c>(SmallVec<[&'c [Note]; 2]>);

impl Notes<'_> {
    /// The notes in order.
    pub fn iter(&self) -> impl Iterator<Item = &Note> {
        self.0.iter().flat_map(|n| n.iter())
    }

    /// An identity of these notes: equal for notes that are the same shared values (each
    /// phase's notes are kept once per memoized outcome).
    pub fn key(&self) -> SmallVec<[usize; 4]> {
        self.0
            .iter()
            .flat_map(|n| [n.as_ptr() as usize, n.len()])
            .collect()
    }

    /// [`Notes::key`] in four words (zeros after the last), when the notes come from at
    /// most two phases: cheaper to make and compare.
    pub fn short_key(&self) -> Option<[usize; 4]> {
        let mut out = [0; 4];
        match &self.0[..] {
            [] => {}
            [a] => out[..2].copy_from_slice(&[a.as_ptr() as usize, a.len()]),
            [a, b] => out = [a.as_ptr() as usize, a.len(), b.as_ptr() as usize, b.len()],
            _ => return None,
        }
        Some(out)
    }

    /// The notes as [`Semantics::successors`] gives them.
    pub fn to_vec(&self) -> Vec<Note> {
        self.iter().cloned().collect()
    }
}

/// One option of a deliberation: the events it queues, the intention it starts or resumes,
/// its notes.
struct Chosen {
    events: SmallVec<[Held<Part<Event>>; 1]>,
    intention: Option<Held<Part<Intention>>>,
    notes: Box<[Note]>,
}

/// One act phase (or its `ProcAct` stage): the atoms it adds and removes (and those added
/// whose order is kept, newest first), the events it queues, the intention that goes to
/// the back of the queue (none when it finished, failed, was suspended or waits for its
/// action's feedback), the intention that waits for its action's feedback, its notes.
struct Acted {
    added: AtomSet,
    removed: AtomSet,
    front: Vec<AtomId>,
    events: SmallVec<[Held<Part<Event>>; 2]>,
    back: Option<Held<Part<Intention>>>,
    pending: Option<Held<Part<Pending>>>,
    notes: Box<[Note]>,
}

/// A phase computed for a memo, with the parts it was computed on (the belief base is the
/// whole state's): what [`Compiled::phases_equivariant`] checks.
#[derive(Clone, Copy)]
enum Phase {
    Deliberation(Held<Part<Event>>, Held<Part<Base>>),
    Act(Held<Part<Intention>>, Held<Part<Base>>),
    ProcAct(Held<Part<Pending>>),
}

/// What [`Compiled::phases_equivariant`] compares of an act phase (see
/// [`Compiled::acted_key`]).
type ActedKey = (
    Vec<AtomId>,
    Vec<AtomId>,
    Vec<AtomId>,
    Vec<usize>,
    Option<usize>,
    Option<usize>,
);

/// A part's address: its identity.
fn address<T>(part: &Part<T>) -> usize {
    part as *const Part<T> as usize
}

/// The compiled transition system of a [`Semantics`] whose library is local.
pub struct Compiled<'s, 'p> {
    sem: &'s Semantics<'p>,
    /// Distinct for every compiled system made: whose images a thread's [`LOCAL_IMAGES`]
    /// holds.
    serial: u64,
    beliefs: Interner<Base>,
    events: Interner<Event>,
    intentions: Interner<Intention>,
    pendings: Interner<Pending>,
    agendas: Interner<Agenda>,
    /// Per event and read beliefs: the options, and whether the deliberation goes on to
    /// the next event (an external belief event with no applicable plan).
    deliberations: Memo<(Vec<Chosen>, bool)>,
    acts: Memo<Acted>,
    proc_acts: Memo<Acted>,
    /// Per event and read beliefs: the plans applicable to it.
    applicable: Memo<Box<[u32]>>,
    /// Maps by name (see [`Compiled::map_id`]).
    map_ids: std::sync::RwLock<HashMap<Box<[u16]>, u64, Quick>>,
    /// Per requests made (a bit each) and map: their image.
    mapped_requests: std::sync::RwLock<HashMap<(u64, u64), u64, Quick>>,
    /// Per part and map (see [`Compiled::map`]): the part's image.
    mapped_bases: Images<Base>,
    mapped_events: Images<Event>,
    mapped_intentions: Images<Intention>,
    mapped_pendings: Images<Pending>,
    mapped_agendas: Images<Agenda>,
    /// Per agenda and a client's tag: what the client derived from the agenda (see
    /// [`Compiled::derived`]).
    derived: Derived<u16>,
    /// The same per belief base (see [`Compiled::derived_from_beliefs`]).
    derived_from_beliefs: Derived<u64>,
    /// Per request: its event and its note.
    requests: Vec<(Held<Part<Event>>, [Note; 1])>,
    /// Every phase computed for the memos, in the order they were computed.
    phases: Mutex<Vec<Phase>>,
}

/// A map of agent states that works part by part (see [`Compiled::map`]).
pub trait PartMap {
    /// The beliefs and their order.
    fn base(&self, b: &Base) -> Base;
    /// An event.
    fn event(&self, e: &Event) -> Event;
    /// An intention.
    fn intention(&self, i: &Intention) -> Intention;
    /// An intention that waits for its action's feedback.
    fn pending(&self, p: &Pending) -> Pending;
    /// The requests made (a bit each).
    fn requested(&self, r: u64) -> u64;
}

/// How many distinct parts and memoized phases a compiled search holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sizes {
    /// Distinct belief sets.
    pub beliefs: usize,
    /// Distinct events.
    pub events: usize,
    /// Distinct intentions.
    pub intentions: usize,
    /// Memoized deliberations (event, read beliefs).
    pub deliberations: usize,
    /// Memoized act phases (intention, read beliefs).
    pub acts: usize,
}

impl<'s, 'p> Compiled<'s, 'p> {
    /// The compiled form of `sem`, or `None` when its library is not local (then only the
    /// whole state decides a cycle, and [`Semantics::successors`] must be used).
    pub fn new(sem: &'s Semantics<'p>) -> Option<Compiled<'s, 'p>> {
        if !sem.is_local() {
            return None;
        }
        let mut c = Compiled {
            sem,
            serial: super::recent::serial(),
            beliefs: Interner::new(),
            events: Interner::new(),
            intentions: Interner::new(),
            pendings: Interner::new(),
            agendas: Interner::new(),
            deliberations: Memo::new(),
            acts: Memo::new(),
            proc_acts: Memo::new(),
            applicable: Memo::new(),
            map_ids: Default::default(),
            mapped_requests: Default::default(),
            mapped_bases: PerPart::new(),
            mapped_events: PerPart::new(),
            mapped_intentions: PerPart::new(),
            mapped_pendings: PerPart::new(),
            mapped_agendas: PerPart::new(),
            derived: PerPart::new(),
            derived_from_beliefs: PerPart::new(),
            requests: Vec::new(),
            phases: Mutex::default(),
        };
        c.requests = (0..sem.requests.len())
            .map(|r| {
                let event = c.event(sem.request_event(r));
                (event, [Note::Request { index: r as u8 }])
            })
            .collect();
        Some(c)
    }

    /// The semantics compiled.
    pub fn semantics(&self) -> &'s Semantics<'p> {
        self.sem
    }

    fn belief_set(&self, b: Base) -> Held<Part<Base>> {
        self.beliefs.intern(b, |_| AtomSet::default())
    }

    fn event(&self, e: Event) -> Held<Part<Event>> {
        self.events.intern(e, |e| self.sem.event_reads(e))
    }

    fn intention(&self, i: Intention) -> Held<Part<Intention>> {
        self.intentions.intern(i, |i| self.sem.intention_reads(i))
    }

    fn pending(&self, p: Pending) -> Held<Part<Pending>> {
        // `ProcAct` reads no belief: it clears finished plans or looks for a failure plan.
        self.pendings.intern(p, |_| AtomSet::default())
    }

    /// The packed form of a state.
    pub fn pack<'c>(&'c self, s: &State) -> Packed<'c> {
        // SAFETY: every `Held` here comes from this compiled system's tables.
        let open = unsafe {
            Open {
                beliefs: self
                    .belief_set((s.beliefs.clone(), s.order.clone()))
                    .get(self),
                events: s
                    .events
                    .iter()
                    .map(|e| self.event(e.clone()).get(self))
                    .collect(),
                intentions: s
                    .intentions
                    .iter()
                    .map(|i| self.intention(i.clone()).get(self))
                    .collect(),
                pending: s
                    .pending
                    .as_ref()
                    .map(|p| self.pending(p.clone()).get(self)),
                requested: s.requested,
            }
        };
        self.close(open)
    }

    /// `p` opened for a transition to change it.
    fn open<'c>(&'c self, p: &Packed<'c>) -> Open<'c> {
        let a = &p.agenda.value;
        // Copied as slices: collecting through an iterator cost several times the copy.
        Open {
            beliefs: p.beliefs,
            events: SmallVec::from_slice(a.events()),
            intentions: SmallVec::from_slice(a.intentions()),
            pending: a.pending(),
            requested: p.requested,
        }
    }

    /// `o` packed again: its agenda interned.
    fn close<'c>(&'c self, o: Open<'c>) -> Packed<'c> {
        let agenda = self.agenda_of(Agenda {
            events: SmallVec::from_slice(helds(&o.events)),
            intentions: SmallVec::from_slice(helds(&o.intentions)),
            pending: o.pending.map(Held::new),
        });
        Packed {
            beliefs: o.beliefs,
            // SAFETY: the agenda's part is in this system's tables.
            agenda: unsafe { agenda.get(self) },
            requested: o.requested,
        }
    }

    /// The agenda of these parts, which must be in this system's tables.
    fn agenda<'c>(
        &'c self,
        events: impl Iterator<Item = &'c Part<Event>>,
        intentions: impl Iterator<Item = &'c Part<Intention>>,
        pending: Option<&'c Part<Pending>>,
    ) -> Held<Part<Agenda>> {
        self.agenda_of(Agenda {
            events: events.map(Held::new).collect(),
            intentions: intentions.map(Held::new).collect(),
            pending: pending.map(Held::new),
        })
    }

    /// `agenda` interned; its parts must be in this system's tables. Found in this thread's
    /// [`LOCAL_AGENDAS`] when it made it lately.
    fn agenda_of(&self, agenda: Agenda) -> Held<Part<Agenda>> {
        let hash = agenda.mixed();
        let mut new = Some(agenda);
        let at = recently(
            &LOCAL_AGENDAS,
            LOCAL_PARTS,
            (self.serial, hash),
            || {
                let agenda = new.take().expect("interned once");
                let held = self
                    .agendas
                    .intern_hashed(hash, agenda, |_| AtomSet::default());
                held.0.as_ptr() as usize
            },
            |&at| at,
        );
        // SAFETY: the address is of an agenda in this system's tables (the entries are of
        // this system: its serial), which are never dropped while it lives.
        let held = Held(unsafe { NonNull::new_unchecked(at as *mut Part<Agenda>) });
        match new {
            // Another agenda of the same hash: interned, and not kept here.
            Some(agenda) if unsafe { held.get(self) }.value != agenda => self
                .agendas
                .intern_hashed(hash, agenda, |_| AtomSet::default()),
            _ => held,
        }
    }

    /// The state a packed one stands for.
    pub fn unpack(&self, p: &Packed) -> State {
        State {
            beliefs: p.beliefs.value.0.clone(),
            order: p.beliefs.value.1.clone(),
            events: p.events().cloned().collect(),
            intentions: p
                .agenda
                .value
                .intentions()
                .iter()
                .map(|i| i.value.clone())
                .collect(),
            pending: p.agenda.value.pending().map(|x| x.value.clone()),
            waiting: Vec::new(),
            requested: p.requested,
            library: None,
            told: Vec::new(),
            asked: 0,
            atomic: false,
        }
    }

    /// The initial states (see [`Semantics::initial_states`]).
    pub fn initial_states(&self) -> Vec<Packed<'_>> {
        self.sem
            .initial_states()
            .iter()
            .map(|s| self.pack(s))
            .collect()
    }

    /// The initial states made one at a time (see [`Semantics::initial_iter`]).
    pub fn initial_iter(&self) -> impl Iterator<Item = Packed<'_>> + '_ {
        self.sem.initial_iter().map(|s| self.pack(&s))
    }

    /// The plans applicable to the first event of `p` (see [`Semantics::applicable`]), none
    /// when it has no event: computed once per event and the beliefs its plans' contexts
    /// read, which is what the agent's search asks of every state when lint left plan
    /// overlaps to confirm.
    pub fn applicable_plans<'c>(&'c self, p: &Packed<'c>) -> &'c [u32] {
        let Some(event) = p.agenda.value.events().first() else {
            return &[];
        };
        let key = Key::new(event, &p.beliefs.value, 0);
        // SAFETY: memoized outcomes are in this system's tables.
        unsafe {
            self.applicable
                .get(key, || {
                    let read = Self::alone(&p.beliefs.value, &event.reads, None);
                    self.sem
                        .applicable(&read, &event.value.trigger, false)
                        .into_iter()
                        .map(|(plan, _)| plan)
                        .collect()
                })
                .get(self)
        }
    }

    /// The id, for [`Compiled::map`], of the map named `name` (a permutation of objects,
    /// say): one per distinct name. These ids count up from 0; a caller that can name its
    /// maps in 63 bits may instead use such a name with the top bit set ([`MAP_CODE`]),
    /// which needs no lookup.
    pub fn map_id(&self, name: &[u16]) -> u64 {
        if let Some(id) = self
            .map_ids
            .read()
            .unwrap_or_else(|e| e.into_inner())
            .get(name)
        {
            return *id;
        }
        let mut ids = self.map_ids.write().unwrap_or_else(|e| e.into_inner());
        let next = ids.len() as u64;
        *ids.entry(name.into()).or_insert(next)
    }

    /// What `derive` makes of `p`'s agenda (its events, intentions and pending action:
    /// nothing else of `p` may be read), computed once per agenda and `tag`. A client
    /// takes a tag of its own (one tag, one `derive`): the symmetry reduction keeps there
    /// the order in which an agenda's terms name objects.
    pub fn derived<'c>(
        &'c self,
        p: &Packed<'c>,
        tag: u64,
        derive: impl FnOnce(&Packed<'c>) -> Vec<u16>,
    ) -> &'c [u16] {
        let held = self.derived.get(
            (p.agenda_key(), p.agenda.hash),
            tag,
            |list| Held::new(&**list),
            || derive(p).into_boxed_slice(),
        );
        // SAFETY: the list is boxed in this system's table, never moved out, replaced or
        // dropped before the table is.
        unsafe { held.get(self) }
    }

    /// [`Compiled::derived`] for the beliefs and their order (`derive` may read nothing
    /// else of `p`): computed once per belief base and `tag`.
    pub fn derived_from_beliefs<'c>(
        &'c self,
        p: &Packed<'c>,
        tag: u64,
        derive: impl FnOnce(&Packed<'c>) -> Vec<u64>,
    ) -> &'c [u64] {
        let held = (self.derived_from_beliefs).get(
            (p.beliefs_key(), p.beliefs.hash),
            tag,
            |list| Held::new(&**list),
            || derive(p).into_boxed_slice(),
        );
        // SAFETY: as in `derived`.
        unsafe { held.get(self) }
    }

    /// The image of the requests made `r` under the map `id`, `f`, computed once.
    fn map_requests(&self, r: u64, id: u64, f: &impl PartMap) -> u64 {
        let known = self
            .mapped_requests
            .read()
            .unwrap_or_else(|e| e.into_inner())
            .get(&(r, id))
            .copied();
        known.unwrap_or_else(|| {
            let image = f.requested(r);
            self.mapped_requests
                .write()
                .unwrap_or_else(|e| e.into_inner())
                .insert((r, id), image);
            image
        })
    }

    /// The image of `p` under `f`, part by part: each distinct part is mapped once per map
    /// (`id` names the map, see [`Compiled::map_id`]; one `id`, one map), so that mapping a state costs a lookup per
    /// part. Renaming objects, for the symmetry reduction's equivariance check, is one.
    pub fn map<'c>(&'c self, p: &Packed<'c>, id: u64, f: &impl PartMap) -> Packed<'c> {
        let beliefs_at = p.beliefs as *const Part<Base> as usize;
        let agenda_at = p.agenda as *const Part<Agenda> as usize;
        let known = LOCAL_IMAGES.with(|l| {
            let mut l = l.borrow_mut();
            if l.serial != self.serial {
                *l = LocalImages {
                    serial: self.serial,
                    ..LocalImages::default()
                };
            }
            let beliefs = l.parts.get(&(beliefs_at, id)).copied()?;
            let agenda = l.parts.get(&(agenda_at, id)).copied()?;
            let requested = l.requests.get(&(p.requested, id)).copied()?;
            Some((beliefs, agenda, requested))
        });
        if let Some((beliefs, agenda, requested)) = known {
            // SAFETY: these addresses are of parts in this system's tables (the thread's
            // images are of the system whose serial they carry), which live as long as
            // it does.
            return unsafe {
                Packed {
                    beliefs: &*(beliefs as *const Part<Base>),
                    agenda: &*(agenda as *const Part<Agenda>),
                    requested,
                }
            };
        }
        let image = self.map_shared(p, id, f);
        LOCAL_IMAGES.with(|l| {
            let mut l = l.borrow_mut();
            if l.serial == self.serial {
                let beliefs = image.beliefs as *const Part<Base> as usize;
                let agenda = image.agenda as *const Part<Agenda> as usize;
                l.parts.insert((beliefs_at, id), beliefs);
                l.parts.insert((agenda_at, id), agenda);
                l.requests.insert((p.requested, id), image.requested);
            }
        });
        image
    }

    /// [`Compiled::map`] through the tables every thread shares.
    fn map_shared<'c>(&'c self, p: &Packed<'c>, id: u64, f: &impl PartMap) -> Packed<'c> {
        let a = &p.agenda.value;
        // An agenda's image is its parts' images: kept per agenda and map too.
        let agenda = self.image(&self.mapped_agendas, p.agenda, id, || {
            self.agenda(
                a.events().iter().map(|e| self.image_event(e, id, f)),
                a.intentions()
                    .iter()
                    .map(|i| self.image_intention(i, id, f)),
                a.pending().map(|x| self.image_pending(x, id, f)),
            )
        });
        Packed {
            beliefs: self.image_base(p.beliefs, id, f),
            agenda,
            requested: self.map_requests(p.requested, id, f),
        }
    }

    /// Whether every phase the memos computed so far commutes with the map `id`, `f`: its
    /// outcome on the parts' images is the image of its outcome (events, intentions and
    /// pending actions as parts, the beliefs it adds and removes, and the order it puts
    /// them in; notes aside, as the states are what a reduction merges), and the map takes
    /// each request's event to a request's event.
    ///
    /// This is equivariance of the whole cycle (`successors(f(p)) = f(successors(p))` for
    /// every state `p` reached), checked once per memoized phase instead of once per
    /// state: [`Compiled::successors`] does nothing but take these phases' outcomes and
    /// put them together by position (the first event, the first intention, the back of
    /// the queues), by counts that a renaming keeps (requests made, environment atoms) and
    /// by predicate order (`Semantics::reorder_front`), and `f` maps beliefs atom by atom.
    /// So when every phase commutes, every state's successors do.
    pub fn phases_equivariant(&self, id: u64, f: &impl PartMap) -> bool {
        let phases: Vec<Phase> = lock(&self.phases).clone();
        // SAFETY (throughout): every `Held` here is in this system's tables.
        let requests = self.requests.iter().enumerate().all(|(r, (event, _))| {
            let image = f.requested(1 << r);
            image.count_ones() == 1
                && std::ptr::eq(
                    self.image_event(unsafe { event.get(self) }, id, f),
                    unsafe { self.requests[image.trailing_zeros() as usize].0.get(self) },
                )
        });
        requests
            && phases.iter().all(|&phase| match phase {
                Phase::Deliberation(event, base) => {
                    let (event, base) = unsafe { (event.get(self), base.get(self)) };
                    let (chosen, goes_on) = self.deliberate(event, &base.value);
                    let image = self.deliberate(
                        self.image_event(event, id, f),
                        &self.image_base(base, id, f).value,
                    );
                    // The options as a multiset: each of the image's takes one renamed.
                    let mut renamed: Vec<_> = chosen
                        .iter()
                        .map(|c| {
                            let events: Vec<usize> = c
                                .events
                                .iter()
                                .map(|e| address(self.image_event(unsafe { e.get(self) }, id, f)))
                                .collect();
                            let intention = c.intention.map(|i| {
                                address(self.image_intention(unsafe { i.get(self) }, id, f))
                            });
                            (events, intention)
                        })
                        .collect();
                    goes_on == image.1
                        && chosen.len() == image.0.len()
                        && image.0.iter().all(|c| {
                            let events: Vec<usize> =
                                c.events.iter().map(|e| e.0.as_ptr() as usize).collect();
                            let intention = c.intention.map(|i| i.0.as_ptr() as usize);
                            renamed
                                .iter()
                                .position(|x| *x == (events.clone(), intention))
                                .map(|k| renamed.swap_remove(k))
                                .is_some()
                        })
                }
                Phase::Act(intention, base) => {
                    let (intention, base) = unsafe { (intention.get(self), base.get(self)) };
                    let image_base = self.image_base(base, id, f);
                    let acted =
                        self.compute_act(intention, &base.value, self.sem.env_count(&base.value.0));
                    let image = self.compute_act(
                        self.image_intention(intention, id, f),
                        &image_base.value,
                        self.sem.env_count(&image_base.value.0),
                    );
                    self.acted_image(&acted, id, f) == self.acted_key(&image)
                }
                Phase::ProcAct(pending) => {
                    let pending = unsafe { pending.get(self) };
                    let done = self.compute_proc_act(pending);
                    let image = self.compute_proc_act(self.image_pending(pending, id, f));
                    self.acted_image(&done, id, f) == self.acted_key(&image)
                }
            })
    }

    /// What [`Compiled::phases_equivariant`] compares of an act phase: the beliefs added
    /// and removed, the order kept, and the parts by address.
    fn acted_key(&self, a: &Acted) -> ActedKey {
        (
            // As lists: a set's words may differ in length for the same atoms.
            a.added.iter().collect(),
            a.removed.iter().collect(),
            self.by_predicate(a.front.clone()),
            a.events.iter().map(|e| e.0.as_ptr() as usize).collect(),
            a.back.map(|i| i.0.as_ptr() as usize),
            a.pending.map(|p| p.0.as_ptr() as usize),
        )
    }

    /// `front` as `Semantics::reorder_front` reads it: each added atom goes in front of
    /// its predicate's beliefs, so only the order of each predicate's atoms matters.
    fn by_predicate(&self, mut front: Vec<AtomId>) -> Vec<AtomId> {
        front.sort_by_key(|&a| self.sem.project.atoms.pred_of(a));
        front
    }

    /// [`Compiled::acted_key`] of `a`'s image under the map `id`, `f`.
    fn acted_image(&self, a: &Acted, id: u64, f: &impl PartMap) -> ActedKey {
        let (added, front) = f.base(&(a.added.clone(), a.front.clone()));
        let (removed, _) = f.base(&(a.removed.clone(), Vec::new()));
        // SAFETY: an outcome's parts are in this system's tables.
        unsafe {
            (
                added.iter().collect(),
                removed.iter().collect(),
                self.by_predicate(front),
                a.events
                    .iter()
                    .map(|e| address(self.image_event(e.get(self), id, f)))
                    .collect(),
                a.back
                    .map(|i| address(self.image_intention(i.get(self), id, f))),
                a.pending
                    .map(|p| address(self.image_pending(p.get(self), id, f))),
            )
        }
    }

    /// The image of `part` under the map `id` in `table`, made by `make` the first time.
    fn image<'c, T>(
        &'c self,
        table: &Images<T>,
        part: &Part<T>,
        id: u64,
        make: impl FnOnce() -> Held<Part<T>>,
    ) -> &'c Part<T> {
        // SAFETY: images are interned parts of this system's tables.
        unsafe {
            table
                .get((address(part), part.hash), id, |v| *v, make)
                .get(self)
        }
    }

    /// The image of a belief base under the map `id`, `f` (as [`Compiled::map`] makes it).
    fn image_base<'c>(&'c self, b: &Part<Base>, id: u64, f: &impl PartMap) -> &'c Part<Base> {
        self.image(&self.mapped_bases, b, id, || {
            self.belief_set(f.base(&b.value))
        })
    }

    /// The image of an event (see [`Compiled::image_base`]).
    fn image_event<'c>(&'c self, e: &Part<Event>, id: u64, f: &impl PartMap) -> &'c Part<Event> {
        self.image(&self.mapped_events, e, id, || self.event(f.event(&e.value)))
    }

    /// The image of an intention (see [`Compiled::image_base`]).
    fn image_intention<'c>(
        &'c self,
        i: &Part<Intention>,
        id: u64,
        f: &impl PartMap,
    ) -> &'c Part<Intention> {
        self.image(&self.mapped_intentions, i, id, || {
            self.intention(f.intention(&i.value))
        })
    }

    /// The image of an intention that waits for its action's feedback (see
    /// [`Compiled::image_base`]).
    fn image_pending<'c>(
        &'c self,
        p: &Part<Pending>,
        id: u64,
        f: &impl PartMap,
    ) -> &'c Part<Pending> {
        self.image(&self.mapped_pendings, p, id, || {
            self.pending(f.pending(&p.value))
        })
    }

    /// How much the tables hold.
    pub fn sizes(&self) -> Sizes {
        Sizes {
            beliefs: self.beliefs.len(),
            events: self.events.len(),
            intentions: self.intentions.len(),
            deliberations: self.deliberations.len(),
            acts: self.acts.len(),
        }
    }

    /// Every successor of `p`, in [`Semantics::successors`]'s order, with its notes.
    pub fn successors<'c>(&'c self, p: &Packed<'c>) -> Vec<(Notes<'c>, Packed<'c>)> {
        let mut out = Vec::new();
        self.successors_into(p, &mut out);
        out
    }

    /// [`Compiled::successors`] appended to `out`.
    pub fn successors_into<'c>(&'c self, p: &Packed<'c>, out: &mut Vec<(Notes<'c>, Packed<'c>)>) {
        if self.sem.may_request(p.requested, p.is_idle()) {
            for (r, (event, note)) in self.requests.iter().enumerate() {
                if p.requested >> r & 1 == 1 {
                    continue;
                }
                let mut next = self.open(p);
                next.requested |= 1 << r;
                // SAFETY: the request events are in this system's tables.
                next.events.push(unsafe { event.get(self) });
                out.push((Notes(smallvec::smallvec![&note[..]]), self.close(next)));
            }
        }
        if p.is_idle() {
            return;
        }
        let agenda = &p.agenda.value;
        let Some(event) = agenda.events().first() else {
            let mut next = self.open(p);
            let mut notes = Notes::default();
            self.proc_act(&mut next, &mut notes);
            self.act(&mut next, &mut notes);
            out.push((notes, self.close(next)));
            return;
        };
        // The events the deliberation takes: the first, and the next one after each that
        // is discarded (`Semantics::deliberate`).
        let mut taken = 1;
        let mut before = Notes::default();
        let mut event = event;
        let chosen = loop {
            // SAFETY: memoized outcomes and the parts they hold are in this system's tables.
            let (chosen, goes_on) = unsafe {
                self.memo_read(Memoized::Deliberation, event, p.beliefs, || {
                    let key = Key::new(event, &p.beliefs.value, 0);
                    self.deliberations.get(key, || {
                        self.computed(Phase::Deliberation(Held::new(event), Held::new(p.beliefs)));
                        self.deliberate(event, &p.beliefs.value)
                    })
                })
                .get(self)
            };
            match agenda.events().get(taken) {
                Some(next) if *goes_on => {
                    before.0.push(&chosen[0].notes[..]);
                    event = next;
                    taken += 1;
                }
                _ => break chosen,
            }
        };
        for c in chosen {
            let mut next = self.open(p);
            // The events deliberated on are taken.
            next.events.drain(..taken);
            // SAFETY: as above.
            unsafe {
                next.events.extend_from_slice(refs(&c.events));
                if let Some(i) = c.intention {
                    next.intentions.push(i.get(self));
                }
            }
            let mut notes = before.clone();
            notes.0.push(&c.notes[..]);
            self.proc_act(&mut next, &mut notes);
            self.act(&mut next, &mut notes);
            out.push((notes, self.close(next)));
        }
    }

    /// The `ProcAct` stage on `p`, memoized on the pending intention.
    fn proc_act<'c>(&'c self, p: &mut Open<'c>, notes: &mut Notes<'c>) {
        let Some(pending) = p.pending.take() else {
            return;
        };
        // SAFETY: memoized outcomes and the parts they hold are in this system's tables.
        unsafe {
            let done = self
                .memo_read(Memoized::ProcAct, pending, p.beliefs, || {
                    let key = Key::new(pending, &p.beliefs.value, 0);
                    self.proc_acts.get(key, || {
                        self.computed(Phase::ProcAct(Held::new(pending)));
                        self.compute_proc_act(pending)
                    })
                })
                .get(self);
            p.events.extend_from_slice(refs(&done.events));
            if let Some(i) = done.back {
                p.intentions.push(i.get(self));
            }
            notes.0.push(&done.notes[..]);
        }
    }

    /// The act phase on `p`, memoized.
    fn act<'c>(&'c self, p: &mut Open<'c>, notes: &mut Notes<'c>) {
        if p.intentions.is_empty() {
            return;
        }
        let first = p.intentions.remove(0);
        let held: &'c Part<Base> = p.beliefs;
        let base = &held.value;
        // SAFETY: memoized outcomes and the parts they hold are in this system's tables.
        unsafe {
            let acted = self
                .memo_read(Memoized::Act, first, held, || {
                    // How many environment atoms hold decides the order of perceived effects.
                    let env = self.sem.env_count(&base.0);
                    let key = Key::new(first, base, self.sem.env_class(env));
                    self.acts.get(key, || {
                        self.computed(Phase::Act(Held::new(first), Held::new(held)));
                        self.compute_act(first, base, env)
                    })
                })
                .get(self);
            if !acted.added.is_empty() || !acted.removed.is_empty() {
                p.beliefs = self.acted_on(held, acted).get(self);
            }
            p.events.extend_from_slice(refs(&acted.events));
            if let Some(i) = acted.back {
                p.intentions.push(i.get(self));
            }
            if let Some(pending) = acted.pending {
                p.pending = Some(pending.get(self));
            }
            notes.0.push(&acted.notes[..]);
        }
    }

    /// What `get` reads of the memo `memo` for `part` in a state with belief base `base`:
    /// found in this thread's [`LOCAL_MEMOS`] when it read it lately. Every memo's key is
    /// made of the part and of what the belief base decides.
    fn memo_read<T, V>(
        &self,
        memo: Memoized,
        part: &Part<T>,
        base: &Part<Base>,
        get: impl FnOnce() -> Held<V>,
    ) -> Held<V> {
        let key = (address(part), address(base), memo as usize);
        let at = recently(
            &LOCAL_MEMOS,
            LOCAL_PARTS,
            (self.serial, key),
            || get().0.as_ptr() as usize,
            |&at| at,
        );
        // SAFETY: the address is of this memo's outcome for this key (the memo is told by
        // `memo`, the system by its serial), in this system's tables, which are never
        // dropped while it lives.
        Held(unsafe { NonNull::new_unchecked(at as *mut V) })
    }

    /// The belief base `acted` (an act phase's outcome that changes beliefs) makes of
    /// `held`: found in this thread's [`LOCAL_BASES`] when it made it lately.
    fn acted_on(&self, held: &Part<Base>, acted: &Acted) -> Held<Part<Base>> {
        let key = (address(held), acted as *const Acted as usize);
        let at = recently(
            &LOCAL_BASES,
            LOCAL_PARTS,
            (self.serial, key),
            || {
                let base = &held.value;
                let next = base.0.with_changes(&acted.added, &acted.removed);
                let mut order = base.1.clone();
                (self.sem).reorder_front(&mut order, &acted.front, &acted.removed, &acted.added);
                self.belief_set((next, order)).0.as_ptr() as usize
            },
            |&at| at,
        );
        // SAFETY: the address is of a belief base in this system's tables (the entries are
        // of this system: its serial), which are never dropped while it lives.
        Held(unsafe { NonNull::new_unchecked(at as *mut Part<Base>) })
    }

    /// The `ProcAct` stage of `pending` (it reads no belief).
    fn compute_proc_act(&self, pending: &Part<Pending>) -> Acted {
        let none = (AtomSet::default(), Vec::new());
        let mut s = Self::alone(&none, &AtomSet::default(), None);
        s.pending = Some(pending.value.clone());
        let mut notes = Vec::new();
        self.sem.proc_act(&mut s, &mut notes);
        debug_assert!(s.pending.is_none() && s.intentions.len() <= 1);
        Acted {
            added: AtomSet::default(),
            removed: AtomSet::default(),
            front: Vec::new(),
            events: s.events.into_iter().map(|e| self.event(e)).collect(),
            back: s.intentions.pop().map(|i| self.intention(i)),
            pending: None,
            notes: notes.into(),
        }
    }

    /// Notes that a memo computed `phase`.
    fn computed(&self, phase: Phase) {
        lock(&self.phases).push(phase);
    }

    /// A state with only the beliefs `reads` selects and the given intention: what a phase
    /// that reads no more sees of a whole state.
    fn alone(base: &Base, reads: &AtomSet, intention: Option<&Intention>) -> State {
        State {
            beliefs: base.0.intersection(reads),
            order: base
                .1
                .iter()
                .copied()
                .filter(|a| reads.contains(*a))
                .collect(),
            events: Vec::new(),
            intentions: intention.into_iter().cloned().collect(),
            pending: None,
            waiting: Vec::new(),
            requested: 0,
            library: None,
            told: Vec::new(),
            asked: 0,
            atomic: false,
        }
    }

    fn deliberate(&self, event: &Part<Event>, beliefs: &Base) -> (Vec<Chosen>, bool) {
        let read = Self::alone(beliefs, &event.reads, None);
        let before = read.beliefs.clone();
        let (options, goes_on) = self.sem.deliberate_event(read, event.value.clone());
        let chosen = options
            .into_iter()
            .map(|(mut s, notes)| {
                debug_assert!(s.beliefs == before, "deliberation changes no belief");
                debug_assert!(s.intentions.len() <= 1, "one intention at most");
                Chosen {
                    events: s.events.into_iter().map(|e| self.event(e)).collect(),
                    intention: s.intentions.pop().map(|i| self.intention(i)),
                    notes: notes.into(),
                }
            })
            .collect();
        (chosen, goes_on)
    }

    fn compute_act(&self, intention: &Part<Intention>, base: &Base, env: usize) -> Acted {
        let mut s = Self::alone(base, &intention.reads, Some(&intention.value));
        let before = s.beliefs.clone();
        let mut notes = Vec::new();
        // Agents with steps of several outcomes (`.random`) are not compiled.
        self.sem.act_with(&mut s, &mut notes, env, 0);
        debug_assert!(s.intentions.len() <= 1, "one intention at most");
        let added = s.beliefs.difference(&before);
        Acted {
            front: s
                .order
                .iter()
                .copied()
                .filter(|a| added.contains(*a))
                .collect(),
            added,
            removed: before.difference(&s.beliefs),
            events: s.events.into_iter().map(|e| self.event(e)).collect(),
            back: s.intentions.pop().map(|i| self.intention(i)),
            pending: s.pending.map(|p| self.pending(p)),
            notes: notes.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_interner_keeps_each_distinct_value_once() {
        let parts: Interner<u64> = Interner::new();
        let mut asked = 0;
        let mut held = Vec::new();
        for v in [7u64, 8, 7, 9, 8, 7] {
            held.push(parts.intern(v, |_| {
                asked += 1;
                AtomSet::default()
            }));
        }
        // Three distinct values, each read once, and equal values share their part.
        assert_eq!(parts.len(), 3);
        assert_eq!(asked, 3);
        let at = |i: usize| held[i].0.as_ptr() as usize;
        assert_eq!(at(0), at(2));
        assert_eq!(at(0), at(5));
        assert_eq!(at(1), at(4));
        assert_ne!(at(0), at(1));
        assert_ne!(at(1), at(3));
    }

    #[test]
    fn a_packed_state_is_three_words() {
        // Frontiers hold millions of packed states: the agenda is one interned part.
        assert_eq!(
            std::mem::size_of::<Packed>(),
            3 * std::mem::size_of::<usize>()
        );
    }

    /// Values that all hash alike: only their equality tells them apart.
    #[derive(PartialEq, Eq)]
    struct Colliding(u8);

    impl Hash for Colliding {
        fn hash<H: Hasher>(&self, _: &mut H) {}
    }

    #[test]
    fn an_interner_tells_apart_values_whose_hashes_collide() {
        let parts: Interner<Colliding> = Interner::new();
        let a = parts.intern(Colliding(1), |_| AtomSet::default());
        let b = parts.intern(Colliding(2), |_| AtomSet::default());
        let a2 = parts.intern(Colliding(1), |_| AtomSet::default());
        assert_eq!(parts.len(), 2);
        assert_ne!(a.0.as_ptr(), b.0.as_ptr());
        assert_eq!(a.0.as_ptr(), a2.0.as_ptr());
    }

    fn pass_through(x: &impl Hash) -> u64 {
        let mut h = PassThrough::default();
        x.hash(&mut h);
        h.finish()
    }

    #[test]
    fn parts_and_keys_hash_as_the_hash_they_keep() {
        // The tables' buckets come straight from these hashes: none is recomputed.
        let part = Part {
            hash: 0xdead_beef_1234,
            reads: AtomSet::default(),
            value: 3u8,
            annex: Annex::default(),
        };
        assert_eq!(pass_through(&part), 0xdead_beef_1234);
        let key = Key::new(&part, &(AtomSet::default(), Vec::new()), 9);
        assert_eq!(pass_through(&key), key.hash);
        assert_eq!(pass_through(&7u64), 7);
    }

    #[test]
    fn a_pass_through_hasher_mixes_the_bytes_it_is_given() {
        // Keys other than one `u64` (none today) would still be told apart: every string
        // of up to two bytes below 16 hashes differently.
        let mut seen = HashSet::new();
        for len in 0..=2u32 {
            for n in 0..16u32.pow(len) {
                let bytes: Vec<u8> = (0..len).map(|i| (n >> (4 * i) & 15) as u8).collect();
                let mut h = PassThrough::default();
                h.write(&bytes);
                assert!(seen.insert((len, h.finish())), "{bytes:?}");
            }
        }
    }

    #[test]
    fn an_annex_is_its_first_clients() {
        let annex = Annex::default();
        assert_eq!(annex.read(7), Annexed::Empty);
        annex.set(7, Box::new([1, 2]));
        annex.set(8, Box::new([3]));
        assert_eq!(annex.read(7), Annexed::Mine(&[1, 2]));
        assert_eq!(annex.read(8), Annexed::Other);
    }

    #[test]
    fn a_memo_computes_each_key_once() {
        let part = Part {
            hash: 5,
            reads: AtomSet::default(),
            value: (),
            annex: Annex::default(),
        };
        let other = Part {
            hash: 5,
            reads: AtomSet::default(),
            value: (),
            annex: Annex::default(),
        };
        let base = (AtomSet::default(), Vec::new());
        let memo: Memo<u32> = Memo::new();
        let mut computed = 0;
        let mut get = |p: &Part<()>, extra: u64, v: u32| {
            let held = memo.get(Key::new(p, &base, extra), || {
                computed += 1;
                v
            });
            held.0.as_ptr() as usize
        };
        let first = get(&part, 0, 1);
        // The same part and reads: the kept outcome, not the new one.
        assert_eq!(get(&part, 0, 2), first);
        // Another part (parts are told apart by address) or another extra: a new entry.
        assert_ne!(get(&other, 0, 3), first);
        assert_ne!(get(&part, 1, 4), first);
        assert_eq!(computed, 3);
        assert_eq!(memo.len(), 3);
    }

    #[test]
    fn shards_spread_the_hashes_by_their_middle_bits() {
        assert_eq!(shard_of(0), 0);
        assert_eq!(shard_of(5 << 40), 5);
        assert_eq!(shard_of(70 << 40), 70 % SHARDS);
        assert_eq!(shard_of(u64::MAX), (u64::MAX >> 40) as usize % SHARDS);
        assert!((0..1000u64).all(|h| shard_of(h.wrapping_mul(0x9E37_79B9_7F4A_7C15)) < SHARDS));
    }
}
