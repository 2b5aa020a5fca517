//! Per-thread caches in front of memos that the searching threads share.
//!
//! A shared memo costs a shard's lock, a hash and a probe that most often misses the
//! processor's cache; consecutive states of one job mostly read the entries read just
//! before. Each thread keeps the entries it read last in a direct-mapped table, tagged with
//! the memo's [`serial`], so that an entry is never given to another memo (or another
//! search) with equal keys.

use super::compiled::{mix, Quick};
use std::hash::{BuildHasher, Hash};

/// A thread's table of entries: the memo (by [`serial`]), the key, the value.
pub(crate) type Recently<K, V> = std::cell::RefCell<Vec<(u64, K, Option<V>)>>;

/// A number no other memo has: tells its entries from every other memo's in the threads'
/// tables.
pub(crate) fn serial() -> u64 {
    static SERIAL: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// `read` of the value of `key` in the memo numbered `serial`: from this thread's `cache`
/// (of `size` entries, a power of two) when it holds it, else made by `find` (which
/// reads the shared memo) and kept in the cache.
pub(crate) fn recently<K: Copy + PartialEq + Hash, V, R>(
    cache: &'static std::thread::LocalKey<Recently<K, V>>,
    size: usize,
    (serial, key): (u64, K),
    find: impl FnOnce() -> V,
    read: impl Fn(&V) -> R,
) -> R {
    debug_assert!(size.is_power_of_two());
    let slot = (mix(Quick::default().hash_one(key) ^ serial) as usize) & (size - 1);
    let hit = cache.with_borrow(|r| {
        (r.get(slot))
            .filter(|e| (e.0, e.1) == (serial, key))
            .and_then(|e| e.2.as_ref().map(&read))
    });
    if let Some(r) = hit {
        return r;
    }
    let v = find();
    let r = read(&v);
    cache.with_borrow_mut(|c| {
        if c.is_empty() {
            c.resize_with(size, || (0, key, None));
        }
        c[slot] = (serial, key, Some(v));
    });
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A thread's cache gives an entry again only to the memo (serial) and key it was read
    /// for, and reads it without taking it from the memo again.
    #[test]
    fn entries_are_given_again_only_to_their_memo_and_key() {
        const SIZE: usize = 1 << 10;
        thread_local! {
            static CACHE: Recently<(usize, usize), u32> = const { std::cell::RefCell::new(Vec::new()) };
        }
        let found = std::cell::Cell::new(0);
        let read = |serial, key, value| {
            recently(
                &CACHE,
                SIZE,
                (serial, key),
                || {
                    found.set(found.get() + 1);
                    value
                },
                |v: &u32| *v,
            )
        };
        assert_eq!(read(1, (8, 3), 10), 10);
        assert_eq!(read(1, (8, 3), 99), 10);
        assert_eq!(found.get(), 1);
        // Another memo, another key: each its own entry.
        assert_eq!(read(2, (8, 3), 20), 20);
        assert_eq!(read(1, (8, 4), 30), 30);
        assert_eq!(found.get(), 3);
        // Many keys: entries that share a slot replace each other, and none is mistaken
        // for another.
        for round in 0..2 {
            for k in 0..3 * SIZE {
                assert_eq!(read(3, (k, 0), k as u32), k as u32, "round {round}");
            }
        }
        assert!(found.get() > 3 * SIZE);
        // Serials are never given twice.
        assert_ne!(serial(), serial());
    }
}
