//! Ground conditions: formulas over atom ids, evaluated on an [`AtomSet`].
//!
//! PDDL preconditions and `when` conditions, and the manifest's constraints and invariants,
//! are compiled to this one form once (quantifiers expanded over the typed objects, equality
//! and `.count` bounds resolved), so evaluating them in the search is a walk over a small
//! tree. Three-valued evaluation over a partial assignment lets the initial-state enumerator
//! prune assignments that can no longer satisfy a constraint.

use super::atoms::{AtomId, AtomSet};

/// How `.count(Query, N)` compares the number of true atoms with `N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CountCmp {
    /// Exactly `n` (`.count(q, N)`, `.count(q, X) & X == n`).
    Eq,
    /// Fewer than `n`.
    Lt,
    /// At most `n`.
    Le,
    /// More than `n`.
    Gt,
    /// At least `n`.
    Ge,
    /// Not `n`.
    Ne,
}

impl CountCmp {
    fn holds(self, count: i64, n: i64) -> bool {
        match self {
            CountCmp::Eq => count == n,
            CountCmp::Lt => count < n,
            CountCmp::Le => count <= n,
            CountCmp::Gt => count > n,
            CountCmp::Ge => count >= n,
            CountCmp::Ne => count != n,
        }
    }
}

/// A ground condition.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Cond {
    /// Always holds.
    True,
    /// Never holds.
    False,
    /// The atom is in the state.
    Atom(AtomId),
    /// Negation (closed world: an atom not in the state is false).
    Not(Box<Cond>),
    /// Every part holds.
    And(Vec<Cond>),
    /// Some part holds.
    Or(Vec<Cond>),
    /// The number of atoms in the state among `atoms` compares with `n` by `cmp`.
    Count {
        /// The candidate atoms.
        atoms: Vec<AtomId>,
        /// The comparison.
        cmp: CountCmp,
        /// The bound.
        n: i64,
    },
}

impl Cond {
    /// `a & b`, simplified.
    pub fn and(parts: Vec<Cond>) -> Cond {
        let mut out = Vec::with_capacity(parts.len());
        for p in parts {
            match p {
                Cond::True => {}
                Cond::False => return Cond::False,
                Cond::And(inner) => out.extend(inner),
                other => out.push(other),
            }
        }
        match out.len() {
            0 => Cond::True,
            1 => out.pop().unwrap_or(Cond::True),
            _ => Cond::And(out),
        }
    }

    /// `a | b`, simplified.
    pub fn or(parts: Vec<Cond>) -> Cond {
        let mut out = Vec::with_capacity(parts.len());
        for p in parts {
            match p {
                Cond::False => {}
                Cond::True => return Cond::True,
                Cond::Or(inner) => out.extend(inner),
                other => out.push(other),
            }
        }
        match out.len() {
            0 => Cond::False,
            1 => out.pop().unwrap_or(Cond::False),
            _ => Cond::Or(out),
        }
    }

    /// `not a`, simplified.
    pub fn negate(c: Cond) -> Cond {
        match c {
            Cond::True => Cond::False,
            Cond::False => Cond::True,
            Cond::Not(inner) => *inner,
            other => Cond::Not(Box::new(other)),
        }
    }

    /// A `.count` bound, decided at once when the candidates alone settle it.
    pub fn count(atoms: Vec<AtomId>, cmp: CountCmp, n: i64) -> Cond {
        let max = atoms.len() as i64;
        let always = (0..=max).all(|k| cmp.holds(k, n));
        let never = (0..=max).all(|k| !cmp.holds(k, n));
        if always {
            Cond::True
        } else if never {
            Cond::False
        } else {
            Cond::Count { atoms, cmp, n }
        }
    }

    /// Whether the condition holds in `s`.
    pub fn eval(&self, s: &AtomSet) -> bool {
        match self {
            Cond::True => true,
            Cond::False => false,
            Cond::Atom(a) => s.contains(*a),
            Cond::Not(c) => !c.eval(s),
            Cond::And(cs) => cs.iter().all(|c| c.eval(s)),
            Cond::Or(cs) => cs.iter().any(|c| c.eval(s)),
            Cond::Count { atoms, cmp, n } => {
                let k = atoms.iter().filter(|a| s.contains(**a)).count() as i64;
                cmp.holds(k, *n)
            }
        }
    }

