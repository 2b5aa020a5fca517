//! Formula evaluation (`Cond::eval`, `Cond::eval3`): agrees with the formula's truth table.
//!
//! Formulas are trees of depth at most 2 over three atoms: `true`, `false`, atoms, `not`,
//! binary `&` and `|`, and `.count` leaves (any subset of the atoms, any comparison, a bound
//! 0 to 3), as a heap-ordered array of [`NODES`] codes. Each is built twice, as the raw tree
//! and through the simplifying constructors (`Cond::and`, `Cond::or`, `Cond::negate`,
//! `Cond::count`), and both are compared with a reference evaluator on all 8 states; `eval3`
//! on all 27 partial assignments must equal `eval` when every atom is known, and be sound
//! otherwise (`Some(v)` only if every completion gives `v`).

use crate::model::atoms::{AtomId, AtomSet};
use crate::model::cond::{Cond, CountCmp};

/// Atoms the formulas range over.
pub const ATOMS: usize = 3;
/// Nodes of a tree of depth at most 2.
pub const NODES: usize = 7;
const TRUE: u16 = 0;
const FALSE: u16 = 1;
const ATOM: u16 = 2; // 2, 3, 4
const NOT: u16 = 5;
const AND: u16 = 6;
const OR: u16 = 7;
const COUNT: u16 = 8;
/// `.count` leaves: atom subset (8) x comparison (6) x bound (4).
const COUNTS: u16 = 8 * 6 * 4;
/// Node codes.
pub const CODES: u16 = COUNT + COUNTS;
/// Codes of the leaves that are not `.count`s.
pub const PLAIN_LEAVES: u16 = NOT;

const CMPS: [CountCmp; 6] = [
    CountCmp::Eq,
    CountCmp::Lt,
    CountCmp::Le,
    CountCmp::Gt,
    CountCmp::Ge,
    CountCmp::Ne,
];

/// A formula as node codes; unused nodes are 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallCond {
    nodes: [u16; NODES],
}

fn arity(code: u16) -> usize {
    match code {
        NOT => 1,
        AND | OR => 2,
        _ => 0,
    }
}

fn used_nodes(nodes: &[u16; NODES]) -> [bool; NODES] {
    let mut used = [false; NODES];
    used[0] = true;
    for i in 0..3 {
        if used[i] {
            for k in 0..arity(nodes[i]) {
                used[2 * i + 1 + k] = true;
            }
        }
    }
    used
}

fn count_parts(code: u16) -> (u8, CountCmp, i64) {
    let k = code - COUNT;
    ((k / 24) as u8, CMPS[(k / 4 % 6) as usize], i64::from(k % 4))
}

fn holds(cmp: CountCmp, k: i64, n: i64) -> bool {
    match cmp {
        CountCmp::Eq => k == n,
        CountCmp::Lt => k < n,
        CountCmp::Le => k <= n,
        CountCmp::Gt => k > n,
        CountCmp::Ge => k >= n,
        CountCmp::Ne => k != n,
    }
}

impl SmallCond {
    /// The formula these codes spell, if canonical: codes in range, connectives above
    /// depth 2 only, unused nodes 0.
    pub fn new(nodes: [u16; NODES]) -> Option<SmallCond> {
        let used = used_nodes(&nodes);
        for i in 0..NODES {
            let ok = if used[i] {
                nodes[i] < CODES && (i < 3 || arity(nodes[i]) == 0)
            } else {
                nodes[i] == 0
            };
            if !ok {
                return None;
            }
        }
        Some(SmallCond { nodes })
    }

    /// A canonical formula from any codes: codes reduced into range, connectives at depth
    /// 2 turned into leaves, unused nodes cleared (every formula is the image of itself).
    pub fn normalized(raw: [u16; NODES]) -> SmallCond {
        let mut nodes = raw.map(|c| c % CODES);
        for n in nodes.iter_mut().skip(3) {
            if arity(*n) > 0 {
                *n = TRUE;
            }
        }
        let used = used_nodes(&nodes);
        for i in 0..NODES {
            if !used[i] {
                nodes[i] = 0;
            }
        }
        SmallCond { nodes }
    }

