//! Formulas, conditions and the literals at fault, as Jason text for messages.

use crate::model::atoms::{AtomId, AtomTable};
use crate::model::cond::{Cond, CountCmp};
use crate::model::plans::Formula;
use crate::model::term::Term;
use crate::model::universe::Universe;

/// A term as the user wrote it: anonymous variables print as `_`.
pub fn term(t: &Term) -> String {
    t.map_vars(&mut |v| {
        if v.is_anonymous() {
            Term::var("_")
        } else {
            Term::Var(v.clone())
        }
    })
    .to_string()
}

/// A plan formula as Jason writes it: `used(C) & not cupAt(C,table)`.
pub fn formula(f: &Formula) -> String {
    match f {
        Formula::True => "true".into(),
        Formula::Literal(t) | Formula::Call(t) => term(t),
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
        Formula::Rel(op, a, b) => format!("{} {} {}", term(a), op.symbol(), term(b)),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn why_names_the_deciding_atoms() {
        let (a, b, c) = (AtomId(0), AtomId(1), AtomId(2));
        let holds = |x: AtomId| x == b;
        // A false conjunction: its first false part only.
        let and = Cond::And(vec![Cond::Atom(b), Cond::Atom(a), Cond::Atom(c)]);
        assert_eq!(why(&and, &holds), vec![(a, false)]);
        // A true disjunction: its first true part; a false one: every part.
        let or = Cond::Or(vec![Cond::Atom(a), Cond::Atom(b)]);
        assert_eq!(why(&or, &holds), vec![(b, true)]);
        let none = Cond::Or(vec![Cond::Atom(a), Cond::Not(Box::new(Cond::Atom(b)))]);
        assert_eq!(why(&none, &holds), vec![(a, false), (b, true)]);
        // A count: the true candidates, or every candidate when none is true.
        let count = Cond::Count {
            atoms: vec![a, b, c],
            cmp: CountCmp::Eq,
            n: 2,
        };
        assert_eq!(why(&count, &holds), vec![(b, true)]);
        let nothing = |_: AtomId| false;
        assert_eq!(
            why(&count, &nothing),
            vec![(a, false), (b, false), (c, false)]
        );
    }

    #[test]
    fn formulas_print_as_jason_writes_them() {
        use crate::model::term::Var;
        let lit = |s: &str, args: Vec<Term>| Formula::Literal(Term::structure(s, args));
        let anon = Term::Var(Var::anonymous(3));
        let f = Formula::And(
            Box::new(Formula::Or(
                Box::new(lit("used", vec![Term::var("C")])),
                Box::new(Formula::True),
            )),
            Box::new(Formula::Not(Box::new(lit(
                "cupAt",
                vec![Term::var("C"), anon],
            )))),
        );
        assert_eq!(formula(&f), "(used(C) | true) & not cupAt(C,_)");
        assert_eq!(formula(&Formula::Not(Box::new(Formula::True))), "false");
    }
}
