//! Initial states, as SPEC §1 defines them: every assignment of the `vary` atoms, plus the
//! `facts`, that satisfies the `constraints` and the `[invariants]`; every other atom false.
//!
//! The assignments are enumerated depth-first in atom order with three-valued evaluation of
//! the constraints on the partial assignment: a branch is cut as soon as one constraint is
//! decided false, so assignments the constraints exclude are not visited one by one (with
//! six cups, `.count(cupAt(C,_), 1)` leaves 3^6 of the 2^18 placements of cups).

use super::atoms::{AtomId, AtomSet};
use super::cond::Cond;

/// Why enumeration stopped early.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TooMany {
    /// The states found before stopping.
    pub found: usize,
}

/// Every initial state, sorted (by [`AtomSet`]'s order, so the same on every run).
///
/// `base` holds the facts; `vary` the atoms that may start either way (facts among them stay
/// true); `constraints` must all hold. Stops with [`TooMany`] past `limit` states.
pub fn enumerate(
    len: usize,
    base: &AtomSet,
    vary: &[AtomId],
    constraints: &[Cond],
    limit: usize,
) -> Result<Vec<AtomSet>, TooMany> {
    match first(len, base, vary, constraints, limit) {
        (states, true) => Ok(states),
        (states, false) => Err(TooMany {
            found: states.len(),
        }),
    }
}

/// The first `limit` initial states in the enumeration's order (the same on every run),
/// sorted, and whether they are all of them (see [`enumerate`]).
pub fn first(
    len: usize,
    base: &AtomSet,
    vary: &[AtomId],
    constraints: &[Cond],
    limit: usize,
) -> (Vec<AtomSet>, bool) {
    let mut it = Enumeration::new(len, base, vary, constraints.to_vec());
    let mut out: Vec<AtomSet> = it.by_ref().take(limit).collect();
    let all = it.next().is_none();
    out.sort();
    (out, all)
}

/// The initial states one at a time, in the enumeration's order (depth first, each varying
/// atom false before true): a search takes them as it needs them, so that a project with
/// more than it can hold is searched from the first ones, with no list of them all.
#[derive(Clone, Debug)]
pub struct Enumeration {
    free: Vec<AtomId>,
    constraints: Vec<Cond>,
    values: AtomSet,
    known: AtomSet,
    /// Per decided atom, the value tried.
    tried: Vec<bool>,
    done: bool,
}

impl Enumeration {
    /// The enumeration of [`enumerate`]'s states.
    pub fn new(len: usize, base: &AtomSet, vary: &[AtomId], constraints: Vec<Cond>) -> Self {
        let free: Vec<AtomId> = vary
            .iter()
            .copied()
            .filter(|a| !base.contains(*a))
            .collect();
        let mut known = AtomSet::empty(len);
        for i in 0..len as u32 {
            known.insert(AtomId(i));
        }
        for a in &free {
            known.remove(*a);
        }
        Enumeration {
            free,
            constraints,
            values: base.clone(),
            known,
            tried: Vec::new(),
            done: false,
        }
    }

    /// Back to the deepest atom still to be tried true; `false` when there is none.
    fn backtrack(&mut self) -> bool {
        loop {
            let Some(d) = self.tried.len().checked_sub(1) else {
                return false;
            };
            let a = self.free[d];
            if !self.tried[d] {
                self.tried[d] = true;
                self.values.set(a, true);
                return true;
            }
            self.tried.pop();
            self.values.remove(a);
            self.known.remove(a);
        }
    }
}

impl Iterator for Enumeration {
    type Item = AtomSet;

    /// Depth-first with an explicit stack, so that tens of thousands of varying atoms do
    /// not overflow the thread's stack; a branch is cut as soon as a constraint is false.
    fn next(&mut self) -> Option<AtomSet> {
        while !self.done {
            let i = self.tried.len();
            let cut = self
                .constraints
                .iter()
                .any(|c| c.eval3(&self.values, &self.known) == Some(false));
            if !cut && i < self.free.len() {
                let a = self.free[i];
                self.known.insert(a);
                self.values.set(a, false);
                self.tried.push(false);
                continue;
            }
            // Everything is known: the three-valued verdicts are the real ones.
            let found = (!cut && self.constraints.iter().all(|c| c.eval(&self.values)))
                .then(|| self.values.clone());
            self.done = !self.backtrack();
            if found.is_some() {
                return found;
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cond::CountCmp;

    #[test]
    fn enumeration_equals_brute_force_filtering() {
        // Three "cups" in three "places": atoms 3*c + l; one place per cup, and cup 0 not
        // in place 2; atom 9 is a fact.
        let len = 10;
        let mut base = AtomSet::empty(len);
        base.insert(AtomId(9));
        let vary: Vec<AtomId> = (0..10).map(AtomId).collect();
        let mut constraints: Vec<Cond> = (0..3)
            .map(|c| Cond::count((0..3).map(|l| AtomId(3 * c + l)).collect(), CountCmp::Eq, 1))
            .collect();
        constraints.push(Cond::negate(Cond::Atom(AtomId(2))));
        let got = enumerate(len, &base, &vary, &constraints, 1000).unwrap();
        let mut brute = Vec::new();
        for bits in 0u32..512 {
            let mut s = base.clone();
            (0..9)
                .filter(|i| bits >> i & 1 == 1)
                .for_each(|i| s.insert(AtomId(i)));
            if constraints.iter().all(|c| c.eval(&s)) {
                brute.push(s);
            }
        }
        brute.sort();
        assert_eq!(got.len(), 2 * 3 * 3);
        assert_eq!(got, brute);
        assert_eq!(
            enumerate(len, &base, &vary, &constraints, 5),
            Err(TooMany { found: 5 })
        );
    }
}
