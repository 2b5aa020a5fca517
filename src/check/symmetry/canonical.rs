//! The canonical member of a state's class, found without trying all `k!` renamings:
//! objects sorted by a signature renaming carries along, and only the ties among objects
//! that are not interchangeable tried in every order (see the `symmetry` module documentation).

use super::{mix, next_arrangement};
use super::{Involves, Perm, Renaming, Symmetry};
use crate::check::explore::fingerprint;
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::Substitution;
use crate::semantics::compiled::MAP_CODE;
use crate::semantics::state::{CursorKind, Event, Intention};
use crate::semantics::{Compiled, Origin, Packed, State};
use smallvec::{smallvec, SmallVec};

/// Most orders tried to break ties between objects that are not interchangeable; beyond
/// it the sorted order is kept as it is (less reduction, still sound).
const MAX_TIE_ORDERS: usize = 5040;

/// Symmetric objects in order of first occurrence; on the stack for up to 16 of them, as
/// this is found for every successor.
type Occurrences = SmallVec<[u16; 16]>;

/// One value per symmetric object, on the stack for up to 16 of them.
type Features<T> = SmallVec<[T; 16]>;

impl Symmetry {
    /// The symmetric objects in the order they first occur in the state's terms.
    fn occurrences(&self, s: &State) -> Occurrences {
        let mut named = Vec::new();
        let intentions = s
            .intentions
            .iter()
            .chain(s.pending.iter().map(|p| &p.intention))
            .chain(s.waiting.iter().map(|w| &w.intention));
        self.agenda_objects(s.events.iter(), intentions, &mut named);
        let mut out = Occurrences::from_vec(named);
        self.order_objects(&s.order, &mut out);
        out
    }

