//! Ground atoms and the environment state: a bitset over them.
//!
//! Every predicate of the vocabulary (PDDL predicates and mental notes) is grounded over the
//! objects of its parameter types. Atom ids are dense: a predicate owns a contiguous block,
//! and inside it the arguments are a mixed-radix number (first argument most significant), so
//! ids follow `(predicate, arguments)` order and every state prints in the same order.
//!
//! [`AtomSet`] is the state: one bit per atom, inline for up to 256 atoms, so copying and
//! hashing a state touches a few machine words and no heap for small domains. Mapping a
//! state under a permutation of interchangeable objects (symmetry reduction) is a table
//! lookup per set bit: [`AtomTable::permutation_map`] builds the table once.

use super::term::Term;
use super::universe::{ObjectId, TypeId, Universe};
use smallvec::SmallVec;
use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;

/// A ground atom's index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct AtomId(pub u32);

/// A predicate's index in the [`AtomTable`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PredId(pub u32);

#[derive(Clone, Debug)]
struct PredEntry {
    name: Arc<str>,
    params: Vec<TypeId>,
    offset: u32,
    count: u32,
}

/// Every ground atom of a project, numbered.
#[derive(Clone, Debug)]
pub struct AtomTable {
    preds: Vec<PredEntry>,
    by_name: HashMap<Arc<str>, PredId>,
    /// The strongly negated predicates (`~p`, a name of its own in the vocabulary), by the
    /// name of `p`: Jason keeps `~p` apart from `p` (different predicate indicators).
    negated_by_name: HashMap<Arc<str>, PredId>,
    /// For each type, each object's position among the objects of that type (`u32::MAX`
    /// when the object is not of the type).
    position: Vec<Vec<u32>>,
    /// For each type, its objects in id order.
    members: Vec<Vec<ObjectId>>,
    len: u32,
}

/// Ground atoms beyond this are refused: states would no longer be small.
pub const MAX_ATOMS: u64 = 1 << 24;

impl AtomTable {
    /// Grounds `predicates` (name and parameter types, in vocabulary order) over `universe`.
    /// Fails with the name of the first predicate that would push the table past
    /// [`MAX_ATOMS`].
    pub fn new(
        universe: &Universe,
        predicates: &[(Arc<str>, Vec<TypeId>)],
    ) -> Result<AtomTable, String> {
        let n_types = universe.type_count();
        let mut position = vec![vec![u32::MAX; universe.object_count()]; n_types];
        let mut members = Vec::with_capacity(n_types);
        for (t, pos) in position.iter_mut().enumerate() {
            let objs = universe.objects_of(TypeId(t as u16)).to_vec();
            for (i, o) in objs.iter().enumerate() {
                pos[o.0 as usize] = i as u32;
            }
            members.push(objs);
        }
        let mut table = AtomTable {
            preds: Vec::new(),
            by_name: HashMap::new(),
            negated_by_name: HashMap::new(),
            position,
            members,
            len: 0,
        };
        let mut total: u64 = 0;
        for (name, params) in predicates {
            let count: u64 = params
                .iter()
                .map(|t| table.members[t.0 as usize].len() as u64)
                .product();
            if total + count > MAX_ATOMS {
                return Err(name.to_string());
            }
            let id = PredId(table.preds.len() as u32);
            table.preds.push(PredEntry {
                name: name.clone(),
                params: params.clone(),
                offset: total as u32,
                count: count as u32,
            });
            table.by_name.insert(name.clone(), id);
            if let Some(positive) = name.strip_prefix('~') {
                table.negated_by_name.insert(positive.into(), id);
            }
            total += count;
        }
        table.len = total as u32;
        Ok(table)
    }

    /// Number of ground atoms.
    pub fn len(&self) -> usize {
        self.len as usize
    }

    /// Whether there is no ground atom at all.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Number of predicates.
    pub fn pred_count(&self) -> usize {
        self.preds.len()
    }

    /// The predicate with this name.
    pub fn pred(&self, name: &str) -> Option<PredId> {
        self.by_name.get(name).copied()
    }

    /// The predicate of a literal `name` or, when `negated`, `~name`.
    pub fn pred_lit(&self, name: &str, negated: bool) -> Option<PredId> {
        if negated {
            self.negated_by_name.get(name).copied()
        } else {
            self.by_name.get(name).copied()
        }
    }

