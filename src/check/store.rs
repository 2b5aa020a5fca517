//! The visited-state store: a fingerprint and a parent link per state, nothing else.
//!
//! States are numbered in the order they are found (breadth first, so by depth). The store
//! keeps, per state, its 64-bit fingerprint (8 bytes) and its parent's number (about two
//! bits in a breadth-first search, whose parents never decrease: `Parents`), plus one
//! 5-byte slot of an open-addressing hash table that maps fingerprints to numbers
//! (kept between 3/8 and 3/4 full, so 6.7 to 13.3 bytes per state; up to 7/8 when sized
//! in advance, [`Store::with_room`]). A slot holds the
//! state's number and the top byte of its fingerprint, so that probing past other states
//! seldom reads their fingerprints (a cache miss each). The fingerprints and the parents'
//! bits grow by chunks that never move (`Chunked`: copying them into fresh memory cost
//! more than the search did with it), with less than one chunk (2^18 states) of slack: 15
//! to 25 bytes per state from a million states on. No state is kept: a state, or the run to it, is rebuilt by
//! replaying transitions from an initial state and following the fingerprints (as stateright does). Growth uses
//! `try_reserve`, so running out of memory ends the search as `incomplete` instead of
//! aborting the process.
//!
//! A search that will not rebuild a run (a user's explanation search that finds nothing
//! to report) needs neither fingerprints by number nor parents: [`Store::fingerprints_only`]
//! keeps one 8-byte slot per state in the table (the fingerprint itself) and counts the
//! states: 9.1 to 18.3 bytes a state (7/16 to 7/8 full) instead of 15 to 25.
//!
//! A user's search on the agent's stored graph meets states that are pairs (the user's
//! view, the agent's state), fingerprinted exactly ([`pair_fingerprint`]). Its store
//! ([`Store::fingerprints_by_place`]) keeps the first four pairs met at each agent state in
//! an array by agent state (their views' numbers, 2 bytes each), and the others in the
//! table: the agent's states are numbered breadth first, and a user's search meets them
//! nearly in that order, so most lookups read memory next to the last one's instead of a
//! random slot of a gigabyte-sized table.

/// Marks an empty hash-table slot.
const NONE: u32 = u32::MAX;

/// What [`Store::lookup`] gives for a stored state in a store of fingerprints only.
pub const UNNUMBERED: u32 = NONE;

/// A hash-table slot: a state's number (little-endian) and its fingerprint's top byte.
type Slot = [u8; 5];

const EMPTY: Slot = [0xff, 0xff, 0xff, 0xff, 0];

fn slot_of(i: u32, fp: u64) -> Slot {
    let [a, b, c, d] = i.to_le_bytes();
    [a, b, c, d, tag(fp)]
}

fn tag(fp: u64) -> u8 {
    (fp >> 56) as u8
}

// One load of four bytes: built from the bytes one by one, as it was, the compiler made
// four loads and three shifts of every slot probed.
#[inline(always)]
fn number(s: &Slot) -> u32 {
    let (four, _) = s.split_first_chunk::<4>().expect("a slot has five bytes");
    u32::from_le_bytes(*four)
}

use super::chunked::Chunked;
use super::parents::Parents;
use super::slots::Slots;
use crate::semantics::compiled::mix;