    /// Whether the formula has a `.count` leaf.
    pub fn has_count(&self) -> bool {
        let used = used_nodes(&self.nodes);
        (0..NODES).any(|i| used[i] && self.nodes[i] >= COUNT)
    }

    /// The raw tree, node for node.
    pub fn raw(&self) -> Cond {
        self.raw_at(0)
    }

    fn raw_at(&self, i: usize) -> Cond {
        let c = self.nodes[i];
        match c {
            TRUE => Cond::True,
            FALSE => Cond::False,
            NOT => Cond::Not(Box::new(self.raw_at(2 * i + 1))),
            AND => Cond::And(vec![self.raw_at(2 * i + 1), self.raw_at(2 * i + 2)]),
            OR => Cond::Or(vec![self.raw_at(2 * i + 1), self.raw_at(2 * i + 2)]),
            _ if c < NOT => Cond::Atom(AtomId(u32::from(c - ATOM))),
            _ => {
                let (mask, cmp, n) = count_parts(c);
                Cond::Count {
                    atoms: atoms_of(mask),
                    cmp,
                    n,
                }
            }
        }
    }

    /// The tree built with the simplifying constructors.
    pub fn simplified(&self) -> Cond {
        self.simplified_at(0)
    }

    fn simplified_at(&self, i: usize) -> Cond {
        let c = self.nodes[i];
        match c {
            NOT => Cond::negate(self.simplified_at(2 * i + 1)),
            AND => Cond::and(vec![
                self.simplified_at(2 * i + 1),
                self.simplified_at(2 * i + 2),
            ]),
            OR => Cond::or(vec![
                self.simplified_at(2 * i + 1),
                self.simplified_at(2 * i + 2),
            ]),
            _ if c >= COUNT => {
                let (mask, cmp, n) = count_parts(c);
                Cond::count(atoms_of(mask), cmp, n)
            }
            _ => self.raw_at(i),
        }
    }

    /// The reference: the formula's value in the state whose atom `k` is bit `k` of `state`.
    pub fn reference(&self, state: u8) -> bool {
        self.reference_at(0, state)
    }

    fn reference_at(&self, i: usize, state: u8) -> bool {
        let c = self.nodes[i];
        match c {
            TRUE => true,
            FALSE => false,
            NOT => !self.reference_at(2 * i + 1, state),
            AND => self.reference_at(2 * i + 1, state) && self.reference_at(2 * i + 2, state),
            OR => self.reference_at(2 * i + 1, state) || self.reference_at(2 * i + 2, state),
            _ if c < NOT => state >> (c - ATOM) & 1 == 1,
            _ => {
                let (mask, cmp, n) = count_parts(c);
                holds(cmp, i64::from((mask & state).count_ones()), n)
            }
        }
    }
}

fn atoms_of(mask: u8) -> Vec<AtomId> {
    (0..ATOMS as u32)
        .filter(|k| mask >> k & 1 == 1)
        .map(AtomId)
        .collect()
}

/// The state whose atom `k` is in it when bit `k` of `bits` is set.
pub fn state(bits: u8) -> AtomSet {
    let mut s = AtomSet::empty(ATOMS);
    for a in atoms_of(bits) {
        s.insert(a);
    }
    s
}

/// Every canonical formula whose nodes at depth 2 are plain leaves (no `.count`): `.count`
/// leaves at depth 0 and 1 only.
pub fn all_conds() -> Vec<SmallCond> {
    let depth1 = |at: usize, out: &mut Vec<[u16; NODES]>, base: [u16; NODES]| {
        for c in 0..CODES {
            let mut n = base;
            n[at] = c;
            match arity(c) {
                0 => out.push(n),
                k => {
                    let (l, r) = (2 * at + 1, 2 * at + 2);
                    for x in 0..PLAIN_LEAVES {
                        for y in 0..if k == 2 { PLAIN_LEAVES } else { 1 } {
                            let mut m = n;
                            m[l] = x;
                            if k == 2 {
                                m[r] = y;
                            }
                            out.push(m);
                        }
                    }
                }
            }
        }
    };
    let mut subtrees1 = Vec::new();
    depth1(1, &mut subtrees1, [0; NODES]);
    let mut subtrees2 = Vec::new();
    depth1(2, &mut subtrees2, [0; NODES]);
    let mut out = Vec::new();
    for c in 0..CODES {
        match arity(c) {
            0 => out.push([c, 0, 0, 0, 0, 0, 0]),
            1 => {
                for s in &subtrees1 {
                    let mut n = *s;
                    n[0] = c;
                    out.push(n);
                }
            }
            _ => {
                for s in &subtrees1 {
                    for t in &subtrees2 {
                        let mut n = [0; NODES];
                        for k in 0..NODES {
                            n[k] = s[k] | t[k];
                        }
                        n[0] = c;
                        out.push(n);
                    }
                }
            }
        }
    }
    out.into_iter()
        .map(|n| SmallCond::new(n).expect("the enumeration builds canonical formulas"))
        .collect()
}