    /// The predicate of a literal term (`p(..)` or `~p(..)`), if it names one.
    pub fn pred_of_literal(&self, t: &Term) -> Option<PredId> {
        self.pred_lit(t.functor()?, t.is_negated())
    }

    /// A predicate as a literal's functor and strong negation: `~p` is `("p", true)`.
    pub fn pred_literal(&self, p: PredId) -> (&str, bool) {
        let name = self.pred_name(p);
        match name.strip_prefix('~') {
            Some(positive) => (positive, true),
            None => (name, false),
        }
    }

    /// A predicate's name.
    pub fn pred_name(&self, p: PredId) -> &str {
        &self.preds[p.0 as usize].name
    }

    /// A predicate's parameter types.
    pub fn pred_params(&self, p: PredId) -> &[TypeId] {
        &self.preds[p.0 as usize].params
    }

    /// The ids of a predicate's ground atoms.
    pub fn atoms_of(&self, p: PredId) -> impl Iterator<Item = AtomId> {
        let e = &self.preds[p.0 as usize];
        (e.offset..e.offset + e.count).map(AtomId)
    }

    /// The atom `p(args)`, or `None` when an argument is not of its parameter's type or the
    /// arity is wrong.
    pub fn id(&self, p: PredId, args: &[ObjectId]) -> Option<AtomId> {
        let e = &self.preds[p.0 as usize];
        if args.len() != e.params.len() {
            return None;
        }
        let mut index: u32 = 0;
        for (t, o) in e.params.iter().zip(args) {
            let pos = *self.position[t.0 as usize].get(o.0 as usize)?;
            if pos == u32::MAX {
                return None;
            }
            index = index * self.members[t.0 as usize].len() as u32 + pos;
        }
        Some(AtomId(e.offset + index))
    }

    /// The predicate of an atom.
    pub fn pred_of(&self, a: AtomId) -> PredId {
        let i = self.preds.partition_point(|e| e.offset + e.count <= a.0);
        PredId(i as u32)
    }

    /// The predicate and arguments of an atom.
    pub fn decode(&self, a: AtomId) -> (PredId, SmallVec<[ObjectId; 4]>) {
        let p = match self.preds.binary_search_by(|e| {
            if a.0 < e.offset {
                std::cmp::Ordering::Greater
            } else if a.0 >= e.offset + e.count {
                std::cmp::Ordering::Less
            } else {
                std::cmp::Ordering::Equal
            }
        }) {
            Ok(i) => i,
            Err(_) => panic!("atom {} is not in the table", a.0),
        };
        let e = &self.preds[p];
        let mut rest = a.0 - e.offset;
        let mut args: SmallVec<[ObjectId; 4]> = SmallVec::from_elem(ObjectId(0), e.params.len());
        for (i, t) in e.params.iter().enumerate().rev() {
            let n = self.members[t.0 as usize].len() as u32;
            args[i] = self.members[t.0 as usize][(rest % n) as usize];
            rest /= n;
        }
        (PredId(p as u32), args)
    }

    /// The atom as a Jason term, e.g. `cupAt(cup1,table)`.
    pub fn term(&self, a: AtomId, universe: &Universe) -> Term {
        let (p, args) = self.decode(a);
        let (name, negated) = self.pred_literal(p);
        let args = args
            .iter()
            .map(|o| Term::atom(universe.object_name(*o)))
            .collect();
        Term::literal(name, negated, args, Vec::new())
    }

    /// The atom as Jason prints it.
    pub fn display(&self, a: AtomId, universe: &Universe) -> String {
        self.term(a, universe).to_string()
    }

    /// For a permutation of objects (`perm[o]` is the image of object `o`; it must map every
    /// object to one of the same type), the image of every atom.
    pub fn permutation_map(&self, perm: &[ObjectId]) -> Vec<AtomId> {
        (0..self.len)
            .map(|a| {
                let (p, args) = self.decode(AtomId(a));
                let image: SmallVec<[ObjectId; 4]> =
                    args.iter().map(|o| perm[o.0 as usize]).collect();
                self.id(p, &image)
                    .expect("a permutation within a type keeps every atom well-typed")
            })
            .collect()
    }
}

/// A set of ground atoms: the environment (and mental-note) part of a state.
#[derive(PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct AtomSet {
    words: SmallVec<[u64; 4]>,
}