/// Asks the kernel to back the 2 MiB-aligned parts of `v`'s buffer with huge pages, as
/// `madvise(MADV_HUGEPAGE)` does (a hint; nothing where it is refused, or elsewhere than
/// Linux). A table is read at random: with 4 KiB pages, nearly every lookup in a table of
/// a gigabyte missed the processor's TLB as well as its cache (the users' searches at 6
/// cups: 36-37 s each instead of 42 s). Called before the buffer is first written, so that
/// its pages are made huge from the start.
fn huge_pages<T>(v: &Vec<T>) {
    #[cfg(target_os = "linux")]
    {
        const HUGE: usize = 2 << 20;
        let start = v.as_ptr() as usize;
        let end = start + v.capacity() * std::mem::size_of::<T>();
        let (from, to) = (start.next_multiple_of(HUGE), end / HUGE * HUGE);
        if from < to {
            // SAFETY: advice about pages of our own allocation: it changes neither what
            // they hold nor whether they are mapped.
            unsafe { libc::madvise(from as *mut libc::c_void, to - from, libc::MADV_HUGEPAGE) };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = v;
}

/// Puts state `i` with fingerprint `fp` in the first free slot from its own.
fn place(slots: &mut [Slot], i: u32, fp: u64) {
    let mask = slots.len() - 1;
    let mut at = fp as usize & mask;
    while number(&slots[at]) != NONE {
        at = (at + 1) & mask;
    }
    slots[at] = slot_of(i, fp);
}

/// Where a state not found by [`Store::lookup`] goes: the empty slot the probe ended at
/// (none in an empty table), or the empty slot of its place ([`Store::fingerprints_by_place`]),
/// and how many states were stored then.
#[derive(Clone, Copy, Debug)]
pub struct Vacant {
    slot: Option<usize>,
    len: usize,
    /// When `slot` is of a place, what goes there: the pair's tag plus one.
    place: Option<u16>,
}

/// The pairs kept by place, per place ([`Store::fingerprints_by_place`]): at 6 cups, a
/// user meets 1.6 views per agent state, and with two a place 12% of its states went to
/// the table, each a lookup at random in a table of huge pages (the first write to one
/// costs several times a small page's in this project's virtual machines). Four tags of
/// 2 bytes take the 8 bytes two of 4 did.
const PER_PLACE: usize = 4;

/// The fingerprint of the pair `(tag, place)`: a bijection (SplitMix64's finalizer,
/// `semantics::compiled::mix`, of `tag << 32 | place`), so two pairs never share one,
/// and every bit of each spreads over it, as a hash table's probes want.
pub fn pair_fingerprint(tag: u32, place: u32) -> u64 {
    mix(u64::from(tag) << 32 | u64::from(place))
}

/// The pair whose fingerprint is `fp` ([`pair_fingerprint`]'s inverse: `mix` undone).
fn pair_of(fp: u64) -> (u32, u32) {
    // `x ^ x >> k` is undone by xoring the shifts by k, 2k, ...; a multiplication by an
    // odd number, by its inverse modulo 2^64.
    const fn inverse(a: u64) -> u64 {
        // Newton's iteration doubles the bits right at each step (a is its own inverse
        // modulo 8).
        let mut x = a;
        let mut i = 0;
        while i < 5 {
            x = x.wrapping_mul(2u64.wrapping_sub(a.wrapping_mul(x)));
            i += 1;
        }
        x
    }
    let mut z = fp;
    z ^= z >> 31 ^ z >> 62;
    z = z.wrapping_mul(const { inverse(0x94d0_49bb_1331_11eb) });
    z ^= z >> 27 ^ z >> 54;
    z = z.wrapping_mul(const { inverse(0xbf58_476d_1ce4_e5b9) });
    z ^= z >> 30 ^ z >> 60;
    ((z >> 32) as u32, z as u32)
}

/// The store could not grow: memory is exhausted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutOfMemory;

/// The smallest table capacity (states) whose next growth is faulted in ahead
/// ([`Slots::prepare`]): below it, the growth is over before a helper could help.
const PREPARED: usize = 1 << 20;

/// Fingerprints and parent links of the visited states.
pub struct Store {
    fps: Chunked<u64>,
    parent: Parents,
    slots: Slots<Slot>,
    /// How full the table may be, in eighths of its slots, before it doubles.
    full: usize,
    /// The fingerprints alone, when the store keeps no numbers ([`Store::fingerprints_only`]):
    /// `fps`, `parent` and `slots` then stay empty.
    only: Option<Fingerprints>,
    /// Once the search is over, when the fingerprints can be had otherwise
    /// ([`Store::derive_fingerprints`]): how many states there are, and what gives state
    /// `i`'s fingerprint; `fps` is then empty.
    derived: Option<(usize, Derived)>,
}

/// What gives a stored state's fingerprint by its number, owning what it reads
/// ([`Store::derive_fingerprints`]).
pub type Derived = Box<dyn Fn(u32) -> u64 + Send + Sync>;

/// A set of fingerprints: an open-addressing table of the fingerprints themselves (0 marks
/// an empty slot, so fingerprint 0 is kept apart), and how many there are; when they are
/// of pairs ([`Store::fingerprints_by_place`]), the first met of each place apart.
#[derive(Default)]
struct Fingerprints {
    table: Vec<u64>,
    /// Fingerprints in `table`.
    held: usize,
    len: usize,
    zero: bool,
    /// Per place, [`PER_PLACE`] slots: the tags of the first pairs met there, plus one
    /// (0: none yet). A tag of 2^16 - 1 or more (a user's view numbered so: 39 K views
    /// at 6 cups) goes to the table.
    first: Slots<u16>,
}

impl Fingerprints {
    /// Where `fp` (not 0) is, or the empty slot where its probe ends.
    fn probe(&self, fp: u64) -> Result<usize, usize> {
        let mask = self.table.len() - 1;
        let mut at = fp as usize & mask;
        loop {
            match self.table[at] {
                0 => return Err(at),
                x if x == fp => return Ok(at),
                _ => at = (at + 1) & mask,
            }
        }
    }

    /// Where `fp` is among its place's slots (`Ok`), or the first empty one and what goes
    /// there, its tag plus one (`Err`); `None` when it has no place, or the place's slots
    /// hold others (it is then in the table, if anywhere: a place's slots are filled in
    /// order, and never emptied).
    #[inline]
    fn at_place(&self, fp: u64) -> Option<Result<usize, (usize, u16)>> {
        if self.first.is_empty() {
            return None;
        }
        let (tag, place) = pair_of(fp);
        let tag = u16::try_from(tag).ok()?.checked_add(1)?;
        let from = (place as usize).checked_mul(PER_PLACE)?;
        let slots = self.first.get(from..from + PER_PLACE)?;
        slots.iter().enumerate().find_map(|(k, &t)| match t {
            0 => Some(Err((from + k, tag))),
            t if t == tag => Some(Ok(from + k)),
            _ => None,
        })
    }

    /// Asks for the table slot where a probe for `fp` starts.
    fn prefetch_table(&self, fp: u64) {
        if !self.table.is_empty() {
            super::chunked::prefetch(&self.table[fp as usize & (self.table.len() - 1)]);
        }
    }

    fn contains(&self, fp: u64) -> bool {
        if let Some(r) = self.at_place(fp) {
            return r.is_ok();
        }
        match fp {
            0 => self.zero,
            _ => !self.table.is_empty() && self.probe(fp).is_ok(),
        }
    }

    fn grow(&mut self) -> Result<(), OutOfMemory> {
        let table = table((self.table.len() * 2).max(1024), 0, true)?;
        let old = std::mem::replace(&mut self.table, table);
        for fp in old.into_iter().filter(|&x| x != 0) {
            let Err(at) = self.probe(fp) else {
                unreachable!("a fingerprint is kept once")
            };
            self.table[at] = fp;
        }
        Ok(())
    }
}

/// A hash table of `cap` slots, each `empty`, its pages advised huge before it is
/// written if `huge` ([`huge_pages`]); [`OutOfMemory`] when it cannot be had.
pub(super) fn table<T: Clone>(cap: usize, empty: T, huge: bool) -> Result<Vec<T>, OutOfMemory> {
    let mut t = Vec::new();
    t.try_reserve_exact(cap).map_err(|_| OutOfMemory)?;
    if huge {
        huge_pages(&t);
    }
    t.resize(cap, empty);
    Ok(t)
}

/// The slots of a table sized in advance for `states`, at most 7/8 full.
fn slots_for(states: usize) -> usize {
    (states.saturating_mul(8) / 7 + 1)
        .next_power_of_two()
        .max(1024)
}

impl Default for Store {
    fn default() -> Store {
        Store {
            fps: Chunked::default(),
            parent: Parents::default(),
            slots: Slots::default(),
            full: 6,
            only: None,
            derived: None,
        }
    }
}

impl Store {
    /// An empty store.
    pub fn new() -> Store {
        Store::default()
    }

    /// An empty store whose table holds `states` states without growing (an empty one
    /// when memory for it cannot be had: it then grows as it fills). Such a table may be
    /// up to 7/8 full instead of 3/4: its size is a guess made for a search that fills
    /// most of it (a user's search on the agent's graph), and at 6 cups 3/4 took the
    /// users' tables to 2^28 slots (1.34 GB each) for 104 and 108 M states, where 7/8
    /// fits them in half (peak 11.4 -> 10.3 GB, the users' searches as fast or faster,
    /// docs/benchmarks.md).
    pub fn with_room(states: usize) -> Store {
        let mut s = Store::default();
        if states > 0 {
            s.full = 7;
            s.slots = Slots::new(slots_for(states), EMPTY);
        }
        s
    }

    /// A store that keeps the fingerprints alone, with room for `states` as
    /// [`Store::with_room`] makes it: states are still numbered in the order they are
    /// stored, but a number is neither kept nor found again ([`Store::lookup`] gives
    /// [`UNNUMBERED`] for a stored state), and no fingerprint or parent is kept by number
    /// ([`Store::numbered`]).
    pub fn fingerprints_only(states: usize) -> Store {
        let mut only = Fingerprints::default();
        if states > 0 {
            only.table = table(slots_for(states), 0, true).unwrap_or_default();
        }
        Store {
            full: 7,
            only: Some(only),
            ..Store::default()
        }
    }

    /// A store of fingerprints only ([`Store::fingerprints_only`]) of pairs `(tag, place)`
    /// ([`pair_fingerprint`]), places below `places`: the first four pairs met at
    /// each place (of tags below 2^16 - 1) are kept in an array by place, the others in
    /// the table, which makes room for a sixteenth of `states` beyond `places` (a user's
    /// search on the 5-cup kitchen: 1.6 views per agent state, 11-12% of its states
    /// beyond the first two of theirs, 1.3-2.5% beyond the first four; at 6 cups 1.7-2.5%).
    /// Any fingerprint may be stored: one of no such pair goes to the table. Without
    /// places, [`Store::fingerprints_only`] with room for `states`.
    pub fn fingerprints_by_place(states: usize, places: usize) -> Store {
        if places == 0 {
            return Store::fingerprints_only(states);
        }
        let mut s = Store::fingerprints_only(states.saturating_sub(places) / 16);
        if let Some(f) = &mut s.only {
            // In the memory of the table this thread dropped last, if it kept it (the
            // agent's: `slots::keep_a_freed_table`), which was written already. Else in
            // fresh memory of small pages: read nearly in order, it needs no huge pages,
            // whose first write cost several times a small page's in this project's
            // virtual machines (`slots`); huge pages spare TLB misses to lookups at random.
            // Either is kept when dropped by a thread that keeps freed tables, for the
            // `ltl` products that run next on it (`runs::Scratch::head`).
            let n = places.min(u32::MAX as usize) * PER_PLACE;
            f.first = Slots::reused_or_fresh(n, 0).unwrap_or_default();
        }
        s
    }

    /// Whether the store keeps each state's fingerprint and parent by number (all but
    /// [`Store::fingerprints_only`] do).
    pub fn numbered(&self) -> bool {
        self.only.is_none()
    }

    /// How many more states the table takes before it grows, and how many it holds: a
    /// growth re-places those, and the merge waits for it.
    pub fn room(&self) -> (usize, usize) {
        let (held, slots) = match &self.only {
            None => (self.fps.len(), self.slots.len()),
            Some(f) => (f.held, f.table.len()),
        };
        ((slots * self.full / 8).saturating_sub(held), held)
    }

    /// Whether one more state fits in the table as it is.
    fn fits_one_more(&self) -> bool {
        self.room().0 > 0
    }

    /// Number of states stored.
    pub fn len(&self) -> usize {
        match (&self.only, &self.derived) {
            (Some(f), _) => f.len,
            (None, Some((len, _))) => *len,
            (None, None) => self.fps.len(),
        }
    }

    /// Whether nothing is stored.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The fingerprint of state `i` (of a store that keeps numbers: [`Store::numbered`]).
    pub fn fingerprint(&self, i: u32) -> u64 {
        assert!(
            self.numbered(),
            "a store of fingerprints only keeps no numbers"
        );
        match &self.derived {
            Some((len, derived)) => {
                assert!((i as usize) < *len, "state {i} of {len}");
                derived(i)
            }
            None => self.fps.get(i as usize),
        }
    }

    /// Whether the fingerprints are derived ([`Store::derive_fingerprints`]).
    pub fn derived(&self) -> bool {
        self.derived.is_some()
    }

    /// Frees the fingerprints kept by number (and the hash table: no state is looked up
    /// any more), once the search is over, if `derived` gives state `i`'s fingerprint as
    /// the store kept it on a sample of about a thousand states (the first and last
    /// among them): 8 bytes a state that the searches after this one need only for the
    /// few runs they replay. Whether it did (if not, nothing changed).
    pub fn derive_fingerprints(&mut self, derived: Derived) -> bool {
        assert!(
            self.numbered(),
            "a store of fingerprints only keeps no numbers"
        );
        let len = self.len();
        let step = len / 1024 + 1;
        let sample = (0..len).step_by(step).chain(len.checked_sub(1));
        if !sample
            .into_iter()
            .all(|i| derived(i as u32) == self.fps.get(i))
        {
            return false;
        }
        self.drop_index();
        self.derived = Some((len, derived));
        std::mem::take(&mut self.fps).give_back();
        true
    }

    /// The state `i` was first reached from (`None` for an initial state), in a store
    /// that keeps numbers ([`Store::numbered`]).
    pub fn parent(&self, i: u32) -> Option<u32> {
        assert!(
            self.numbered(),
            "a store of fingerprints only keeps no parents"
        );
        self.parent.get(i as usize)
    }

    /// Whether a state with fingerprint `fp` is stored.
    pub fn contains(&self, fp: u64) -> bool {
        match &self.only {
            None => self.lookup(fp).is_ok(),
            Some(f) => f.contains(fp),
        }
    }

    /// The number of the state with fingerprint `fp`, if stored ([`UNNUMBERED`] in a
    /// store of fingerprints only).
    pub fn find(&self, fp: u64) -> Option<u32> {
        self.lookup(fp).ok()
    }

    /// The number of the state with fingerprint `fp`, or where [`Store::insert_vacant`]
    /// puts it: the merge looks a successor up, then stores it if it is new, and the
    /// probe (most often through several slots: the table is up to 3/4 or 7/8 full) is
    /// made once.
    pub fn lookup(&self, fp: u64) -> Result<u32, Vacant> {
        if let Some(f) = &self.only {
            // One probe: most lookups of a user's search are of new states.
            let len = f.len;
            let vacant = |slot, place| Err(Vacant { slot, len, place });
            match f.at_place(fp) {
                Some(Ok(_)) => return Ok(UNNUMBERED),
                Some(Err((slot, tag))) => return vacant(Some(slot), Some(tag)),
                None => {}
            }
            return match fp {
                0 if f.zero => Ok(UNNUMBERED),
                _ if fp == 0 || f.table.is_empty() => vacant(None, None),
                _ => match f.probe(fp) {
                    Ok(_) => Ok(UNNUMBERED),
                    Err(at) => vacant(Some(at), None),
                },
            };
        }
        let len = self.fps.len();
        if self.slots.is_empty() {
            return Err(Vacant {
                slot: None,
                len,
                place: None,
            });
        }
        let mask = self.slots.len() - 1;
        let mut at = fp as usize & mask;
        let t = tag(fp);
        loop {
            let s = &self.slots[at];
            let i = number(s);
            if i == NONE {
                return Err(Vacant {
                    slot: Some(at),
                    len,
                    place: None,
                });
            }
            if s[4] == t && self.fps.get(i as usize) == fp {
                return Ok(i);
            }
            at = (at + 1) & mask;
        }
    }

    /// Stores `fp` (reached from `parent`), which [`Store::lookup`] did not find when the
    /// store was as it is (else it is looked up again): its number.
    pub fn insert_vacant(
        &mut self,
        vacant: Vacant,
        fp: u64,
        parent: Option<u32>,
    ) -> Result<u32, OutOfMemory> {
        if let (Some(slot), Some(tag), Some(f)) = (vacant.slot, vacant.place, &mut self.only) {
            // Nothing was stored since: the place's slot is still empty.
            if vacant.len == f.len {
                debug_assert!(f.at_place(fp) == Some(Err((slot, tag))));
                let i = u32::try_from(f.len).map_err(|_| OutOfMemory)?;
                f.first[slot] = tag;
                f.len += 1;
                return Ok(i);
            }
            return self.insert(fp, parent).map(|(i, _)| i);
        }
        let slot = vacant
            .slot
            .filter(|_| vacant.len == self.len() && self.fits_one_more());
        if let Some(f) = &mut self.only {
            let Some(at) = slot.filter(|_| fp != 0) else {
                return self.insert(fp, parent).map(|(i, _)| i);
            };
            debug_assert!(f.table[at] == 0 && !f.contains(fp));
            let i = u32::try_from(f.len).map_err(|_| OutOfMemory)?;
            f.table[at] = fp;
            f.len += 1;
            f.held += 1;
            return Ok(i);
        }
        let Some(at) = slot else {
            return self.insert(fp, parent).map(|(i, _)| i);
        };
        debug_assert!(number(&self.slots[at]) == NONE && self.find(fp).is_none());
        let i = self.push(fp, parent)?;
        self.slots[at] = slot_of(i, fp);
        Ok(i)
    }

    /// Asks the processor to bring the slot where a lookup of `fp` starts into its cache,
    /// without waiting for it: the merge prefetches a whole job's successors before it
    /// looks them up, so that their cache misses (most lookups miss, the table being far
    /// larger than the cache) overlap instead of following one another.
    pub fn prefetch(&self, fp: u64) {
        match &self.only {
            None if !self.slots.is_empty() => {
                let at = fp as usize & (self.slots.len() - 1);
                super::chunked::prefetch(&self.slots[at]);
            }
            Some(f) => {
                // A pair of a place is most often found, or stored, there (9 in 10 at 5
                // cups): its slot in the table is asked for only when it has none.
                let placed = (!f.first.is_empty())
                    .then(|| f.first.get(pair_of(fp).1 as usize * PER_PLACE))
                    .flatten();
                if let Some(slot) = placed {
                    super::chunked::prefetch(slot);
                } else {
                    f.prefetch_table(fp);
                }
            }
            _ => {}
        }
    }

    /// What a lookup of `fp` reads after what [`Store::prefetch`] asked for, asked for
    /// some lookups later, once that has come: the table's slot of a pair whose place's
    /// slots hold others ([`Store::fingerprints_by_place`]; the users' searches at 6 cups
    /// spent a fifteenth of their time waiting for these).
    pub fn prefetch_late(&self, fp: u64) {
        if let Some(f) = &self.only {
            if !f.first.is_empty() && f.at_place(fp).is_none() {
                f.prefetch_table(fp);
            }
        }
    }

    /// Stores `fp` (reached from `parent`) unless it is there: its number, and whether it
    /// is new.
    pub fn insert(&mut self, fp: u64, parent: Option<u32>) -> Result<(u32, bool), OutOfMemory> {
        if let Some(i) = self.find(fp) {
            return Ok((i, false));
        }
        if self.only.is_some() {
            return self.insert_fingerprint(fp).map(|i| (i, true));
        }
        if self.fps.len() >= NONE as usize - 1 {
            return Err(OutOfMemory);
        }
        if !self.fits_one_more() {
            self.grow()?;
        }
        let i = self.push(fp, parent)?;
        place(&mut self.slots, i, fp);
        Ok((i, true))
    }

    /// Adds `fp`, not stored yet, to a store of fingerprints only: its number.
    fn insert_fingerprint(&mut self, fp: u64) -> Result<u32, OutOfMemory> {
        let grow = !self.fits_one_more();
        let f = self.only.as_mut().expect("a store of fingerprints only");
        let i = u32::try_from(f.len)
            .ok()
            .filter(|&i| i < NONE - 1)
            .ok_or(OutOfMemory)?;
        if let Some(Err((slot, tag))) = f.at_place(fp) {
            f.first[slot] = tag;
        } else if fp == 0 {
            f.zero = true;
        } else {
            if grow || f.table.is_empty() {
                f.grow()?;
            }
            let Err(at) = f.probe(fp) else {
                unreachable!("looked up before")
            };
            f.table[at] = fp;
            f.held += 1;
        }
        f.len += 1;
        Ok(i)
    }

    /// Appends a state's fingerprint and parent (not yet in the table): its number.
    fn push(&mut self, fp: u64, parent: Option<u32>) -> Result<u32, OutOfMemory> {
        debug_assert!(
            self.derived.is_none(),
            "no state is added once the search is over"
        );
        if self.fps.len() >= NONE as usize - 1 {
            return Err(OutOfMemory);
        }
        let i = self.fps.len() as u32;
        self.fps.push(fp)?;
        if let Err(e) = self.parent.push(parent) {
            self.fps.pop();
            return Err(e);
        }
        // Seven eighths of the way to the table's next growth, the memory it will grow
        // into is faulted in by a helper thread (`Slots::prepare`): the merging thread
        // stores about 2.5 M states a second at 6 cups, and has 6 M to go before the
        // last growth there, the helper 0.34 GB to fault in.
        let cap = self.slots.len() * self.full / 8;
        if cap >= PREPARED && i as usize == cap - cap / 8 {
            self.slots.prepare(self.slots.len() * 2);
        }
        Ok(i)
    }

    fn grow(&mut self) -> Result<(), OutOfMemory> {
        let cap = (self.slots.len() * 2).max(1024);
        // Rebuilt from the fingerprints: the old slots are not read, and their memory is
        // the new table's first half (`Slots`).
        self.slots.reset(cap, EMPTY)?;
        let slots = &mut self.slots[..];
        // The slots are written at random: each is asked for some states ahead, so that
        // their cache misses overlap instead of following one another (the merging thread
        // waits for the growth, and the other threads soon for it).
        const AHEAD: usize = 16;
        let mut ahead = self.fps.iter().skip(AHEAD);
        for (i, fp) in self.fps.iter().enumerate() {
            if let Some(next) = ahead.next() {
                super::chunked::prefetch(&slots[next as usize & (cap - 1)]);
            }
            place(slots, i as u32, fp);
        }
        Ok(())
    }

    /// Frees the hash table once no state will be looked up (the search is over): the
    /// fingerprints and parents stay (the count alone, in a store of fingerprints only),
    /// and a lookup after this finds nothing.
    pub fn drop_index(&mut self) {
        self.slots = Slots::default();
        if let Some(f) = &mut self.only {
            (f.table, f.zero, f.first) = (Vec::new(), false, Slots::default());
        }
    }

    /// Bytes held (capacity, not just length).
    pub fn bytes(&self) -> usize {
        let only = (self.only.as_ref()).map_or(0, |f| f.table.capacity() * 8 + f.first.bytes());
        self.fps.bytes() + self.parent.bytes() + self.slots.bytes() + only
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inserts_find_and_link_parents() {
        let mut s = Store::new();
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        assert_eq!(s.insert(fp(0), None), Ok((0, true)));
        for k in 1..10_000u64 {
            assert_eq!(s.insert(fp(k), Some(k as u32 - 1)), Ok((k as u32, true)));
        }
        assert_eq!(s.insert(fp(5), Some(0)), Ok((5, false)));
        assert_eq!(s.len(), 10_000);
        assert_eq!(s.find(fp(1234)), Some(1234));
        assert_eq!(s.find(fp(10_001)), None);
        assert_eq!(s.parent(0), None);
        assert_eq!(s.parent(77), Some(76));
        assert_eq!(s.fingerprint(9), fp(9));
        // At most (8 + 4) * 5/4 + 5 / (3/8) bytes per state, plus the first allocations.
        assert!(s.bytes() <= 10_000 * 29 + 1024 * 17, "{} bytes", s.bytes());
        // Without its table, the store keeps every fingerprint and parent, in fewer bytes.
        let before = s.bytes();
        s.drop_index();
        assert!(
            s.bytes() + 10_000 * 5 <= before,
            "{} of {before} bytes",
            s.bytes()
        );
        assert_eq!(
            (s.len(), s.fingerprint(9), s.parent(77)),
            (10_000, fp(9), Some(76))
        );
    }

    #[test]
    fn room_counts_down_to_a_growth() {
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        for mut s in [Store::new(), Store::fingerprints_only(0)] {
            assert_eq!(s.room(), (0, 0), "no table yet");
            s.insert(fp(0), None).expect("memory");
            let (room, held) = s.room();
            assert_eq!(held, 1);
            for k in 1..=room as u64 {
                assert_eq!(s.room(), (room + 1 - k as usize, k as usize));
                s.insert(fp(k), None).expect("memory");
            }
            assert_eq!(s.room(), (0, room + 1), "full");
            // The next state grows the table.
            s.insert(fp(1 << 40), None).expect("memory");
            let (after, held) = s.room();
            assert_eq!(held, room + 2);
            assert_eq!(after + held, 2 * (room + 1), "twice the states fit");
        }
    }

    /// Seven eighths of the way to a growth of a large table, the memory it grows into is
    /// made ready (`Slots::prepare`, on Linux), and the growth keeps every state.
    #[test]
    fn a_large_table_prepares_its_growth() {
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut s = Store::with_room(PREPARED * 8 / 7 + 1);
        let (room, _) = s.room();
        let (cap, slots) = (room, s.slots.bytes());
        assert!(cap >= PREPARED);
        for k in 0..(cap - cap / 8) as u64 {
            s.insert(fp(k), None).expect("memory");
        }
        assert_eq!(s.slots.bytes(), slots, "not yet");
        s.insert(fp(1 << 40), None).expect("memory");
        #[cfg(target_os = "linux")]
        assert_eq!(s.slots.bytes(), 2 * slots, "the next size made ready");
        for k in (cap - cap / 8) as u64..=cap as u64 {
            s.insert(fp(k), None).expect("memory");
        }
        assert!(s.room().0 > cap / 2, "grown");
        assert_eq!(s.slots.bytes(), 2 * slots);
        assert_eq!(s.find(fp(17)), Some(17));
        assert_eq!(s.find(fp(1 << 40)), Some((cap - cap / 8) as u32));
        assert_eq!(s.len(), cap + 2);
    }

    #[test]
    fn a_vacant_slot_stores_what_insert_would() {
        // States looked up then stored where the probe ended, across the table's growths,
        // and a stale vacancy (the store changed since): the same numbers, parents and
        // lookups as inserting them.
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0xa5a5;
        let (mut a, mut b) = (Store::new(), Store::new());
        let mut stale = 0;
        for k in 0..20_000u64 {
            let parent = k.checked_sub(1).map(|p| p as u32);
            let key = fp(k % 15_000);
            match b.lookup(key) {
                Ok(i) => assert_eq!(a.insert(key, parent), Ok((i, false)), "state {k}"),
                Err(v) => {
                    if k % 7 == 3 {
                        // Another state is stored in between: the vacancy is stale.
                        let other = fp(1 << 40 | k);
                        a.insert(other, None).expect("memory");
                        b.insert(other, None).expect("memory");
                        stale += 1;
                    }
                    let i = b.insert_vacant(v, key, parent).expect("memory");
                    assert_eq!(a.insert(key, parent), Ok((i, true)), "state {k}");
                }
            }
        }
        assert!(stale > 1000, "{stale}");
        assert_eq!(a.len(), b.len());
        for i in 0..a.len() as u32 {
            assert_eq!(a.fingerprint(i), b.fingerprint(i));
            assert_eq!(a.parent(i), b.parent(i));
            assert_eq!(b.find(a.fingerprint(i)), Some(i));
        }
    }

    /// Looks each `(k, key)` of `keys` up in both stores and, when new, stores it where the
    /// lookup ended, after storing `other(k)` first for every fifth (the vacancy is then
    /// stale): both must answer alike, `b` (of fingerprints only) `UNNUMBERED` for a
    /// stored state, and give the same numbers and counts.
    fn look_up_alike(
        (a, b): (&mut Store, &mut Store),
        keys: impl Iterator<Item = (u64, u64)>,
        other: impl Fn(u64) -> u64,
    ) {
        for (k, key) in keys {
            match (a.lookup(key), b.lookup(key)) {
                (Ok(_), Ok(i)) => assert_eq!(i, UNNUMBERED, "state {k}"),
                (Err(va), Err(vb)) => {
                    if k % 5 == 2 {
                        let other = other(k);
                        assert_eq!(a.insert(other, None), b.insert(other, None), "{k}");
                    }
                    assert_eq!(
                        a.insert_vacant(va, key, None),
                        b.insert_vacant(vb, key, None),
                        "state {k}"
                    );
                }
                (x, y) => panic!("state {k}: {x:?} against {y:?}"),
            }
            assert_eq!(a.len(), b.len());
        }
    }

    #[test]
    fn fingerprints_alone_number_and_find_as_a_numbered_store() {
        // The same sequence of lookups, vacant inserts (some stale) and inserts, fingerprint
        // 0 among them: the same answers, numbers and count, from a store sized in advance
        // and from one that grows; a stored state looks up as `UNNUMBERED`.
        let fp = |k: u64| match k {
            7 => 0,
            _ => k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0x0f0f,
        };
        for room in [0, 5_000, 30_000] {
            let (mut a, mut b) = (Store::new(), Store::fingerprints_only(room));
            assert!(a.numbered() && !b.numbered());
            let keys = (0..40_000u64).map(|k| (k, fp(k % 25_000)));
            look_up_alike((&mut a, &mut b), keys, |k| fp(1 << 50 | k));
            assert!((0..25_000).all(|k| b.contains(fp(k)) && b.find(fp(k)).is_some()));
            assert!(!b.contains(fp(1 << 40)) && b.find(fp(1 << 40)).is_none());
            assert_eq!(b.insert(fp(3), None), Ok((UNNUMBERED, false)));
            // 8 bytes a slot, 7/16 to 7/8 full, no fingerprint or parent by number: at
            // most 18.3 bytes a state (a numbered store: 15 to 25).
            assert!(
                b.bytes() * 10 <= b.len() * 183 + 1024 * 80,
                "{room}: {}",
                b.bytes()
            );
        }
    }

    /// Fingerprints given by a function instead of kept: only one that agrees with the
    /// kept ones on the sample replaces them; the states keep their numbers and parents,
    /// and nothing is looked up any more.
    #[test]
    fn fingerprints_are_derived_only_alike() {
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 5;
        let mut s = Store::new();
        for k in 0..50_000u64 {
            s.insert(fp(k), k.checked_sub(1).map(|p| p as u32))
                .expect("room");
        }
        // Wrong on one state: the last, or one of the sampled in between.
        for wrong in [49_999, 49 * 1_000] {
            let derived = Box::new(move |i: u32| fp(u64::from(i)) ^ u64::from(i == wrong));
            assert!(!s.derive_fingerprints(derived), "{wrong}");
            assert!(!s.derived() && s.find(fp(7)) == Some(7));
        }
        assert!(s.derive_fingerprints(Box::new(move |i| fp(u64::from(i)))));
        assert!(s.derived() && s.fps.len() == 0 && s.slots.is_empty());
        assert_eq!(
            (s.len(), s.fingerprint(49_999), s.parent(77)),
            (50_000, fp(49_999), Some(76))
        );
        assert_eq!(s.find(fp(7)), None);
    }

    #[test]
    fn a_pair_is_read_back_from_its_fingerprint() {
        let mut x = 0x0123_4567_89ab_cdefu64;
        for _ in 0..10_000 {
            x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let (tag, place) = ((x >> 32) as u32, x as u32);
            assert_eq!(pair_of(pair_fingerprint(tag, place)), (tag, place));
        }
        assert_eq!(pair_fingerprint(0, 0), 0);
        assert_ne!(pair_fingerprint(1, 0), pair_fingerprint(0, 1));
    }

    #[test]
    fn fingerprints_by_place_answer_as_fingerprints_alone() {
        // Pairs of up to four tags per place (the first met at a place kept by place, the
        // others in the table), pair (0, 0) (fingerprint 0) among them, places beyond the
        // array, the greatest tag, and fingerprints of no pair known to the store: the
        // same answers, numbers and count as a store of fingerprints alone, sized in
        // advance or not, stale vacancies included.
        let fp = |k: u64| match k % 11 {
            3 => pair_fingerprint(u32::MAX, (k / 11) as u32 % 700),
            5 => pair_fingerprint(0, 1_000 + (k / 11) as u32),
            _ => pair_fingerprint((k % 4) as u32 * 7, (k / 4) as u32 % 900),
        };
        // Without places, a store of fingerprints alone with all the room asked for.
        let (a, b) = (
            Store::fingerprints_only(30_000),
            Store::fingerprints_by_place(30_000, 0),
        );
        assert_eq!(a.bytes(), b.bytes());
        for (room, places) in [(0, 900), (2_000, 900), (30_000, 1)] {
            let (mut a, mut b) = (
                Store::fingerprints_only(room),
                Store::fingerprints_by_place(room, places),
            );
            let keys = (0..20_000u64).map(|k| (k, if k == 17 { 0 } else { fp(k % 9_000) }));
            look_up_alike((&mut a, &mut b), keys, |k| fp(1 << 20 | k));
            assert!(b.contains(0) && b.contains(fp(3)) && !b.contains(pair_fingerprint(1, 5)));
            assert!((0..9_000).all(|k| a.contains(fp(k)) == b.contains(fp(k))));
            assert_eq!(b.insert(fp(4), None), Ok((UNNUMBERED, false)));
            if places > 1 {
                // The four tags of each of 900 places are kept by place, and the table
                // holds the rest only.
                let f = b.only.as_ref().expect("fingerprints only");
                assert_eq!(f.first.iter().filter(|&&t| t != 0).count(), 3600);
                assert_eq!(f.held + 3600, b.len());
            }
        }
    }

    #[test]
    fn tags_of_more_than_two_bytes_and_a_fifth_tag_go_to_the_table() {
        // At place 3: the greatest tag a place keeps (2^16 - 2, stored plus one), the
        // first it does not, a tag of four bytes, then three small tags, of which the
        // last finds the place's four slots taken.
        let tags = [65_534, 65_535, 1 << 20, 0, 1, 2, 3];
        let (mut a, mut b) = (
            Store::fingerprints_only(0),
            Store::fingerprints_by_place(0, 10),
        );
        // Keys that are multiples of 5: no other state is stored before a vacant one.
        let keys = (tags.iter()).map(|&t| pair_fingerprint(t, 3));
        look_up_alike((&mut a, &mut b), (0..).step_by(5).zip(keys), |k| k);
        let f = b.only.as_ref().expect("fingerprints only");
        assert_eq!(f.first[12..16], [65_535, 1, 2, 3]);
        assert_eq!(f.held, 3);
        assert!(tags.iter().all(|&t| b.contains(pair_fingerprint(t, 3))));
        assert!(!b.contains(pair_fingerprint(4, 3)) && !b.contains(pair_fingerprint(0, 4)));
    }

    #[test]
    fn a_store_with_room_holds_that_many_states_without_growing() {
        let fp = |k: u64| k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0x5555;
        for room in [1, 1_000, 10_000, 12_289, 14_000] {
            let mut s = Store::with_room(room);
            let slots = s.slots.len();
            assert!(slots >= 1024, "{room}: {slots} slots");
            for k in 0..room as u64 {
                assert_eq!(s.insert(fp(k), None), Ok((k as u32, true)), "{room}");
            }
            assert_eq!(s.slots.len(), slots, "{room}: the table grew");
            assert!((0..room as u64).all(|k| s.find(fp(k)) == Some(k as u32)));
            // One more than it made room for may grow it, and everything is still found.
            s.insert(fp(room as u64), None).expect("memory");
            assert!((0..=room as u64).all(|k| s.find(fp(k)) == Some(k as u32)));
        }
        assert!(Store::with_room(0).slots.is_empty());
        // Up to 7/8 full: 14,000 states in 2^14 slots, where 3/4 would have doubled it.
        assert_eq!(Store::with_room(14_000).slots.len(), 1 << 14);
        // A store grown as it fills doubles past 3/4.
        let mut s = Store::new();
        for k in 0..12_289u64 {
            s.insert(fp(k), None).expect("memory");
        }
        assert_eq!(
            s.slots.len(),
            1 << 15,
            "12,289 states are more than 3/4 of 2^14"
        );
    }
}
