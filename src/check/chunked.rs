//! Arrays that grow by adding chunks, never by copying.
//!
//! A `Vec` that grows reallocates: it copies itself into fresh memory, whose pages the
//! kernel must clear first. On this project's machines clearing a page costs more than
//! anything the search does with it, and a vector grown by a quarter at a time clears five
//! times its final size. A [`Chunked`] array keeps its elements in chunks of doubling size
//! up to [`MAX_CHUNK`] elements and equal size after, so every page is cleared once and
//! an element never moves; the next chunk is allocated with the last, and its pages are
//! faulted in ahead by a helper thread ([`populate_later`]). Its slack is at most about its
//! size while it is small, and at most two chunks after.

use super::store::OutOfMemory;

/// The first chunk's length, as a power of two.
const FIRST: u32 = 10;

/// The length of the largest chunks, as a power of two: 2 MiB of `u64`s (the size of a
/// huge page).
const MAX: u32 = 18;

/// The length of the largest chunks.
pub const MAX_CHUNK: usize = 1 << MAX;

/// Asks the processor to bring the cache line at `p` in: a hint, which never faults and
/// never changes what memory holds (a no-op where the target has no such instruction).
#[inline(always)]
pub fn prefetch<T>(p: *const T) {
    // SAFETY: every x86-64 processor has SSE; a prefetch reads no memory the program sees.
    #[cfg(target_arch = "x86_64")]
    unsafe {
        core::arch::x86_64::_mm_prefetch::<{ core::arch::x86_64::_MM_HINT_T0 }>(p.cast())
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// Chunks at least this large (in bytes) are faulted in ahead ([`populate_later`]).
const POPULATED: usize = 1 << 18;

/// How much [`populate_later`]'s helper faults in at one call (a power of two): a huge
/// page, about 12 ms of the kernel's work where fresh memory is slowest here.
#[cfg(target_os = "linux")]
const POPULATE_PIECE: usize = 1 << 21;

/// Asks a helper thread to fault in the pages of the `len` bytes at `start` (Linux's
/// `MADV_POPULATE_WRITE`), so that the thread that writes them first finds them ready: on
/// this project's machines the kernel clearing fresh pages costs about 1.5 s a gigabyte,
/// and the merging thread, which bounds a search, spent a fifth of the 6-cup kitchen's
/// search clearing the pages of the arrays it appends to. A hint: faulting in changes no
/// byte the program sees (a range unmapped meanwhile is refused, and nothing else happens),
/// and where it cannot be asked for, nothing is done.
pub fn populate_later<T>(start: *const T, len: usize) {
    #[cfg(target_os = "linux")]
    {
        use std::sync::mpsc::{channel, Sender};
        use std::sync::OnceLock;
        /// Where ranges (address, length) are sent to be faulted in, if the helper runs.
        static HELPER: OnceLock<Option<Sender<(usize, usize)>>> = OnceLock::new();
        let helper = HELPER.get_or_init(|| {
            let (tx, rx) = channel::<(usize, usize)>();
            let spawned = std::thread::Builder::new()
                .name("populate".into())
                .spawn(move || {
                    for (at, n) in rx {
                        populate_now(at, n);
                    }
                });
            spawned.ok().map(|_| tx)
        });
        if let Some(tx) = helper {
            let _ = tx.send((start as usize, len));
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (start, len);
}

/// Faults in the whole pages of the `n` bytes at `at` (`MADV_POPULATE_WRITE`), a piece of
/// [`POPULATE_PIECE`] at a time: faulting in holds the process's memory map for reading,
/// and a thread that maps memory meanwhile waits until the call returns (mimalloc growing
/// does, under its own lock, which the other threads then wait for). In one call, the
/// 6-cup table's growth stalled both searching threads for 1.7 s. A partial first page is
/// left to the thread that writes it; a piece refused (unmapped meanwhile) ends it.
#[cfg(target_os = "linux")]
fn populate_now(at: usize, n: usize) {
    let end = at.saturating_add(n);
    let mut from = at.next_multiple_of(super::slots::page());
    while from < end {
        let to = ((from + POPULATE_PIECE) & !(POPULATE_PIECE - 1)).min(end);
        // SAFETY: advice to fault pages in; it changes no memory's content and is refused
        // for a range that is not mapped.
        let done = unsafe {
            libc::madvise(
                from as *mut libc::c_void,
                to - from,
                libc::MADV_POPULATE_WRITE,
            )
        };
        if done != 0 {
            break;
        }
        from = to;
    }
}

/// Gives back to the system the whole pages of the `n` bytes at `at` (`MADV_DONTNEED`),
/// which the caller is about to free: they read as zeros if touched again, and are
/// faulted in afresh then.
fn dont_need(at: *const u8, n: usize) {
    #[cfg(target_os = "linux")]
    {
        let page = super::slots::page();
        let (from, to) = (
            at.addr().next_multiple_of(page),
            (at.addr() + n) & !(page - 1),
        );
        if from < to {
            // SAFETY: advice on whole pages of an allocation the caller owns and frees
            // next; no reference into it is used again before it is freed, and the
            // allocator may read its pages as zeros (a freed block's content is not its).
            unsafe {
                libc::madvise(from as *mut libc::c_void, to - from, libc::MADV_DONTNEED);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (at, n);
}

/// A chunk of `size` elements: `spare` if it is that large (`exact`: exactly that large),
/// else a new one; `spare` then becomes the chunk of `next` elements after it, faulted in
/// ahead ([`populate_later`]) when it is large. Without a spare (memory short), the next
/// chunk is allocated when it is needed.
fn next_chunk<T>(
    spare: &mut Vec<T>,
    (size, exact): (usize, bool),
    next: usize,
) -> Result<Vec<T>, OutOfMemory> {
    let mut chunk = std::mem::take(spare);
    if chunk.capacity() < size || (exact && chunk.capacity() != size) {
        chunk = Vec::new();
        chunk.try_reserve_exact(size).map_err(|_| OutOfMemory)?;
    }
    let bytes = next * std::mem::size_of::<T>();
    if bytes >= POPULATED && spare.try_reserve_exact(next).is_ok() {
        populate_later(spare.as_ptr(), bytes);
    }
    Ok(chunk)
}

/// A growable array in chunks that never move.
#[derive(Debug)]
pub struct Chunked<T> {
    chunks: Vec<Vec<T>>,
    len: usize,
    /// The next chunk, allocated with the last one and faulted in ahead
    /// ([`populate_later`]) when it is large.
    spare: Vec<T>,
}

impl<T> Default for Chunked<T> {
    fn default() -> Chunked<T> {
        Chunked {
            chunks: Vec::new(),
            len: 0,
            spare: Vec::new(),
        }
    }
}

/// Numbers by position, each in as few bytes as the largest so far needs (one, two or
/// four): the numbers of a search's distinct letters or sets of pending requests, one per
/// state, and of its transitions' distinct notes, one per transition, are most often
/// below 2^8 or 2^16 (6-cup kitchen: 121 sets, tens of thousands of letters, fewer than
/// 2^16 notes), and four bytes a state each was 328 MB of fresh memory (the notes' 287
/// MB), which this project's virtual machines fill at under 1 GB/s. A number too large
/// for the width so far widens every number held, once.
#[derive(Debug)]
pub enum Narrow {
    /// Every number below 2^8.
    Bytes(Chunked<u8>),
    /// Every number below 2^16.
    Halves(Chunked<u16>),
    /// Any number.
    Words(Chunked<u32>),
}

impl Default for Narrow {
    fn default() -> Narrow {
        Narrow::Bytes(Chunked::default())
    }
}

impl Narrow {
    /// Number of numbers.
    pub fn len(&self) -> usize {
        match self {
            Narrow::Bytes(c) => c.len(),
            Narrow::Halves(c) => c.len(),
            Narrow::Words(c) => c.len(),
        }
    }

    /// Number `i` (panics past the end, as slices do).
    // Always inlined, as `Chunked::get` is: out of line, it and `push` took 305 M
    // instructions where the callers had taken 180 M inlined (cachegrind, 4 cups).
    #[inline(always)]
    pub fn get(&self, i: usize) -> u32 {
        match self {
            Narrow::Bytes(c) => u32::from(c.get(i)),
            Narrow::Halves(c) => u32::from(c.get(i)),
            Narrow::Words(c) => c.get(i),
        }
    }

    /// Asks the processor to bring number `i` into its cache ([`Chunked::prefetch`]).
    #[inline(always)]
    pub fn prefetch(&self, i: usize) {
        match self {
            Narrow::Bytes(c) => c.prefetch(i),
            Narrow::Halves(c) => c.prefetch(i),
            Narrow::Words(c) => c.prefetch(i),
        }
    }

    /// Appends `x`; memory that cannot be had is [`OutOfMemory`].
    #[inline(always)]
    pub fn push(&mut self, x: u32) -> Result<(), OutOfMemory> {
        match self {
            Narrow::Bytes(c) if x < 1 << 8 => c.push(x as u8),
            Narrow::Halves(c) if x < 1 << 16 => c.push(x as u16),
            Narrow::Words(c) => c.push(x),
            _ => self.widen_and_push(x),
        }
    }

    /// Every number held again in a width that holds `x` too, then `x` appended.
    #[cold]
    #[inline(never)]
    fn widen_and_push(&mut self, x: u32) -> Result<(), OutOfMemory> {
        fn copied<T: Copy>(
            numbers: impl Iterator<Item = u32>,
            narrow: impl Fn(u32) -> T,
        ) -> Result<Chunked<T>, OutOfMemory> {
            let mut c = Chunked::default();
            for n in numbers {
                c.push(narrow(n))?;
            }
            Ok(c)
        }
        let numbers = (0..self.len()).map(|i| self.get(i)).chain([x]);
        *self = match x < 1 << 16 {
            true => Narrow::Halves(copied(numbers, |n| n as u16)?),
            false => Narrow::Words(copied(numbers, |n| n)?),
        };
        Ok(())
    }
}

/// Chunk `k` holds the elements from `start(k)` on, `capacity(k)` of them: chunks 0 and 1
/// hold `2^FIRST` each, chunk `k` up to `MAX - FIRST + 1` holds `2^(FIRST + k - 1)`, and
/// every later one `2^MAX`.
fn capacity(k: usize) -> usize {
    1 << (FIRST as usize + k.saturating_sub(1)).min(MAX as usize)
}

/// The chunk and offset of element `i`.
fn locate(i: usize) -> (usize, usize) {
    if i < 1 << FIRST {
        (0, i)
    } else if i < 1 << MAX {
        // Chunk k >= 1 holds [2^(FIRST + k - 1), 2^(FIRST + k)).
        let log = usize::BITS - 1 - i.leading_zeros();
        ((log - FIRST + 1) as usize, i - (1 << log))
    } else {
        // Chunk MAX - FIRST + 1 starts at 2^MAX, each after it 2^MAX later.
        (
            (MAX - FIRST + 1) as usize + ((i >> MAX) - 1),
            i & (MAX_CHUNK - 1),
        )
    }
}

impl<T: Copy> Chunked<T> {
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Asks the processor to bring element `i` into its cache, if there is one: a search
    /// reads its stored states and edges at random, and waiting for each read in turn was
    /// most of a user's search on a stored graph.
    #[inline]
    pub fn prefetch(&self, i: usize) {
        if i < self.len {
            let (k, at) = locate(i);
            prefetch(self.chunks[k].as_ptr().wrapping_add(at));
        }
    }

    /// Element `i` (panics past the end, as slices do).
    #[inline]
    pub fn get(&self, i: usize) -> T {
        assert!(i < self.len, "index {i} past the end ({})", self.len);
        let (k, at) = locate(i);
        self.chunks[k][at]
    }

    /// Element `i` and the next one, if any (panics past the end): a list's start and
    /// end, found once when they are in one chunk (all but one pair per chunk).
    #[inline]
    pub fn pair(&self, i: usize) -> (T, Option<T>) {
        assert!(i < self.len, "index {i} past the end ({})", self.len);
        let (k, at) = locate(i);
        let chunk = &self.chunks[k];
        match chunk.get(at + 1) {
            Some(&next) => (chunk[at], Some(next)),
            None => (chunk[at], (i + 1 < self.len).then(|| self.get(i + 1))),
        }
    }

    /// Appends `x`; a new chunk that cannot be allocated is [`OutOfMemory`].
    // Inlined, with the new chunk out of line: the merge pushes to several arrays per
    // state, and a call's prologue and epilogue were half of each push.
    #[inline]
    pub fn push(&mut self, x: T) -> Result<(), OutOfMemory> {
        let (k, _) = locate(self.len);
        if k == self.chunks.len() {
            self.add_chunk(k)?;
        }
        self.chunks[k].push(x);
        self.len += 1;
        Ok(())
    }

    /// Adds chunk `k` (the next one).
    #[cold]
    #[inline(never)]
    fn add_chunk(&mut self, k: usize) -> Result<(), OutOfMemory> {
        // Exactly its size: where an element is follows from the chunks' sizes.
        let chunk = next_chunk(&mut self.spare, (capacity(k), true), capacity(k + 1))?;
        self.chunks.try_reserve(1).map_err(|_| OutOfMemory)?;
        self.chunks.push(chunk);
        Ok(())
    }

    /// Removes every element, keeping the chunks for the next ones.
    pub fn clear(&mut self) {
        self.chunks.iter_mut().for_each(Vec::clear);
        self.len = 0;
    }

    /// Removes the last element.
    pub fn pop(&mut self) -> Option<T> {
        let last = self.len.checked_sub(1)?;
        let (k, _) = locate(last);
        self.len = last;
        self.chunks[k].pop()
    }

    /// The elements in order.
    pub fn iter(&self) -> impl Iterator<Item = T> + '_ {
        self.chunks.iter().flatten().copied()
    }

    /// Frees the chunks, their whole pages given back to the system first: the process
    /// keeps what it frees for its later allocations (`keep_freed_memory` in `main.rs`),
    /// and when those are mappings of their own (tables: `Slots`) it would hold both.
    /// (The store's fingerprints, once derived: 525 MB at 6 cups, which the users'
    /// searches after it did not reuse.)
    pub fn give_back(self) {
        for chunk in self.chunks.iter().chain([&self.spare]) {
            dont_need(
                chunk.as_ptr().cast(),
                chunk.capacity() * std::mem::size_of::<T>(),
            );
        }
    }

    /// Bytes allocated.
    pub fn bytes(&self) -> usize {
        (self.chunks.iter().map(Vec::capacity).sum::<usize>() + self.spare.capacity())
            * std::mem::size_of::<T>()
            + self.chunks.capacity() * std::mem::size_of::<Vec<T>>()
    }
}

/// Lists of numbers (a graph's adjacency lists) in chunks that never move, for the same
/// reason as [`Chunked`]: list `i` lies within one chunk, from where it starts to where
/// list `i + 1` starts if that is in the same chunk, else to the chunk's end. A list is
/// filled first ([`Lists::room`], [`Lists::push`]), then its start recorded
/// ([`Lists::start`]) at a position [`Lists::end`] gave before.
#[derive(Debug, Default)]
pub struct Lists {
    /// Per list, where it starts.
    starts: Starts,
    items: Vec<Vec<u32>>,
    /// The next chunk of items, faulted in ahead ([`populate_later`]) when it is large.
    spare: Vec<u32>,
    /// Per chunk, how many items the chunks before it hold ([`Lists::first_item`]), once
    /// asked for (forgotten when a chunk is added or cut).
    before: std::sync::OnceLock<Vec<u64>>,
}

/// Where each list of [`Lists`] starts: in about 2 bytes each while every start fits
/// ([`Blocked`]; the 6-cup kitchen's 65.6 M lists take 131 MB less than in 4 bytes and
/// 393 MB less than in 8), then in 4 while each fits ([`narrow`]), else all of them as
/// positions ([`Lists::end`]: chunk in the high 32 bits, offset).
#[derive(Debug)]
enum Starts {
    /// Per block of lists: until the first start that does not fit.
    Blocked(Blocked),
    /// Each start [`narrow`]: until the first that does not fit.
    Narrow(Chunked<u32>),
    /// Each start a position, from then on.
    Wide(Chunked<u64>),
}

impl Default for Starts {
    fn default() -> Starts {
        Starts::Blocked(Blocked::default())
    }
}

/// How many lists of [`Blocked`] share a position.
const BLOCK: usize = 64;

/// The mark of a [`Blocked`] start in the chunk after its block's first list's.
const NEXT_CHUNK: u16 = 1 << 15;

/// Lists' starts by blocks of [`BLOCK`]: the position of each block's first list, and
/// per list two bytes: its start's distance from that position in the same chunk, or
/// ([`NEXT_CHUNK`]) its offset in the next chunk. A block's lists hold few items (a
/// graph's states have a few transitions each), and a chunk holds up to 2^20.
#[derive(Debug, Default)]
struct Blocked {
    /// A plain vector, read at every list: 8 MB at 6 cups.
    firsts: Vec<u64>,
    starts: Chunked<u16>,
}

impl Blocked {
    /// Appends the start `at`; `false` (nothing appended) when it does not fit.
    #[inline]
    fn push(&mut self, at: u64) -> Result<bool, OutOfMemory> {
        let i = self.starts.len();
        if i.is_multiple_of(BLOCK) {
            self.firsts.try_reserve(1).map_err(|_| OutOfMemory)?;
            self.firsts.push(at);
            return self.starts.push(0).map(|()| true);
        }
        let first = self.firsts[i / BLOCK];
        let fits = |x: u32| (x < u32::from(NEXT_CHUNK)).then_some(x as u16);
        let short = match (at >> 32).checked_sub(first >> 32) {
            Some(0) => (at as u32).checked_sub(first as u32).and_then(fits),
            Some(1) => fits(at as u32).map(|x| x | NEXT_CHUNK),
            _ => None,
        };
        match short {
            Some(x) => self.starts.push(x).map(|()| true),
            None => Ok(false),
        }
    }

    /// The start whose two bytes are `x`, in the block whose first list starts at `first`.
    #[inline(always)]
    fn at(first: u64, x: u16) -> u64 {
        if x & NEXT_CHUNK == 0 {
            first + u64::from(x)
        } else {
            ((first >> 32) + 1) << 32 | u64::from(x & !NEXT_CHUNK)
        }
    }

    #[inline(always)]
    fn get(&self, i: usize) -> u64 {
        Blocked::at(self.firsts[i / BLOCK], self.starts.get(i))
    }

    /// Start `i` and, if there is one, start `i + 1`.
    #[inline(always)]
    fn pair(&self, i: usize) -> (u64, Option<u64>) {
        let (x, next) = self.starts.pair(i);
        let first = self.firsts[i / BLOCK];
        let next = next.map(|y| match (i + 1) % BLOCK {
            0 => Blocked::at(self.firsts[(i + 1) / BLOCK], y),
            _ => Blocked::at(first, y),
        });
        (Blocked::at(first, x), next)
    }

    fn len(&self) -> usize {
        self.starts.len()
    }

    /// Prefetches start `i`'s two bytes and its block's position.
    fn prefetch(&self, i: usize) {
        self.starts.prefetch(i);
        if let Some(first) = self.firsts.get(i / BLOCK) {
            prefetch(first);
        }
    }

    fn bytes(&self) -> usize {
        self.firsts.capacity() * 8 + self.starts.bytes()
    }
}

/// The largest chunk of [`Lists`] (4 MiB), unless one list is longer.
pub const LIST_CHUNK: usize = 1 << 20;

/// Bits of a narrow start ([`narrow`]) that hold the offset in its chunk: a chunk holds at
/// most [`LIST_CHUNK`] items unless one list is longer.
const OFFSET_BITS: u32 = 21;

/// A position ([`Lists::end`]: chunk in the high 32 bits, offset) in 4 bytes, the chunk
/// in the high 11 bits and the offset in the others, when both fit.
fn narrow(at: u64) -> Option<u32> {
    let (chunk, offset) = (at >> 32, at as u32);
    (chunk < 1 << (32 - OFFSET_BITS) && offset < 1 << OFFSET_BITS)
        .then_some((chunk as u32) << OFFSET_BITS | offset)
}

/// The `len` starts `old` in 4 bytes each ([`narrow`]) when all of them and `at` fit, else in 8,
/// then `at`.
#[cold]
#[inline(never)]
fn widened((len, old): (usize, impl Fn(usize) -> u64), at: u64) -> Result<Starts, OutOfMemory> {
    let all = || (0..len).map(&old).chain([at]);
    if all().all(|x| narrow(x).is_some()) {
        let mut n = Chunked::default();
        for x in all() {
            n.push(narrow(x).expect("fits"))?;
        }
        return Ok(Starts::Narrow(n));
    }
    let mut wide = Chunked::default();
    for x in all() {
        wide.push(x)?;
    }
    Ok(Starts::Wide(wide))
}

/// The position a [`narrow`] start stands for.
#[inline]
fn widen(x: u32) -> u64 {
    u64::from(x >> OFFSET_BITS) << 32 | u64::from(x & ((1 << OFFSET_BITS) - 1))
}

impl Lists {
    /// How many lists were started.
    #[inline]
    pub fn len(&self) -> usize {
        match &self.starts {
            Starts::Blocked(b) => b.len(),
            Starts::Narrow(n) => n.len(),
            Starts::Wide(w) => w.len(),
        }
    }

    /// Where list `i` starts (a position [`Lists::end`] gave).
    // Inlined always, and the readers below inlined: when they were not (perf: a first
    // version had `Lists::prefetch` and `Lists::first_item` out of line), the users'
    // searches, which read a list and its first item at every state, were slower in five
    // of six alternated 5- and 6-cup runs.
    #[inline(always)]
    fn start_of(&self, i: usize) -> u64 {
        match &self.starts {
            Starts::Blocked(b) => b.get(i),
            Starts::Narrow(n) => widen(n.get(i)),
            Starts::Wide(w) => w.get(i),
        }
    }

    /// Where list `i` starts and, if there is one, where list `i + 1` does.
    #[inline(always)]
    fn starts_at(&self, i: usize) -> (u64, Option<u64>) {
        match &self.starts {
            Starts::Blocked(b) => b.pair(i),
            Starts::Narrow(n) => {
                let (a, next) = n.pair(i);
                (widen(a), next.map(widen))
            }
            Starts::Wide(w) => w.pair(i),
        }
    }

    /// Where the next item goes.
    pub fn end(&self) -> u64 {
        match self.items.last() {
            Some(c) => ((self.items.len() as u64 - 1) << 32) | c.len() as u64,
            None => 0,
        }
    }

    /// Makes room for `n` more items in the last chunk, starting a chunk if needed.
    pub fn room(&mut self, n: usize) -> Result<(), OutOfMemory> {
        if self
            .items
            .last()
            .is_some_and(|c| c.capacity() - c.len() >= n)
        {
            return Ok(());
        }
        let size = (self.items.last())
            .map_or(1024, |c| (c.capacity() * 2).min(LIST_CHUNK))
            .max(n);
        let next = (size * 2).min(LIST_CHUNK);
        let chunk = next_chunk(&mut self.spare, (size, false), next)?;
        self.items.try_reserve(1).map_err(|_| OutOfMemory)?;
        self.items.push(chunk);
        self.before.take();
        Ok(())
    }

    /// Appends `x` to the last chunk, which has room ([`Lists::room`]).
    #[inline]
    pub fn push(&mut self, x: u32) {
        let c = self.items.last_mut().expect("room was made");
        debug_assert!(c.len() < c.capacity());
        c.push(x);
    }

    /// Starts the next list at `at`, a position [`Lists::end`] gave (its items pushed
    /// since, in that chunk).
    pub fn start(&mut self, at: u64) -> Result<(), OutOfMemory> {
        match &mut self.starts {
            Starts::Blocked(b) => {
                if !b.push(at)? {
                    self.starts = widened((b.len(), |i| b.get(i)), at)?;
                }
                Ok(())
            }
            Starts::Narrow(n) => match narrow(at) {
                Some(x) => n.push(x),
                None => {
                    self.starts = widened((n.len(), |i| widen(n.get(i))), at)?;
                    Ok(())
                }
            },
            Starts::Wide(w) => w.push(at),
        }
    }

    /// Removes the items from `at` (a position [`Lists::end`] gave) on, in its chunk.
    pub fn truncate(&mut self, at: u64) {
        if let Some(c) = self.items.get_mut((at >> 32) as usize) {
            c.truncate(at as u32 as usize);
            self.before.take();
        }
    }

    /// List `i`.
    #[inline]
    pub fn list(&self, i: usize) -> &[u32] {
        let (a, next) = self.starts_at(i);
        let chunk = &self.items[(a >> 32) as usize];
        let z = next.unwrap_or_else(|| self.end());
        let z = if z >> 32 == a >> 32 {
            z as u32 as usize
        } else {
            chunk.len()
        };
        &chunk[a as u32 as usize..z]
    }

    /// The number of list `i`'s first item among all items, in order (list after list):
    /// for arrays that hold something per item beside the lists, in the same order. The
    /// first call after a chunk is added or cut counts the items of each chunk.
    #[inline]
    pub fn first_item(&self, i: usize) -> u64 {
        let before = self.before.get_or_init(|| {
            let mut n = 0;
            (self.items.iter())
                .map(|c| {
                    let first = n;
                    n += c.len() as u64;
                    first
                })
                .collect()
        });
        let a = self.start_of(i);
        before[(a >> 32) as usize] + u64::from(a as u32)
    }

    /// How many items the lists hold.
    pub fn items(&self) -> u64 {
        self.items.iter().map(|c| c.len() as u64).sum()
    }

    /// Prefetches where list `i` starts, or (`near`) the list itself.
    #[inline]
    pub fn prefetch(&self, i: usize, near: bool) {
        if !near {
            return match &self.starts {
                Starts::Blocked(b) => b.prefetch(i),
                Starts::Narrow(n) => n.prefetch(i),
                Starts::Wide(w) => w.prefetch(i),
            };
        }
        if i < self.len() {
            let a = self.start_of(i);
            if let Some(chunk) = self.items.get((a >> 32) as usize) {
                prefetch(chunk.as_ptr().wrapping_add(a as u32 as usize));
            }
        }
    }

    /// How many chunks hold the items.
    #[cfg(test)]
    pub fn chunks(&self) -> usize {
        self.items.len()
    }

    /// Bytes allocated.
    pub fn bytes(&self) -> usize {
        (match &self.starts {
            Starts::Blocked(b) => b.bytes(),
            Starts::Narrow(n) => n.bytes(),
            Starts::Wide(w) => w.bytes(),
        }) + (self.items.iter().map(Vec::capacity).sum::<usize>() + self.spare.capacity()) * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where chunk `k + 1` starts.
    fn locate_start(k: usize) -> usize {
        (0..=k).map(capacity).sum()
    }

    #[test]
    fn chunks_tile_the_indices_without_gaps() {
        let mut next = 0;
        for k in 0..(MAX - FIRST + 4) as usize {
            assert_eq!(locate(next), (k, 0), "chunk {k} starts at {next}");
            let last = next + capacity(k) - 1;
            assert_eq!(locate(last), (k, capacity(k) - 1));
            next = last + 1;
        }
    }

    /// Narrow numbers read back as pushed, across both widenings (past the first chunk,
    /// so that numbers held in several chunks are moved), in the narrowest width that
    /// holds them all.
    #[test]
    fn narrow_numbers_read_back_as_pushed_in_the_least_width() {
        let n = (1usize << FIRST) + 1_000;
        let number = |i: usize, top: u32| (i as u32).wrapping_mul(2_654_435_761) % top;
        let mut a = Narrow::default();
        let mut pushed = Vec::new();
        for (top, width) in [(256, 1), (65_536, 2), (u32::MAX, 4)] {
            for i in 0..n {
                let x = number(i, top);
                a.push(x).unwrap();
                pushed.push(x);
            }
            let got = match &a {
                Narrow::Bytes(_) => 1,
                Narrow::Halves(_) => 2,
                Narrow::Words(_) => 4,
            };
            assert_eq!(got, width, "below {top}");
            assert_eq!(a.len(), pushed.len());
            assert!(
                (0..pushed.len()).all(|i| a.get(i) == pushed[i]),
                "below {top}"
            );
        }
    }

    /// The chunk a push adds is the one allocated (and faulted in) ahead with the one
    /// before, for arrays and lists alike.
    #[test]
    fn the_next_chunk_is_the_one_made_ahead() {
        let mut a: Chunked<u64> = Chunked::default();
        for i in 0..MAX_CHUNK as u64 {
            a.push(i).unwrap();
        }
        let ahead = a.spare.as_ptr();
        assert_eq!(a.spare.capacity(), capacity(a.chunks.len()));
        let k = a.chunks.len();
        while a.chunks.len() == k {
            a.push(1).unwrap();
        }
        assert_eq!(a.chunks[k].as_ptr(), ahead);
        assert_eq!(a.spare.capacity(), capacity(k + 1));
        let mut l = Lists::default();
        l.room(LIST_CHUNK / 2).unwrap();
        let ahead = l.spare.as_ptr();
        assert_eq!(l.spare.capacity(), LIST_CHUNK);
        for x in 0..LIST_CHUNK / 2 {
            l.push(x as u32);
        }
        l.room(10).unwrap();
        assert_eq!((l.chunks(), l.items[1].as_ptr()), (2, ahead));
        // Small arrays keep no chunk ahead.
        let mut small: Chunked<u32> = Chunked::default();
        small.push(1).unwrap();
        assert_eq!(small.spare.capacity(), 0);
    }

    #[test]
    fn elements_stay_where_they_were_put() {
        let mut a = Chunked::default();
        let n = MAX_CHUNK * 2 + 12_345;
        for i in 0..n as u64 {
            a.push(i * 3).unwrap();
        }
        assert_eq!(a.len(), n);
        assert!((0..n).step_by(997).all(|i| a.get(i) == i as u64 * 3));
        assert_eq!(a.get(n - 1), (n as u64 - 1) * 3);
        // Pairs, across every chunk boundary and at the end.
        let boundaries = (0..20).map(|k| locate_start(k) - 1).filter(|&i| i < n);
        for i in (0..n).step_by(997).chain(boundaries) {
            let next = (i + 1 < n).then(|| (i as u64 + 1) * 3);
            assert_eq!(a.pair(i), (i as u64 * 3, next), "{i}");
        }
        assert_eq!(a.pair(n - 1), ((n as u64 - 1) * 3, None));
        // Prefetching is a hint, anywhere, past the end too.
        for i in [0, n - 1, n, n + MAX_CHUNK, usize::MAX] {
            a.prefetch(i);
        }
        assert_eq!(a.pop(), Some((n as u64 - 1) * 3));
        assert_eq!(a.iter().count(), n - 1);
        assert!(a.iter().enumerate().all(|(i, x)| x == i as u64 * 3));
        // Slack: less than two largest chunks (the last one's room, and the next one,
        // faulted in ahead).
        assert!(a.bytes() < (n + 2 * MAX_CHUNK) * 8 + 4096, "{}", a.bytes());
        // Cleared, it keeps its chunks and fills them again.
        let bytes = a.bytes();
        a.clear();
        assert_eq!((a.len(), a.iter().count(), a.bytes()), (0, 0, bytes));
        for i in 0..n as u64 {
            a.push(i + 7).unwrap();
        }
        assert!((0..n).step_by(997).all(|i| a.get(i) == i as u64 + 7));
        assert_eq!((a.len(), a.bytes()), (n, bytes));
    }

    #[test]
    fn items_are_numbered_list_after_list_across_chunks() {
        // Every start in about 2 bytes, blocks across chunk boundaries.
        numbered_list_after_list(12, |s| matches!(s, Starts::Blocked(_)));
        // A list longer than a block's starts reach: the starts already made move to 4
        // bytes, and every list reads the same.
        numbered_list_after_list(1 << 15, |s| matches!(s, Starts::Narrow(_)));
        numbered_list_after_list(LIST_CHUNK + 5, |s| matches!(s, Starts::Narrow(_)));
        // A list so long that the next one starts past what 4 bytes hold: the starts
        // already made move to 8 bytes.
        numbered_list_after_list((1 << OFFSET_BITS) + 5, |s| matches!(s, Starts::Wide(_)));
    }

    /// Lists of 0 to 12 items and one of `long`, each item its own number: a list's first
    /// item is numbered as `first_item` says, over every chunk, also when it was asked
    /// before the last chunks were added; `held`: whether the starts end held as expected.
    fn numbered_list_after_list(long: usize, held: fn(&Starts) -> bool) {
        let mut lists = Lists::default();
        let mut lens = Vec::new();
        let mut next = 0u32;
        for i in 0..300_000usize {
            if i == 150_000 {
                assert_eq!(lists.first_item(0), 0);
            }
            let n = if i == 1000 { long } else { i * 7 % 13 };
            lists.room(n).expect("memory");
            let at = lists.end();
            for _ in 0..n {
                lists.push(next);
                next += 1;
            }
            lists.start(at).expect("memory");
            lens.push(n);
        }
        assert!(lists.chunks() > 3, "{} chunks", lists.chunks());
        assert!(held(&lists.starts), "{long}");
        assert_eq!(lists.len(), lens.len());
        let mut first = 0u64;
        for (i, &n) in lens.iter().enumerate() {
            assert_eq!(lists.first_item(i), first, "list {i}");
            let items = lists.list(i);
            assert_eq!(items.len(), n, "list {i}");
            assert_eq!(
                items.first().map(|&x| u64::from(x)),
                (n > 0).then_some(first)
            );
            first += n as u64;
        }
        assert_eq!(lists.items(), first);
        // Prefetching is a hint, anywhere.
        for i in [0, lens.len() - 1, lens.len()] {
            lists.prefetch(i, false);
            lists.prefetch(i, true);
        }
    }

    /// A position is the same once made narrow and widened, exactly when it fits.
    #[test]
    fn narrow_starts_widen_to_the_positions_they_were_made_of() {
        for chunk in [0u64, 1, 7, (1 << (32 - OFFSET_BITS)) - 1] {
            for offset in [0u64, 1, LIST_CHUNK as u64, (1 << OFFSET_BITS) - 1] {
                let at = chunk << 32 | offset;
                assert_eq!(narrow(at).map(widen), Some(at), "{chunk} {offset}");
            }
        }
        assert_eq!(narrow(1 << OFFSET_BITS), None);
        assert_eq!(narrow(1 << (32 - OFFSET_BITS) << 32), None);
    }

    #[test]
    #[should_panic(expected = "past the end")]
    fn reading_past_the_end_panics() {
        let mut a = Chunked::default();
        a.push(1u32).unwrap();
        a.get(1);
    }

    /// Runs `f` on a fresh private mapping of `len` bytes in small pages, with a function
    /// telling which of its pages are resident.
    #[cfg(target_os = "linux")]
    fn on_a_mapping(len: usize, f: impl FnOnce(usize, &dyn Fn() -> Vec<bool>)) {
        // SAFETY: a fresh private anonymous mapping, unmapped below; nothing else uses it.
        let base = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                len,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        assert_ne!(base, libc::MAP_FAILED);
        // Small pages, so that residency is told page by page.
        // SAFETY: advice on the mapping made above.
        unsafe { libc::madvise(base, len, libc::MADV_NOHUGEPAGE) };
        let page = crate::check::slots::page();
        let resident = || {
            let mut v = vec![0u8; len / page];
            // SAFETY: `v` has a byte for each page of the mapping.
            assert_eq!(unsafe { libc::mincore(base, len, v.as_mut_ptr()) }, 0);
            v.iter().map(|b| b & 1 == 1).collect::<Vec<bool>>()
        };
        f(base as usize, &resident);
        // SAFETY: the mapping made above, no longer read.
        unsafe { libc::munmap(base, len) };
    }

    /// Faulting in by pieces reaches every whole page of a range that starts and ends
    /// inside pages and spans several pieces, and nothing before it.
    #[cfg(target_os = "linux")]
    #[test]
    fn populating_faults_in_every_whole_page_of_the_range() {
        const LEN: usize = 4 * POPULATE_PIECE;
        on_a_mapping(LEN, |base, resident| {
            // A kernel without the advice (before Linux 5.14) faults nothing in: a hint.
            // SAFETY: advice on no bytes of the mapping.
            if unsafe { libc::madvise(base as *mut _, 0, libc::MADV_POPULATE_WRITE) } != 0 {
                return;
            }
            let page = crate::check::slots::page();
            assert!(resident().iter().all(|&r| !r));
            // From inside the third page to inside the page three pieces and one page later.
            let (from, n) = (2 * page + 100, 3 * POPULATE_PIECE);
            populate_now(base + from, n);
            let r = resident();
            let whole = (3..(from + n) / page).collect::<Vec<usize>>();
            assert!(
                whole.iter().all(|&p| r[p]),
                "a whole page of the range is missing"
            );
            assert!(!r[0] && !r[1], "a page before the range was faulted in");
        });
    }

    /// Giving pages back (`Chunked::give_back`) drops every whole page of a range from
    /// the resident memory, and nothing else: the pages it only overlaps keep what was
    /// written to them, and the whole ones read as zeros.
    #[cfg(target_os = "linux")]
    #[test]
    fn giving_back_drops_every_whole_page_of_the_range_and_nothing_else() {
        const LEN: usize = 2 * POPULATE_PIECE;
        on_a_mapping(LEN, |base, resident| {
            let page = crate::check::slots::page();
            // SAFETY: every byte written is within the mapping, which only this test uses.
            let bytes = unsafe { std::slice::from_raw_parts_mut(base as *mut u8, LEN) };
            bytes.fill(7);
            assert!(resident().iter().all(|&r| r));
            // From inside the second page to inside the second-to-last one.
            let (from, to) = (page + 100, LEN - page - 100);
            dont_need((base + from) as *const u8, to - from);
            let r = resident();
            let pages = LEN / page;
            let kept = [0, 1, pages - 2, pages - 1];
            for (p, &resident) in r.iter().enumerate() {
                assert_eq!(resident, kept.contains(&p), "page {p} of {pages}");
            }
            // SAFETY: as above.
            let bytes = unsafe { std::slice::from_raw_parts(base as *const u8, LEN) };
            assert!(bytes[..2 * page].iter().all(|&b| b == 7));
            assert!(bytes[2 * page..LEN - 2 * page].iter().all(|&b| b == 0));
            assert!(bytes[LEN - 2 * page..].iter().all(|&b| b == 7));
        });
    }
}
