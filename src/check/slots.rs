//! A hash table's slots that double in place: the numbered store's table
//! ([`super::store::Store`]) is rebuilt from the fingerprints at each growth, so the old
//! slots are never read again, and their memory can be the new table's first half.
//!
//! Why: in this project's virtual machines (Firecracker, with the kernel's free page
//! reporting), the first write to memory the process has not touched before costs
//! 1.7 s a GB with huge pages (0.5 s with small ones), against 0.13 s for memory it had
//! already written. A table that doubles into fresh memory touches twice its final size;
//! one that doubles in place touches its final size once (the 6-cup kitchen's agent
//! search: 671 MB of a table instead of 1.34 GB, on the merging thread).
//!
//! On Linux, a table reserves address space once (no memory: `PROT_NONE`), and makes
//! the part it uses readable and writable as it grows. Where that reservation cannot be
//! made (another system, an address-space limit), each size is a fresh vector as before.
//!
//! For the same reason a thread may keep the largest table it drops ([`keep_a_freed_table`])
//! for the next slots it makes that fit in it ([`Slots::in_kept`]): the agent's table,
//! dropped when its search ends, is the first user's array by place, and a user's array,
//! dropped when its search ends, the index of the `ltl` products run next on its thread.

use super::store::OutOfMemory;

/// Slots of type `T`, all reset to one value at each [`Slots::reset`].
pub(super) struct Slots<T: Copy> {
    mem: Mem<T>,
}

enum Mem<T> {
    Heap(Vec<T>),
    #[cfg(target_os = "linux")]
    Mapped(Mapping<T>),
}

/// Address space reserved for a table: `base` is aligned to huge pages; the first
/// `usable` bytes are readable and writable, and the first `len` slots are the table.
#[cfg(target_os = "linux")]
struct Mapping<T> {
    /// What `mmap` gave, and how much: what `munmap` takes back.
    start: *mut libc::c_void,
    reserved: usize,
    base: *mut T,
    usable: usize,
    len: usize,
    /// Whether its pages are left small ([`Slots::small`]) instead of advised huge.
    small: bool,
}

// SAFETY: a `Mapping` owns its memory as a `Vec` does; nothing else points into it.
#[cfg(target_os = "linux")]
unsafe impl<T: Send> Send for Mapping<T> {}
// SAFETY: shared references give shared slices only.
#[cfg(target_os = "linux")]
unsafe impl<T: Sync> Sync for Mapping<T> {}

/// Huge pages' size, to which a mapping's table is aligned.
#[cfg(target_os = "linux")]
const HUGE: usize = 2 << 20;

/// The system's page size, the unit of `mprotect` and `madvise` (a huge page, where the
/// system will not say).
#[cfg(target_os = "linux")]
pub(super) fn page() -> usize {
    // SAFETY: reads a constant of the system.
    usize::try_from(unsafe { libc::sysconf(libc::_SC_PAGESIZE) })
        .ok()
        .filter(|p| p.is_power_of_two())
        .unwrap_or(HUGE)
}

/// The address space a table reserves: enough for 2^33 slots of 8 bytes (a numbered
/// store holds fewer than 2^32 states, at most 3/4 of its slots), nothing of it memory
/// until used.
#[cfg(target_os = "linux")]
const RESERVE: usize = 1 << 36;

/// A table's reservation kept when the table was dropped, its usable memory written
/// (so faulted in): [`keep_a_freed_table`], [`Slots::in_kept`]. Given back when dropped.
#[cfg(target_os = "linux")]
struct Kept {
    start: usize,
    reserved: usize,
    base: usize,
    usable: usize,
}

#[cfg(target_os = "linux")]
impl Drop for Kept {
    fn drop(&mut self) {
        // SAFETY: a reservation a dropped table made, which nothing refers to.
        unsafe { libc::munmap(self.start as *mut libc::c_void, self.reserved) };
    }
}

#[cfg(target_os = "linux")]
thread_local! {
    /// Whether the next table this thread drops is kept, and the one kept. Per thread, so
    /// that which search gets it does not depend on timing: the agent's search drops its
    /// table on the thread that then runs the first user's search.
    static KEPT: std::cell::RefCell<(bool, Option<Kept>)> = const { std::cell::RefCell::new((false, None)) };
}