/// The evaluators under test.
#[derive(Clone, Copy)]
pub struct Evaluators {
    /// `Cond::eval`.
    pub eval: fn(&Cond, &AtomSet) -> bool,
    /// `Cond::eval3`.
    pub eval3: fn(&Cond, &AtomSet, &AtomSet) -> Option<bool>,
}

impl Evaluators {
    /// The crate's.
    pub fn real() -> Evaluators {
        Evaluators {
            eval: Cond::eval,
            eval3: Cond::eval3,
        }
    }
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// The formula is true in some state and false in another.
    pub contingent: bool,
    /// `eval3` left some partial assignment undecided.
    pub undecided: bool,
}

/// The property, for the formula `f` and the evaluators `k`: on each of the 8 states
/// `eval` of the raw and of the simplified tree equals the reference; on each of the 27
/// partial assignments (`known` atoms, with `values` among them) `eval3` is sound, and
/// equals `eval` when all atoms are known.
pub fn eval_agrees_with_truth_table(f: &SmallCond, k: Evaluators) -> Result<Seen, String> {
    let (raw, simple) = (f.raw(), f.simplified());
    let mut table = [false; 8];
    for (bits, value) in table.iter_mut().enumerate() {
        let bits = bits as u8;
        *value = f.reference(bits);
        let s = state(bits);
        for (what, c) in [("raw", &raw), ("simplified", &simple)] {
            let got = (k.eval)(c, &s);
            if got != *value {
                return Err(format!(
                    "{what} {c:?} in state {bits:03b}: eval gives {got}, the truth table {value}"
                ));
            }
        }
    }
    let mut undecided = false;
    for known in 0u8..8 {
        for values in 0u8..8 {
            if values & !known != 0 {
                continue;
            }
            let completions: Vec<bool> = (0u8..8)
                .filter(|full| full & known == values)
                .map(|full| table[full as usize])
                .collect();
            for (what, c) in [("raw", &raw), ("simplified", &simple)] {
                let got = (k.eval3)(c, &state(values), &state(known));
                match got {
                    None if known == 7 => {
                        return Err(format!(
                            "{what} {c:?}: eval3 undecided with every atom known ({values:03b})"
                        ))
                    }
                    None => undecided = true,
                    Some(v) if completions.iter().any(|&x| x != v) => {
                        return Err(format!(
                            "{what} {c:?}: eval3 says {v} with known {known:03b} = {values:03b}, but a completion gives {}",
                            !v
                        ))
                    }
                    Some(_) => {}
                }
            }
        }
    }
    Ok(Seen {
        contingent: table.iter().any(|&v| v) && table.iter().any(|&v| !v),
        undecided,
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// Formulas of depth ≤ 2 over 3 atoms (with `.count` leaves), all 8 states, all 27
    /// partial assignments.
    #[kani::proof]
    #[kani::unwind(9)]
    fn evaluation_agrees_with_the_truth_table() {
        let f = SmallCond::new(kani::any());
        kani::assume(f.is_some());
        let f = f.unwrap();
        let seen = eval_agrees_with_truth_table(&f, Evaluators::real());
        kani::cover!(f.has_count(), "a formula with a .count leaf");
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.contingent),
            "a contingent formula"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.undecided),
            "eval3 leaves something undecided"
        );
        assert!(seen.is_ok());
    }
}
