//! Counting in z3: the number of true Booleans as an integer and cardinality constraints,
//! shared by `.count` in ground conditions and in plan formulas.

use super::{ff, tt};
use crate::model::cond::CountCmp;
use z3::ast::{Bool, Int};

/// The number of true Booleans, as an integer.
pub(super) fn sum(bs: &[Bool]) -> Int {
    if bs.is_empty() {
        return Int::from_i64(0);
    }
    let terms: Vec<Int> = bs
        .iter()
        .map(|b| b.ite(&Int::from_i64(1), &Int::from_i64(0)))
        .collect();
    Int::add(&terms)
}

/// A cardinality constraint: the number of true `bs` compares with `n` by `cmp`.
pub fn pb(bs: &[Bool], cmp: CountCmp, n: i64) -> Bool {
    let len = bs.len() as i64;
    let holds = |k: i64| match cmp {
        CountCmp::Eq => k == n,
        CountCmp::Lt => k < n,
        CountCmp::Le => k <= n,
        CountCmp::Gt => k > n,
        CountCmp::Ge => k >= n,
        CountCmp::Ne => k != n,
    };
    if (0..=len).all(holds) {
        return tt();
    }
    if !(0..=len).any(holds) {
        return ff();
    }
    // Within 0..=len the bound fits an i32 (len is a number of atoms).
    let k = n.clamp(-1, len + 1) as i32;
    let ws: Vec<(&Bool, i32)> = bs.iter().map(|b| (b, 1)).collect();
    match cmp {
        CountCmp::Eq => Bool::pb_eq(&ws, k),
        CountCmp::Ne => Bool::pb_eq(&ws, k).not(),
        CountCmp::Lt => Bool::pb_le(&ws, k - 1),
        CountCmp::Le => Bool::pb_le(&ws, k),
        CountCmp::Gt => Bool::pb_ge(&ws, k + 1),
        CountCmp::Ge => Bool::pb_ge(&ws, k),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use z3::{SatResult, Solver};

    /// Every way `pb` can be asked, against counting on every assignment of three atoms.
    #[test]
    fn cardinality_constraints_count_exactly() {
        let bs: Vec<Bool> = (0..3).map(|i| Bool::new_const(format!("b{i}"))).collect();
        let cmps = [
            CountCmp::Eq,
            CountCmp::Lt,
            CountCmp::Le,
            CountCmp::Gt,
            CountCmp::Ge,
            CountCmp::Ne,
        ];
        let s = Solver::new();
        for cmp in cmps {
            for n in -1..=4i64 {
                let c = pb(&bs, cmp, n);
                for bits in 0u32..8 {
                    let k = bits.count_ones() as i64;
                    let expected = match cmp {
                        CountCmp::Eq => k == n,
                        CountCmp::Lt => k < n,
                        CountCmp::Le => k <= n,
                        CountCmp::Gt => k > n,
                        CountCmp::Ge => k >= n,
                        CountCmp::Ne => k != n,
                    };
                    let values: Vec<Bool> = bs
                        .iter()
                        .enumerate()
                        .map(|(i, b)| {
                            if bits >> i & 1 == 1 {
                                b.clone()
                            } else {
                                b.not()
                            }
                        })
                        .collect();
                    s.push();
                    s.assert(&c);
                    let sat = s.check_assumptions(&values) == SatResult::Sat;
                    s.pop(1);
                    assert_eq!(sat, expected, "{cmp:?} {n} with {bits:03b}");
                }
            }
        }
    }
}