/// While `on`, the largest table this thread drops keeps its memory for this thread's
/// next [`Slots::in_kept`] instead of giving it back; turned off, what is kept is given
/// back.
///
/// The agent's table (671 MB at 6 cups) is dropped when its search ends, and a user's
/// search begins by writing 525 MB of fresh memory (its array by place,
/// [`super::store::Store::fingerprints_by_place`]): in this project's virtual machines
/// the first write to memory the process has not written costs several times a write to
/// memory it has, and 4-5 s of a user's thread at 6 cups went to it.
fn keep_a_freed_table(on: bool) {
    #[cfg(target_os = "linux")]
    {
        let given_back = KEPT.with_borrow_mut(|k| {
            k.0 = on;
            if on {
                None
            } else {
                k.1.take()
            }
        });
        drop(given_back);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = on;
}

/// Keeps the largest table this thread drops ([`keep_a_freed_table`]) until this is
/// dropped.
pub(super) struct Keeping;

impl Keeping {
    /// From now on, the largest table this thread drops is kept.
    pub(super) fn start() -> Keeping {
        keep_a_freed_table(true);
        Keeping
    }
}

impl Drop for Keeping {
    fn drop(&mut self) {
        keep_a_freed_table(false);
    }
}

impl<T: Copy> Default for Slots<T> {
    fn default() -> Self {
        Slots {
            mem: Mem::Heap(Vec::new()),
        }
    }
}

impl<T: Copy> Slots<T> {
    /// `len` slots, each `empty` (none when memory for them cannot be had).
    pub(super) fn new(len: usize, empty: T) -> Slots<T> {
        let mut s = Slots::default();
        if s.reset(len, empty).is_err() {
            s = Slots::default();
        }
        s
    }

    /// Slots on the heap: `v`.
    pub(super) fn from_vec(v: Vec<T>) -> Slots<T> {
        Slots { mem: Mem::Heap(v) }
    }

    /// `len` slots, each `empty`, in fresh memory of small pages that a thread keeping
    /// freed tables keeps when they are dropped ([`Keeping`]; slots on the heap are not
    /// kept); `None` where that cannot be had. For slots read nearly in order, which need
    /// no huge pages (their first write costs several times a small page's here).
    pub(super) fn small(len: usize, empty: T) -> Option<Slots<T>> {
        #[cfg(target_os = "linux")]
        {
            let mut m = Mapping::reserve()?;
            m.small = true;
            m.resize(len).ok()?;
            let mut s = Slots {
                mem: Mem::Mapped(m),
            };
            s.fill(empty);
            Some(s)
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = (len, empty);
            None
        }
    }

    /// `len` slots, each `empty`, in the memory of the table this thread kept
    /// ([`Slots::in_kept`]), else in fresh memory of small pages ([`Slots::small`]), else on
    /// the heap; [`OutOfMemory`] when none can be had. For slots read nearly in order (a
    /// user's array by place) or made whole once (the `ltl` products' index): fresh memory
    /// costs this project's virtual machines up to a CPU-second a gigabyte to clear.
    pub(super) fn reused_or_fresh(len: usize, empty: T) -> Result<Slots<T>, OutOfMemory> {
        match Slots::in_kept(len, empty).or_else(|| Slots::small(len, empty)) {
            Some(s) => Ok(s),
            None => Ok(Slots::from_vec(super::store::table(len, empty, false)?)),
        }
    }

    /// `len` slots, each `empty`, in the memory of the table kept ([`keep_a_freed_table`])
    /// if there is one that large: it is then no longer kept (while this thread keeps, the
    /// next table it drops may be). Its memory beyond the slots, in whole huge pages, is
    /// given back.
    pub(super) fn in_kept(len: usize, empty: T) -> Option<Slots<T>> {
        #[cfg(target_os = "linux")]
        {
            let bytes = len.checked_mul(std::mem::size_of::<T>())?;
            let kept = KEPT.with_borrow_mut(|k| {
                if bytes == 0 || k.1.as_ref().is_none_or(|kept| kept.usable < bytes) {
                    return None;
                }
                k.1.take()
            })?;
            // The reservation is the table's from here on (its `Mapping` gives it back).
            let kept = std::mem::ManuallyDrop::new(kept);
            let usable = bytes.next_multiple_of(HUGE).min(kept.usable);
            if usable < kept.usable {
                let tail = (kept.base + usable) as *mut libc::c_void;
                // SAFETY: pages of the kept reservation past the slots: made inaccessible
                // again and given back; nothing refers to them.
                unsafe {
                    libc::mprotect(tail, kept.usable - usable, libc::PROT_NONE);
                    libc::madvise(tail, kept.usable - usable, libc::MADV_DONTNEED);
                }
            }
            let mut s = Slots {
                mem: Mem::Mapped(Mapping {
                    start: kept.start as *mut libc::c_void,
                    reserved: kept.reserved,
                    base: kept.base as *mut T,
                    usable,
                    len,
                    small: false,
                }),
            };
            s.fill(empty);
            Some(s)
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = (len, empty);
            None
        }
    }

    /// Makes the table `len` slots, each `empty`, in the memory it had where it can
    /// ([`Slots`]); as it was, and [`OutOfMemory`], when memory for them cannot be had.
    pub(super) fn reset(&mut self, len: usize, empty: T) -> Result<(), OutOfMemory> {
        #[cfg(target_os = "linux")]
        {
            if len > 0 && matches!(self.mem, Mem::Heap(_)) {
                if let Some(m) = Mapping::reserve() {
                    self.mem = Mem::Mapped(m);
                }
            }
            if let Mem::Mapped(m) = &mut self.mem {
                m.resize(len)?;
                self[..].fill(empty);
                return Ok(());
            }
        }
        self.mem = Mem::Heap(super::store::table(len, empty, true)?);
        Ok(())
    }

    /// Makes the first `len` slots' memory usable ahead of a [`Slots::reset`] to that size,
    /// and has a helper thread fault it in ([`super::chunked::populate_later`]): the reset
    /// then writes to memory that is there. At 6 cups the merging thread, which bounds
    /// the search, spent 1.4 s clearing the fresh pages of the table's last growth. A
    /// hint: nothing is done where the memory is not a reservation or cannot be had.
    pub(super) fn prepare(&mut self, len: usize) {
        #[cfg(target_os = "linux")]
        if let Mem::Mapped(m) = &mut self.mem {
            let bytes = len.saturating_mul(std::mem::size_of::<T>());
            if let Ok(Some((from, more))) = m.usable_to(bytes) {
                super::chunked::populate_later(from, more);
            }
        }
        #[cfg(not(target_os = "linux"))]
        let _ = len;
    }

    /// Bytes of memory held (those readable and writable, for a mapping).
    pub(super) fn bytes(&self) -> usize {
        match &self.mem {
            Mem::Heap(v) => v.capacity() * std::mem::size_of::<T>(),
            #[cfg(target_os = "linux")]
            Mem::Mapped(m) => m.usable,
        }
    }
}

impl<T: Copy> std::ops::Deref for Slots<T> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        match &self.mem {
            Mem::Heap(v) => v,
            // SAFETY: the first `len` slots are readable and writable, and were written.
            #[cfg(target_os = "linux")]
            Mem::Mapped(m) => unsafe { std::slice::from_raw_parts(m.base, m.len) },
        }
    }
}