impl Clone for AtomSet {
    /// The words copied as a slice: SmallVec's own `clone` goes through a generic
    /// `extend`, several times the cost of the copy, and searches clone belief sets at
    /// every transition.
    fn clone(&self) -> AtomSet {
        AtomSet {
            words: SmallVec::from_slice(&self.words),
        }
    }
}

impl AtomSet {
    /// The empty set over `len` atoms.
    pub fn empty(len: usize) -> AtomSet {
        AtomSet {
            words: SmallVec::from_elem(0, len.div_ceil(64)),
        }
    }

    /// Whether atom `a` is in the set.
    #[inline]
    pub fn contains(&self, a: AtomId) -> bool {
        let (w, b) = (a.0 as usize / 64, a.0 % 64);
        self.words.get(w).is_some_and(|x| x >> b & 1 == 1)
    }

    /// Adds `a`.
    #[inline]
    pub fn insert(&mut self, a: AtomId) {
        let (w, b) = (a.0 as usize / 64, a.0 % 64);
        self.words[w] |= 1 << b;
    }

    /// Removes `a`.
    #[inline]
    pub fn remove(&mut self, a: AtomId) {
        let (w, b) = (a.0 as usize / 64, a.0 % 64);
        self.words[w] &= !(1 << b);
    }

    /// Adds or removes `a`.
    #[inline]
    pub fn set(&mut self, a: AtomId, value: bool) {
        if value {
            self.insert(a)
        } else {
            self.remove(a)
        }
    }

    /// Number of atoms in the set.
    pub fn count(&self) -> usize {
        self.words.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// The atoms in the set, in id order.
    pub fn iter(&self) -> impl Iterator<Item = AtomId> + '_ {
        self.words.iter().enumerate().flat_map(|(i, &w)| {
            let mut w = w;
            std::iter::from_fn(move || {
                if w == 0 {
                    return None;
                }
                let b = w.trailing_zeros();
                w &= w - 1;
                Some(AtomId(i as u32 * 64 + b))
            })
        })
    }

    /// The set's image under an atom map from [`AtomTable::permutation_map`].
    pub fn permuted(&self, map: &[AtomId]) -> AtomSet {
        let mut out = AtomSet {
            words: SmallVec::from_elem(0, self.words.len()),
        };
        for a in self.iter() {
            out.insert(map[a.0 as usize]);
        }
        out
    }

    /// Whether the set has no atom.
    pub fn is_empty(&self) -> bool {
        self.words.iter().all(|w| *w == 0)
    }

    /// The atoms in both sets (over the first set's atoms).
    pub fn intersection(&self, other: &AtomSet) -> AtomSet {
        self.zip_with(other, |a, b| a & b)
    }

    /// The atoms in this set and not in `other` (over the first set's atoms).
    pub fn difference(&self, other: &AtomSet) -> AtomSet {
        self.zip_with(other, |a, b| a & !b)
    }

    /// This set without `removed` and with `added`.
    pub fn with_changes(&self, added: &AtomSet, removed: &AtomSet) -> AtomSet {
        let mut out = self.difference(removed);
        for (w, a) in out.words.iter_mut().zip(added.words.iter()) {
            *w |= a;
        }
        out
    }

    fn zip_with(&self, other: &AtomSet, f: impl Fn(u64, u64) -> u64) -> AtomSet {
        AtomSet {
            words: self
                .words
                .iter()
                .enumerate()
                .map(|(i, &a)| f(a, other.words.get(i).copied().unwrap_or(0)))
                .collect(),
        }
    }

    /// The raw words, for hashing and storage.
    pub fn words(&self) -> &[u64] {
        &self.words
    }
}

impl fmt::Debug for AtomSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_set().entries(self.iter().map(|a| a.0)).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bitset_basics() {
        let mut s = AtomSet::empty(130);
        assert_eq!(s.words().len(), 3);
        for a in [0, 63, 64, 129] {
            s.insert(AtomId(a));
        }
        assert!(s.contains(AtomId(64)) && !s.contains(AtomId(65)));
        assert_eq!(
            s.iter().map(|a| a.0).collect::<Vec<_>>(),
            vec![0, 63, 64, 129]
        );
        s.remove(AtomId(63));
        assert_eq!(s.count(), 3);
        let swap: Vec<AtomId> = (0..130).map(|i| AtomId(129 - i)).collect();
        assert_eq!(
            s.permuted(&swap).iter().map(|a| a.0).collect::<Vec<_>>(),
            vec![0, 65, 129]
        );
    }
}