    /// Appends the symmetric objects that the events' and then the intentions' terms
    /// name, in order of first occurrence.
    fn agenda_objects<'a>(
        &self,
        events: impl Iterator<Item = &'a Event>,
        intentions: impl Iterator<Item = &'a Intention>,
        out: &mut Vec<u16>,
    ) {
        for e in events {
            self.collect_objects(&e.trigger.literal, out);
            self.origin_objects(e.origin, out);
            if let Some(i) = &e.intention {
                self.intention_objects(i, out);
            }
        }
        for i in intentions {
            self.intention_objects(i, out);
        }
    }

    /// Appends the symmetric objects of the beliefs in their order, not yet in `out`: the
    /// belief-base order tells interchangeable objects apart too (`cupAt(cup2, _)` added
    /// after `cupAt(cup1, _)` is answered first).
    fn order_objects(&self, order: &[AtomId], out: &mut Occurrences) {
        for a in order {
            for &(_, _, o) in &self.atom_args[a.0 as usize] {
                if !out.contains(&o) {
                    out.push(o);
                }
            }
        }
    }

    fn origin_objects(&self, o: Origin, out: &mut Vec<u16>) {
        if let Origin::Request(r) = o {
            self.collect_objects(&self.requests[r as usize], out);
        }
    }

    fn intention_objects(&self, i: &Intention, out: &mut Vec<u16>) {
        self.origin_objects(i.origin, out);
        for f in &i.frames {
            self.collect_objects(&f.trigger.literal, out);
            for (_, t) in f.subst.iter() {
                self.collect_objects(t, out);
            }
            for c in &f.cursors {
                let subs: Vec<&Substitution> = match &c.kind {
                    CursorKind::For { rest, base } => {
                        rest.iter().chain(std::iter::once(base)).collect()
                    }
                    CursorKind::While { base, .. } => vec![base],
                    CursorKind::Seq => Vec::new(),
                };
                for sub in subs {
                    for (_, t) in sub.iter() {
                        self.collect_objects(t, out);
                    }
                }
            }
        }
    }

    /// The renaming that takes `s` to its canonical member (see the module documentation),
    /// and whether ties between objects that are not interchangeable remain to be tried.
    fn sorting(&self, s: &State) -> (Perm, Vec<Vec<u16>>) {
        let n = self.objects.len();
        let mut hash: Features<u64> = smallvec![0; n];
        let mut shared: Features<bool> = smallvec![false; n];
        self.belief_features(&s.beliefs, &mut hash, &mut shared);
        self.request_features(s.requested, &mut hash, &mut shared);
        let mut first: Features<u32> = smallvec![u32::MAX; n];
        for (k, &o) in self.occurrences(s).iter().enumerate() {
            first[o as usize] = k as u32;
        }
        self.sort(&first, &hash, &shared)
    }

    /// [`Symmetry::sorting`] of a compiled state, without unpacking it: what its agenda
    /// and its beliefs tell of the objects is found once per agenda and per belief base
    /// ([`Compiled::derived`], [`Compiled::derived_from_beliefs`]).
    fn sorting_compiled(&self, c: &Compiled, p: &Packed) -> (Perm, Vec<Vec<u16>>) {
        let n = self.objects.len();
        let named = c.derived(p, self.serial, |p| {
            let mut out = Vec::new();
            let intentions = p.intentions().chain(p.pending().map(|x| &x.intention));
            self.agenda_objects(p.events(), intentions, &mut out);
            out
        });
        // Per object its hash, then whether it is shared, then the objects in the
        // beliefs' order.
        let base = c.derived_from_beliefs(p, self.serial, |p| {
            let mut hash: Features<u64> = smallvec![0; n];
            let mut shared: Features<bool> = smallvec![false; n];
            self.belief_features(p.beliefs(), &mut hash, &mut shared);
            let mut order = Occurrences::new();
            self.order_objects(p.order(), &mut order);
            let shared = shared.iter().map(|&x| u64::from(x));
            hash.iter()
                .copied()
                .chain(shared)
                .chain(order.iter().map(|&o| u64::from(o)))
                .collect()
        });
        // Where each object first occurs: in the agenda's terms, then in the beliefs' order.
        let mut first: Features<u32> = smallvec![u32::MAX; n];
        let mut next = 0;
        for o in named
            .iter()
            .map(|&o| o as usize)
            .chain(base[2 * n..].iter().map(|&o| o as usize))
        {
            if first[o] == u32::MAX {
                first[o] = next;
                next += 1;
            }
        }
        let mut hash = Features::from_slice(&base[..n]);
        let mut shared: Features<bool> = base[n..2 * n].iter().map(|&x| x != 0).collect();
        self.request_features(p.requested(), &mut hash, &mut shared);
        self.sort(&first, &hash, &shared)
    }

    /// Adds, per object, the hash of the atoms of `beliefs` that involve it alone, and
    /// marks the objects that share an atom with another symmetric object.
    fn belief_features(&self, beliefs: &AtomSet, hash: &mut [u64], shared: &mut [bool]) {
        for a in beliefs.iter() {
            match self.involves[a.0 as usize] {
                Involves::None => {}
                Involves::One(o, key) => {
                    hash[o as usize] = hash[o as usize].wrapping_add(mix(u64::from(key)));
                }
                Involves::Many => {
                    for &(_, _, o) in &self.atom_args[a.0 as usize] {
                        shared[o as usize] = true;
                    }
                }
            }
        }
    }

    /// [`Symmetry::belief_features`] of the requests made, `requested`.
    fn request_features(&self, requested: u64, hash: &mut [u64], shared: &mut [bool]) {
        for (r, inv) in self.request_involves.iter().enumerate() {
            if requested >> r & 1 == 0 {
                continue;
            }
            match *inv {
                Involves::None => {}
                Involves::One(o, key) => {
                    // Tagged apart from atom ids.
                    let key = u64::from(key) | 1 << 40;
                    hash[o as usize] = hash[o as usize].wrapping_add(mix(key));
                }
                Involves::Many => {
                    let mut objs = Vec::new();
                    self.collect_objects(&self.requests[r], &mut objs);
                    objs.iter().for_each(|&o| shared[o as usize] = true);
                }
            }
        }
    }

    /// The sorting renaming and the ties of a state with, per symmetric object, where it
    /// `first` occurs (`u32::MAX`: nowhere), the `hash` of the atoms and requests that
    /// involve it alone, and whether it is `shared` with another symmetric object.
    fn sort(&self, first: &[u32], hash: &[u64], shared: &[bool]) -> (Perm, Vec<Vec<u16>>) {
        let mut perm = self.identity();
        let mut ties = Vec::new();
        for g in &self.groups {
            // Each object's signature, then the object: every key is distinct.
            let mut keyed: SmallVec<[(u32, u64, bool, u16); 16]> = g
                .iter()
                .map(|&o| (first[o as usize], hash[o as usize], shared[o as usize], o))
                .collect();
            keyed.sort_unstable();
            for (slot, &(_, _, _, o)) in keyed.iter().enumerate() {
                perm[o as usize] = g[slot];
            }
            // Runs of equal signatures among objects that are not interchangeable.
            let signature = |k: &(u32, u64, bool, u16)| (k.0, k.1, k.2);
            let mut i = 0;
            while i < keyed.len() {
                let mut j = i + 1;
                while j < keyed.len() && signature(&keyed[j]) == signature(&keyed[i]) {
                    j += 1;
                }
                if j - i > 1 && keyed[i].2 {
                    ties.push(g[i..j].to_vec());
                }
                i = j;
            }
        }
        (perm, ties)
    }

    /// The renamings that may take `s` to its canonical member: the sorting order, and
    /// when objects tie, that order with every arrangement of each tie (none beyond
    /// [`MAX_TIE_ORDERS`]).
    fn candidates(&self, (perm, ties): (Perm, Vec<Vec<u16>>)) -> Vec<Perm> {
        let orders: usize = ties
            .iter()
            .map(|t| (1..=t.len()).product::<usize>())
            .try_fold(1usize, |acc, k| acc.checked_mul(k))
            .unwrap_or(usize::MAX);
        if ties.is_empty() || orders > MAX_TIE_ORDERS {
            return vec![perm];
        }
        // Every order of every tie (slots within a tie are permuted after sorting).
        let mut out = Vec::new();
        let mut arrangement: Vec<Vec<u16>> = ties.clone();
        loop {
            let mut p = perm.clone();
            for (tie, arr) in ties.iter().zip(&arrangement) {
                let mut remap = self.identity();
                for (k, &slot) in tie.iter().enumerate() {
                    remap[slot as usize] = arr[k];
                }
                p.iter_mut().for_each(|x| *x = remap[*x as usize]);
            }
            out.push(p);
            if !next_arrangement(&mut arrangement) {
                break;
            }
        }
        out
    }

    /// The canonical member of `s`'s class and its fingerprint.
    pub fn canonical(&self, s: &State) -> (u64, Option<State>) {
        let candidates = self.candidates(self.sorting(s));
        if let [p] = candidates.as_slice() {
            if p.iter().enumerate().all(|(i, &x)| x as usize == i) {
                return (fingerprint(s), None);
            }
        }
        let (fp, c) = candidates
            .iter()
            .map(|p| {
                let c = self.apply(s, p);
                (fingerprint(&c), c)
            })
            .min_by_key(|(fp, _)| *fp)
            .expect("at least one candidate");
        (fp, Some(c))
    }

    /// The fingerprint of a renaming of `s` together with data about it (`extra`, given the
    /// same renaming to apply to its terms): the least over the renamings [`canonical`]
    /// tries. A model whose states are an agent state and more (a user's view of the run)
    /// stores them under it; since every renaming is applied to the whole, two states are
    /// only merged when one is a renaming of the other.
    ///
    /// [`canonical`]: Symmetry::canonical
    pub fn fingerprint_with<H: std::hash::Hash>(
        &self,
        s: &State,
        extra: impl Fn(&Renaming) -> H,
    ) -> u64 {
        self.candidates(self.sorting(s))
            .iter()
            .map(|p| {
                let r = Renaming { sym: self, perm: p };
                fingerprint(&(self.apply(s, p), extra(&r)))
            })
            .min()
            .expect("at least one candidate")
    }

    /// [`Symmetry::fingerprint_with`] of a compiled state (the same number), its renamings
    /// made part by part, each distinct part once per renaming ([`Compiled::map`]).
    pub fn fingerprint_with_compiled<'c, H: std::hash::Hash>(
        &self,
        c: &'c Compiled,
        p: &Packed<'c>,
        extra: impl Fn(&Renaming) -> H,
    ) -> u64 {
        self.candidates(self.sorting_compiled(c, p))
            .iter()
            .map(|perm| {
                let r = Renaming { sym: self, perm };
                let identity = perm.iter().enumerate().all(|(i, &x)| x as usize == i);
                let renamed = if identity {
                    *p
                } else {
                    c.map(p, self.map_id(c, perm), &r)
                };
                fingerprint(&(renamed, extra(&r)))
            })
            .min()
            .expect("at least one candidate")
    }

    /// The id of the renaming `perm` for [`Compiled::map`]: its images four bits each
    /// when every object's index fits ([`MAP_CODE`]: no lookup), else [`Compiled::map_id`].
    pub(super) fn map_id(&self, c: &Compiled, perm: &[u16]) -> u64 {
        if perm.len() <= 15 {
            perm.iter()
                .enumerate()
                .fold(MAP_CODE, |id, (i, &x)| id | u64::from(x) << (4 * i))
        } else {
            c.map_id(perm)
        }
    }

    /// The canonical fingerprint of `s`.
    pub fn fingerprint(&self, s: &State) -> u64 {
        self.canonical(s).0
    }

    /// [`Symmetry::fingerprint`] of a compiled state (the same number: a state hashes as
    /// the pair of it and nothing).
    pub fn fingerprint_compiled<'c>(&self, c: &'c Compiled, p: &Packed<'c>) -> u64 {
        self.fingerprint_with_compiled(c, p, |_| ())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn arrangements_cover_every_order_once() {
        let mut ties = vec![vec![0, 1, 2], vec![3, 4]];
        let mut seen = HashSet::new();
        loop {
            assert!(seen.insert(ties.clone()));
            if !next_arrangement(&mut ties) {
                break;
            }
        }
        assert_eq!(seen.len(), 12);
        assert_eq!(ties, vec![vec![0, 1, 2], vec![3, 4]]);
    }
}