impl<T: Copy> std::ops::DerefMut for Slots<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        match &mut self.mem {
            Mem::Heap(v) => v,
            // SAFETY: as in `deref`, and `&mut self` is the only way to the memory.
            #[cfg(target_os = "linux")]
            Mem::Mapped(m) => unsafe { std::slice::from_raw_parts_mut(m.base, m.len) },
        }
    }
}

#[cfg(target_os = "linux")]
impl<T> Mapping<T> {
    /// Address space for a table, none of it usable yet; `None` when the system refuses.
    fn reserve() -> Option<Mapping<T>> {
        let reserved = RESERVE + HUGE;
        // SAFETY: a fresh anonymous mapping, inaccessible: it changes no memory of ours.
        let start = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                reserved,
                libc::PROT_NONE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_NORESERVE,
                -1,
                0,
            )
        };
        if start == libc::MAP_FAILED {
            return None;
        }
        let base = (start as usize).next_multiple_of(HUGE) as *mut T;
        Some(Mapping {
            start,
            reserved,
            base,
            usable: 0,
            len: 0,
            small: false,
        })
    }

    /// Makes the first `len` slots usable (their content unspecified).
    fn resize(&mut self, len: usize) -> Result<(), OutOfMemory> {
        let bytes = len
            .checked_mul(std::mem::size_of::<T>())
            .ok_or(OutOfMemory)?;
        self.usable_to(bytes)?;
        self.len = len;
        Ok(())
    }

    /// Makes the first `bytes` of the reservation usable: the part that was not yet
    /// (start, length), if any.
    fn usable_to(&mut self, bytes: usize) -> Result<Option<(*const u8, usize)>, OutOfMemory> {
        if bytes > RESERVE {
            return Err(OutOfMemory);
        }
        if bytes <= self.usable {
            return Ok(None);
        }
        // Whole huge pages once past the first: a small table keeps small pages.
        let usable = bytes.next_multiple_of(if bytes < HUGE || self.small {
            page()
        } else {
            HUGE
        });
        // SAFETY: within the reservation; the part made usable is not ours yet.
        let (from, more) = (
            unsafe { self.base.cast::<u8>().add(self.usable) },
            usable - self.usable,
        );
        // SAFETY: changes the protection of our own reserved, unused pages.
        let r = unsafe { libc::mprotect(from.cast(), more, libc::PROT_READ | libc::PROT_WRITE) };
        if r != 0 {
            return Err(OutOfMemory);
        }
        // Read at random: huge pages spare the processor's TLB a miss per lookup
        // (a hint; see `store::huge_pages`).
        if !self.small {
            // SAFETY: advice about our own pages, before they are first written.
            unsafe { libc::madvise(from.cast(), more, libc::MADV_HUGEPAGE) };
        }
        self.usable = usable;
        Ok(Some((from.cast_const(), more)))
    }
}

