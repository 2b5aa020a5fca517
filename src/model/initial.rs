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
    let free: Vec<AtomId> = vary
        .iter()
        .copied()
        .filter(|a| !base.contains(*a))
        .collect();
    // Every atom but the free ones is known from the start: facts true, the rest false.
    let mut known = AtomSet::empty(len);
    for i in 0..len as u32 {
        known.insert(AtomId(i));
    }
    for a in &free {
        known.remove(*a);
    }
    let mut values = base.clone();
    let mut out = Vec::new();
    let mut search = Search {
        free: &free,
        constraints,
        limit,
        out: &mut out,
    };
    if search.go(&mut values, &mut known) {
        out.sort();
        Ok(out)
    } else {
        Err(TooMany { found: out.len() })
    }
}

struct Search<'a> {
    free: &'a [AtomId],
    constraints: &'a [Cond],
    limit: usize,
    out: &'a mut Vec<AtomSet>,
}

impl Search<'_> {
    /// Returns false when the limit was hit. Depth-first with an explicit stack (one entry
    /// per decided atom, holding the value tried), so that tens of thousands of varying
    /// atoms do not overflow the thread's stack.
    fn go(&mut self, values: &mut AtomSet, known: &mut AtomSet) -> bool {
        let mut tried: Vec<bool> = Vec::new();
        loop {
            let i = tried.len();
            let cut = self
                .constraints
                .iter()
                .any(|c| c.eval3(values, known) == Some(false));
            if !cut && i < self.free.len() {
                let a = self.free[i];
                known.insert(a);
                values.set(a, false);
                tried.push(false);
                continue;
            }
            if !cut {
                // Everything is known: the three-valued verdicts are the real ones.
                if self.constraints.iter().all(|c| c.eval(values)) {
                    if self.out.len() >= self.limit {
                        return false;
                    }
                    self.out.push(values.clone());
                }
            }
            // Backtrack to the deepest atom still to be tried true.
            loop {
                let Some(d) = tried.len().checked_sub(1) else {
                    return true;
                };
                let a = self.free[d];
                if !tried[d] {
                    tried[d] = true;
                    values.set(a, true);
                    break;
                }
                tried.pop();
                values.remove(a);
                known.remove(a);
            }
        }
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
