//! Formulas, conditions and the literals at fault, as Jason text for messages.

use crate::model::atoms::{AtomId, AtomTable};
use crate::model::cond::{Cond, CountCmp};
use crate::model::plans::Formula;
use crate::model::universe::Universe;

/// A plan formula as Jason writes it: `used(C) & not cupAt(C,table)`.
pub fn formula(f: &Formula) -> String {
    match f {
        Formula::True => "true".into(),
        Formula::Literal(t) | Formula::Call(t) => t.to_string(),
        Formula::Not(g) => match **g {
            Formula::True => "false".into(),
            Formula::Literal(_) | Formula::Call(_) => format!("not {}", formula(g)),
            _ => format!("not ({})", formula(g)),
        },
        Formula::And(a, b) => {
            let side = |x: &Formula| match x {
                Formula::Or(..) => format!("({})", formula(x)),
                _ => formula(x),
            };
            format!("{} & {}", side(a), side(b))
        }
        Formula::Or(a, b) => format!("{} | {}", formula(a), formula(b)),
        Formula::Rel(op, a, b) => format!("{a} {} {b}", op.symbol()),
    }
}

/// An atom with its truth value as a literal: `cupAt(cup1,table)`, `not used(cup1)`.
pub fn literal(atoms: &AtomTable, universe: &Universe, a: AtomId, value: bool) -> String {
    let t = atoms.display(a, universe);
    if value {
        t
    } else {
        format!("not {t}")
    }
}

/// The atoms (with their values in the state `value` gives) that decide the value of `c`
/// there: for a false conjunction its first false part, for a true disjunction its first
/// true part, otherwise every part.
pub fn why(c: &Cond, value: &dyn Fn(AtomId) -> bool) -> Vec<(AtomId, bool)> {
    let mut out = Vec::new();
    why_into(c, value, &mut out);
    let mut seen = std::collections::BTreeSet::new();
    out.retain(|(a, _)| seen.insert(*a));
    out
}

fn eval(c: &Cond, value: &dyn Fn(AtomId) -> bool) -> bool {
    match c {
        Cond::True => true,
        Cond::False => false,
        Cond::Atom(a) => value(*a),
        Cond::Not(c) => !eval(c, value),
        Cond::And(cs) => cs.iter().all(|c| eval(c, value)),
        Cond::Or(cs) => cs.iter().any(|c| eval(c, value)),
        Cond::Count { atoms, cmp, n } => {
            let k = atoms.iter().filter(|a| value(**a)).count() as i64;
            match cmp {
                CountCmp::Eq => k == *n,
                CountCmp::Lt => k < *n,
                CountCmp::Le => k <= *n,
                CountCmp::Gt => k > *n,
                CountCmp::Ge => k >= *n,
                CountCmp::Ne => k != *n,
            }
        }
    }
}

fn why_into(c: &Cond, value: &dyn Fn(AtomId) -> bool, out: &mut Vec<(AtomId, bool)>) {
    match c {
        Cond::True | Cond::False => {}
        Cond::Atom(a) => out.push((*a, value(*a))),
        Cond::Not(c) => why_into(c, value, out),
        Cond::And(cs) => match cs.iter().find(|c| !eval(c, value)) {
            Some(first_false) => why_into(first_false, value, out),
            None => cs.iter().for_each(|c| why_into(c, value, out)),
        },
        Cond::Or(cs) => match cs.iter().find(|c| eval(c, value)) {
            Some(first_true) => why_into(first_true, value, out),
            None => cs.iter().for_each(|c| why_into(c, value, out)),
        },
        Cond::Count { atoms, .. } => {
            // The true candidates say what is there; if none is, every candidate is false.
            let true_ones: Vec<AtomId> = atoms.iter().copied().filter(|a| value(*a)).collect();
            if true_ones.is_empty() {
                out.extend(atoms.iter().map(|a| (*a, false)));
            } else {
                out.extend(true_ones.into_iter().map(|a| (a, true)));
            }
        }
    }
}

/// Literals joined as a conjunction: `a & not b`.
pub fn conjunction(lits: &[String]) -> String {
    if lits.is_empty() {
        "true".into()
    } else {
        lits.join(" & ")
    }
}