#[cfg(target_os = "linux")]
impl<T> Drop for Mapping<T> {
    fn drop(&mut self) {
        // A larger table than the one kept takes its place (the kept one is given back).
        let kept = KEPT.try_with(|k| {
            let mut k = k.borrow_mut();
            let keep = k.0 && self.usable > k.1.as_ref().map_or(0, |kept| kept.usable);
            let replaced = keep.then(|| {
                k.1.replace(Kept {
                    start: self.start as usize,
                    reserved: self.reserved,
                    base: self.base as usize,
                    usable: self.usable,
                })
            });
            drop(k);
            drop(replaced);
            keep
        });
        if kept == Ok(true) {
            return;
        }
        // SAFETY: the mapping `reserve` made, which nothing refers to any more.
        unsafe { libc::munmap(self.start, self.reserved) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reset_table_is_all_empty_at_every_size() {
        let mut s = Slots::new(1024, [0xffu8; 5]);
        assert_eq!(s.len(), 1024);
        for len in [2048, 4096, 1 << 20, 1 << 21] {
            // What the previous size held is gone.
            s[7] = [1; 5];
            let last = s.len() - 1;
            s[last] = [2; 5];
            s.reset(len, [0xff; 5]).expect("memory");
            assert_eq!(s.len(), len);
            assert!(s.iter().all(|x| *x == [0xff; 5]));
            assert!(s.bytes() >= len * 5);
        }
        // On Linux the table grows in the memory it had: its first slot stays put.
        #[cfg(target_os = "linux")]
        {
            assert!(matches!(s.mem, Mem::Mapped(_)), "address space reserved");
            let first = s.as_ptr();
            s.reset(1 << 22, [0xff; 5]).expect("memory");
            assert_eq!(s.as_ptr(), first);
        }
        // Smaller again, then empty.
        s.reset(16, [3; 5]).expect("memory");
        assert_eq!(&s[..], &[[3; 5]; 16]);
        s.reset(0, [3; 5]).expect("memory");
        assert!(s.is_empty());
    }

    /// Memory made ready for the next size changes nothing the table holds, and the
    /// reset to that size finds it usable (on Linux, already so) and empties it.
    #[test]
    fn a_prepared_growth_keeps_the_table_and_is_used_by_the_reset() {
        let mut s = Slots::new(1 << 20, [0xffu8; 5]);
        s[3] = [1; 5];
        let held = s.bytes();
        s.prepare(1 << 21);
        assert_eq!(s.len(), 1 << 20);
        assert_eq!(s[3], [1; 5]);
        assert!(s.bytes() >= held);
        #[cfg(target_os = "linux")]
        assert!(s.bytes() >= (1 << 21) * 5, "made usable ahead");
        // Preparing again, or for less, does nothing more.
        let ready = s.bytes();
        s.prepare(1 << 21);
        s.prepare(1 << 10);
        assert_eq!(s.bytes(), ready);
        s.reset(1 << 21, [0xff; 5]).expect("memory");
        assert_eq!(s.bytes(), ready, "the reset used what was prepared");
        assert!(s.iter().all(|x| *x == [0xff; 5]));
        // A table on the heap ignores the hint.
        let mut h = Slots {
            mem: Mem::Heap(vec![7u64; 8]),
        };
        h.prepare(1 << 20);
        assert_eq!((h.len(), h.bytes()), (8, 64));
    }

    /// While this thread keeps a freed table, the largest table it drops is the memory of
    /// its next `in_kept` slots that fit in it, once each; otherwise nothing is kept.
    #[test]
    #[cfg(target_os = "linux")]
    fn a_table_dropped_while_keeping_is_the_memory_of_the_next_slots_in_kept() {
        drop(Slots::new(1 << 20, [0xffu8; 5]));
        assert!(Slots::<u16>::in_kept(16, 0).is_none(), "not keeping");
        let keeping = Keeping::start();
        // The largest dropped is kept, whether dropped before a smaller one or after.
        drop(Slots::new(1 << 10, [0xffu8; 5]));
        let mut t = Slots::new(1 << 20, [0xffu8; 5]);
        t[9] = [1; 5];
        let base = t.as_ptr() as usize;
        drop(t);
        drop(Slots::new(1 << 10, [0xffu8; 5]));
        assert!(
            Slots::<u16>::in_kept(1 << 22, 7).is_none(),
            "too large for it"
        );
        let s = Slots::<u16>::in_kept(1 << 20, 7).expect("the table dropped");
        assert_eq!(s.as_ptr() as usize, base);
        assert_eq!(s.len(), 1 << 20);
        assert!(s.iter().all(|&x| x == 7));
        // The memory past the slots, in whole huge pages, is given back.
        assert_eq!(s.bytes(), HUGE);
        assert!(Slots::<u16>::in_kept(16, 0).is_none(), "taken once");
        // Still keeping: slots made in kept memory, or fresh small ones, are kept in turn
        // when dropped (a user's array by place, then the products' index).
        let small = Slots::<u32>::small(1 << 20, 9).expect("a reservation");
        assert!(small.iter().all(|&x| x == 9) && small.len() == 1 << 20);
        let small_base = small.as_ptr() as usize;
        drop(s);
        drop(small);
        let again = Slots::<u32>::reused_or_fresh(1 << 18, 4).expect("memory");
        assert_eq!(again.as_ptr() as usize, small_base);
        assert!(again.iter().all(|&x| x == 4));
        drop(keeping);
        assert!(
            Slots::<u16>::in_kept(16, 0).is_none(),
            "given back when keeping stops"
        );
        let fresh = Slots::<u16>::reused_or_fresh(16, 3).expect("memory");
        assert_eq!(&fresh[..], &[3; 16]);
        drop(again);
        // Stopping gives back what is kept.
        let keeping = Keeping::start();
        drop(Slots::new(1 << 10, 0u64));
        drop(keeping);
        assert!(Slots::<u16>::in_kept(16, 0).is_none(), "given back");
    }

    #[test]
    fn a_table_beyond_its_reservation_is_refused() {
        let mut s = Slots::new(8, 0u64);
        assert_eq!(s.reset(usize::MAX / 4, 0), Err(OutOfMemory));
        assert_eq!(&s[..], &[0; 8], "left as it was");
    }
}