    /// Kleene evaluation over a partial assignment: atoms in `known` have the value they
    /// have in `values`, the others are unknown. `None` means "depends on the unknown atoms".
    pub fn eval3(&self, values: &AtomSet, known: &AtomSet) -> Option<bool> {
        match self {
            Cond::True => Some(true),
            Cond::False => Some(false),
            Cond::Atom(a) => known.contains(*a).then(|| values.contains(*a)),
            Cond::Not(c) => c.eval3(values, known).map(|v| !v),
            Cond::And(cs) => {
                let mut unknown = false;
                for c in cs {
                    match c.eval3(values, known) {
                        Some(false) => return Some(false),
                        None => unknown = true,
                        Some(true) => {}
                    }
                }
                (!unknown).then_some(true)
            }
            Cond::Or(cs) => {
                let mut unknown = false;
                for c in cs {
                    match c.eval3(values, known) {
                        Some(true) => return Some(true),
                        None => unknown = true,
                        Some(false) => {}
                    }
                }
                (!unknown).then_some(false)
            }
            Cond::Count { atoms, cmp, n } => {
                let (mut t, mut u) = (0i64, 0i64);
                for a in atoms {
                    if !known.contains(*a) {
                        u += 1;
                    } else if values.contains(*a) {
                        t += 1;
                    }
                }
                let possible: Vec<bool> = (t..=t + u).map(|k| cmp.holds(k, *n)).collect();
                if possible.iter().all(|&b| b) {
                    Some(true)
                } else if possible.iter().all(|&b| !b) {
                    Some(false)
                } else {
                    None
                }
            }
        }
    }

    /// Every atom the condition reads, in order of first occurrence.
    pub fn atoms(&self) -> Vec<AtomId> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms(&self, out: &mut Vec<AtomId>) {
        match self {
            Cond::True | Cond::False => {}
            Cond::Atom(a) => {
                if !out.contains(a) {
                    out.push(*a)
                }
            }
            Cond::Not(c) => c.collect_atoms(out),
            Cond::And(cs) | Cond::Or(cs) => cs.iter().for_each(|c| c.collect_atoms(out)),
            Cond::Count { atoms, .. } => {
                for a in atoms {
                    if !out.contains(a) {
                        out.push(*a)
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(len: usize, atoms: &[u32]) -> AtomSet {
        let mut s = AtomSet::empty(len);
        atoms.iter().for_each(|a| s.insert(AtomId(*a)));
        s
    }

    #[test]
    fn simplification_and_evaluation() {
        assert_eq!(
            Cond::and(vec![Cond::True, Cond::Atom(AtomId(1))]),
            Cond::Atom(AtomId(1))
        );
        assert_eq!(
            Cond::or(vec![Cond::True, Cond::Atom(AtomId(1))]),
            Cond::True
        );
        assert_eq!(
            Cond::negate(Cond::negate(Cond::Atom(AtomId(2)))),
            Cond::Atom(AtomId(2))
        );
        assert_eq!(Cond::count(vec![AtomId(0)], CountCmp::Le, 5), Cond::True);
        assert_eq!(Cond::count(vec![AtomId(0)], CountCmp::Eq, 2), Cond::False);
        let one = Cond::count(vec![AtomId(0), AtomId(1), AtomId(2)], CountCmp::Eq, 1);
        assert!(one.eval(&set(3, &[1])));
        assert!(!one.eval(&set(3, &[0, 1])));
    }

    #[test]
    fn three_valued_evaluation_is_sound_and_total_when_everything_is_known() {
        let one = Cond::count(vec![AtomId(0), AtomId(1), AtomId(2)], CountCmp::Eq, 1);
        let c = Cond::and(vec![
            one,
            Cond::or(vec![
                Cond::Atom(AtomId(3)),
                Cond::negate(Cond::Atom(AtomId(0))),
            ]),
        ]);
        // Every partial assignment over 4 atoms: known mask x values.
        for known_bits in 0u32..16 {
            for value_bits in 0u32..16 {
                let known = set(
                    4,
                    &(0..4)
                        .filter(|i| known_bits >> i & 1 == 1)
                        .collect::<Vec<_>>(),
                );
                let values = set(
                    4,
                    &(0..4)
                        .filter(|i| value_bits >> i & 1 == 1 && known_bits >> i & 1 == 1)
                        .collect::<Vec<_>>(),
                );
                let verdict = c.eval3(&values, &known);
                let completions: Vec<bool> = (0u32..16)
                    .filter(|full| (full & known_bits) == (value_bits & known_bits))
                    .map(|full| {
                        c.eval(&set(
                            4,
                            &(0..4).filter(|i| full >> i & 1 == 1).collect::<Vec<_>>(),
                        ))
                    })
                    .collect();
                // Sound: a decided verdict is the value of every completion (Kleene logic may
                // leave undecided what the completions happen to agree on).
                if let Some(v) = verdict {
                    assert!(completions.iter().all(|&x| x == v));
                }
                if known_bits == 15 {
                    assert_eq!(verdict, Some(completions[0]));
                }
            }
        }
    }
}
