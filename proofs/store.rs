//! The visited-state store (`check::store::Store`): states are numbered in the order their
//! fingerprints are first inserted, a fingerprint inserted again gets its first number back
//! (and is not new), every stored fingerprint is found and nothing else is, and each state
//! keeps the parent it was first reached from.
//!
//! Sequences of up to [`MAX_OPS`] inserts over [`FPS`], fingerprints chosen to collide in
//! the hash table (equal low bits) and to wrap around its end (the last slot), each with a
//! parent among the states stored before. The reference is a list in insertion order.

use crate::check::store::Store;

/// Fingerprints: three share the first slot of a table of any size up to 2^32, two share its
/// last slot (so probing wraps around to the first).
pub const FPS: [u64; 5] = [0, 1 << 32, 1 << 40, u64::MAX, u64::MAX >> 1];
/// Most inserts in one sequence.
pub const MAX_OPS: usize = 6;
/// Parent codes: 0 = none (an initial state), `k` = state `k - 1` if it is stored.
pub const PARENTS: u8 = 3;

/// What the property needs of a store; `Store` is the kernel, tests pass broken ones.
pub trait VisitedStore {
    /// Inserts `fp` reached from `parent`: its number and whether it is new.
    fn insert(&mut self, fp: u64, parent: Option<u32>) -> (u32, bool);
    /// The number of `fp`, if stored.
    fn find(&self, fp: u64) -> Option<u32>;
    /// The fingerprint of state `i`.
    fn fingerprint(&self, i: u32) -> u64;
    /// The parent of state `i`.
    fn parent(&self, i: u32) -> Option<u32>;
    /// How many states are stored.
    fn len(&self) -> usize;
}

impl VisitedStore for Store {
    fn insert(&mut self, fp: u64, parent: Option<u32>) -> (u32, bool) {
        Store::insert(self, fp, parent).expect("a few states fit in memory")
    }
    fn find(&self, fp: u64) -> Option<u32> {
        Store::find(self, fp)
    }
    fn fingerprint(&self, i: u32) -> u64 {
        Store::fingerprint(self, i)
    }
    fn parent(&self, i: u32) -> Option<u32> {
        Store::parent(self, i)
    }
    fn len(&self) -> usize {
        Store::len(self)
    }
}

/// A sequence of inserts: `(fingerprint code, parent code)` each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallInserts {
    len: u8,
    ops: [(u8, u8); MAX_OPS],
}

impl SmallInserts {
    /// The sequence these codes spell, if canonical: in range, unused slots all 0.
    pub fn new(len: u8, ops: [(u8, u8); MAX_OPS]) -> Option<SmallInserts> {
        let ok = usize::from(len) <= MAX_OPS
            && ops.iter().enumerate().all(|(i, &(f, p))| {
                if i < usize::from(len) {
                    usize::from(f) < FPS.len() && p < PARENTS
                } else {
                    (f, p) == (0, 0)
                }
            });
        ok.then_some(SmallInserts { len, ops })
    }

    fn ops(&self) -> &[(u8, u8)] {
        &self.ops[..usize::from(self.len)]
    }
}

/// Every canonical sequence of at most `max` inserts.
pub fn all_inserts(max: usize) -> Vec<SmallInserts> {
    let one: Vec<(u8, u8)> = (0..FPS.len() as u8)
        .flat_map(|f| (0..PARENTS).map(move |p| (f, p)))
        .collect();
    let mut out = vec![SmallInserts::new(0, [(0, 0); MAX_OPS]).expect("empty")];
    let mut frontier: Vec<Vec<(u8, u8)>> = vec![Vec::new()];
    for _ in 0..max.min(MAX_OPS) {
        frontier = frontier
            .iter()
            .flat_map(|l| {
                one.iter().map(move |op| {
                    let mut l = l.clone();
                    l.push(*op);
                    l
                })
            })
            .collect();
        for l in &frontier {
            let mut ops = [(0, 0); MAX_OPS];
            ops[..l.len()].copy_from_slice(l);
            out.push(SmallInserts::new(l.len() as u8, ops).expect("canonical"));
        }
    }
    out
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// Two stored fingerprints share a home slot.
    pub collision: bool,
    /// A fingerprint was inserted again.
    pub duplicate: bool,
}

/// The property, with `store` a fresh kernel.
pub fn store_numbers_first_insertions(
    input: &SmallInserts,
    mut store: impl VisitedStore,
) -> Result<Seen, String> {
    // The reference: fingerprints in first-insertion order, with their parents.
    let mut stored: Vec<(u64, Option<u32>)> = Vec::new();
    let mut duplicate = false;
    for &(f, p) in input.ops() {
        let fp = FPS[usize::from(f)];
        let parent = match p {
            0 => None,
            k => Some(u32::from(k) - 1).filter(|&i| (i as usize) < stored.len()),
        };
        let want = match stored.iter().position(|&(x, _)| x == fp) {
            Some(i) => (i as u32, false),
            None => {
                stored.push((fp, parent));
                (stored.len() as u32 - 1, true)
            }
        };
        duplicate |= !want.1;
        let got = store.insert(fp, parent);
        if got != want {
            return Err(format!(
                "{:?}: inserting {fp:#x} gives {got:?}, not {want:?}",
                input.ops()
            ));
        }
    }
    if store.len() != stored.len() {
        return Err(format!(
            "{:?}: {} states stored, not {}",
            input.ops(),
            store.len(),
            stored.len()
        ));
    }
    for (i, &(fp, parent)) in stored.iter().enumerate() {
        let i = i as u32;
        if store.fingerprint(i) != fp || store.parent(i) != parent {
            return Err(format!(
                "{:?}: state {i} is ({:#x}, {:?}), not ({fp:#x}, {parent:?})",
                input.ops(),
                store.fingerprint(i),
                store.parent(i)
            ));
        }
    }
    for fp in FPS {
        let want = stored.iter().position(|&(x, _)| x == fp).map(|i| i as u32);
        if store.find(fp) != want {
            return Err(format!(
                "{:?}: find({fp:#x}) is {:?}, not {want:?}",
                input.ops(),
                store.find(fp)
            ));
        }
    }
    // The first three share slot 0 and the last two the last slot in any table of up to
    // 2^32 slots.
    let low = |fp: u64| fp as u32;
    let collision = stored
        .iter()
        .enumerate()
        .any(|(i, a)| stored[..i].iter().any(|b| low(a.0) == low(b.0)));
    Ok(Seen {
        collision,
        duplicate,
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// Up to 6 inserts over 5 colliding fingerprints (the table's 1,024 slots are filled in
    /// a loop, hence the unwind bound).
    #[kani::proof]
    #[kani::unwind(1030)]
    fn store_numbers_states_by_first_insertion() {
        let input = SmallInserts::new(kani::any(), kani::any());
        kani::assume(input.is_some());
        let seen = store_numbers_first_insertions(&input.unwrap(), Store::new());
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.collision),
            "two fingerprints share a slot"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.duplicate),
            "a fingerprint inserted twice"
        );
        assert!(seen.is_ok());
    }
}
