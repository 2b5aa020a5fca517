//! The pure internal actions (`jason.stdlib`), one function per action, and [`call`], which
//! dispatches to them. Each gives every answer in Jason's order as substitutions extending
//! the caller's (see the module documentation for the conventions they share).

use super::parse::parse_simple;
use super::{
    elements, index_of, jason_text, java_int, java_substring, string_or_text, truth, unified,
    utf16_len, MAX_RANGE_ANSWERS,
};
use crate::model::{unify, Substitution, Term};
use std::cmp::Ordering;
use std::collections::BTreeSet;

/// Runs the pure internal action `name` (with its dot: `.member`) on `args`.
///
/// `args` are evaluated (no arithmetic left) but may hold variables bound in `s`. Returns
/// `None` when `name` is not in [`PURE`]; otherwise every answer, each `s` extended, in the
/// order Jason's iterator gives them (an empty vector: the action fails, also when Jason
/// would throw, e.g. on a wrong arity or argument).
///
/// [`PURE`]: super::PURE
pub fn call(name: &str, args: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let a: Vec<Term> = args.iter().map(|t| s.apply(t)).collect();
    let answers = match name {
        ".member" => member(&a, s),
        ".length" => length(&a, s),
        ".nth" => nth(&a, s),
        ".concat" => concat(&a, s),
        ".reverse" => reverse(&a, s),
        ".sort" => sort(&a, s),
        ".min" => extreme(&a, s, Ordering::Greater),
        ".max" => extreme(&a, s, Ordering::Less),
        ".empty" => type_test(&a, s, |t| match t {
            Term::Nil => true,
            Term::Str(x) => x.is_empty(),
            // `empty.java`: a non-empty list, or anything without a size.
            _ => false,
        }),
        ".list" => type_test(&a, s, Term::is_list),
        ".ground" => type_test(&a, s, Term::is_ground),
        ".atom" => type_test(&a, s, |t| matches!(t, Term::Atom(_))),
        ".number" => type_test(&a, s, |t| matches!(t, Term::Num(_))),
        ".string" => type_test(&a, s, |t| matches!(t, Term::Str(_))),
        // Jason's lists are `Structure`s and its atoms are not (`Atom.isStructure` is false).
        // A literal Jason built as a `LiteralImpl` without arguments or annotations would be a
        // structure there; the model cannot tell it from an atom.
        ".structure" => type_test(&a, s, |t| {
            matches!(t, Term::Struct(_) | Term::Nil | Term::Cons(_))
        }),
        ".literal" => type_test(&a, s, Term::is_literal),
        ".substring" => substring(&a, s),
        ".term2string" => term2string(&a, s),
        ".range" => range(&a, s),
        ".difference" => set_op(&a, s, SetOp::Difference),
        ".intersection" => set_op(&a, s, SetOp::Intersection),
        ".union" => set_op(&a, s, SetOp::Union),
        ".add_nested_source" => {
            let [t, source, out] = &a[..] else {
                return None;
            };
            Some(unified(s, &[(&nested_source(t, source), out)]))
        }
        ".remove_source_annot" => {
            let [t, out] = &a[..] else { return None };
            let plain = match t.list_elements() {
                Some((elems, None)) => Term::list(elems.iter().map(without_sources).collect()),
                _ => without_sources(t),
            };
            Some(unified(s, &[(&plain, out)]))
        }
        _ => return None,
    };
    Some(answers.unwrap_or_default())
}

/// `add_nested_source.addAnnotToList`: `source(Source)` added to a literal, the sources it
/// had nested inside that one (`b[source(a)]` gives `b[source(Source)[source(a)]]`); to each
/// element of a list; any other term as it is.
pub fn nested_source(t: &Term, source: &Term) -> Term {
    if let Some((elems, tail)) = t.list_elements() {
        let elems = elems.iter().map(|e| nested_source(e, source)).collect();
        return Term::list_with_tail(elems, tail.unwrap_or(Term::Nil));
    }
    let Some((f, negated, args, annots)) = t.lit_view() else {
        return t.clone();
    };
    let (sources, mut rest): (Vec<Term>, Vec<Term>) = annots
        .iter()
        .cloned()
        .partition(|a| a.functor() == Some("source"));
    // `Pred.createSource(source).addAnnots(result.getAnnots("source"))`.
    let new = Term::literal("source", false, vec![source.clone()], sources);
    rest.push(new);
    Term::literal(f, negated, args.to_vec(), rest)
}

/// `remove_source_annot.processTerm` (`Literal.noSource`): a literal without its `source`
/// annotations; any other term as it is.
fn without_sources(t: &Term) -> Term {
    match t.lit_view() {
        Some((f, negated, args, annots)) => Term::literal(
            f,
            negated,
            args.to_vec(),
            annots
                .iter()
                .filter(|a| a.functor() != Some("source"))
                .cloned()
                .collect(),
        ),
        None => t.clone(),
    }
}

/// `member.java`: every element that unifies with the first argument, in list order.
fn member(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [x, l] = a else { return None };
    let answers = elements(l)?
        .iter()
        .filter_map(|e| {
            let mut s = s.clone();
            unify(x, e, &mut s).then_some(s)
        })
        .collect();
    Some(answers)
}

/// `length.java`: the number of elements of a list or of UTF-16 units of a string.
fn length(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [l, n] = a else { return None };
    let size = match l {
        Term::Str(x) => utf16_len(x),
        _ => match elements(l) {
            Some(e) => e.len(),
            // `getSize` gives null: the action returns false.
            None => return Some(Vec::new()),
        },
    };
    Some(unified(s, &[(n, &Term::int(size as i64))]))
}

/// `nth.java`: the element at a 0-based index (truncated to `int`; out of bounds throws), or,
/// for an unbound index, every position whose element unifies. A string is indexed by the
/// bytes of its UTF-8 form, each as a one-byte string (`getBytes()`; a non-ASCII byte
/// decodes to U+FFFD).
fn nth(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [i, l, x] = a else { return None };
    let items: Vec<Term> = match l {
        Term::Str(text) => text
            .bytes()
            .map(|b| {
                let c = if b.is_ascii() {
                    char::from(b)
                } else {
                    '\u{FFFD}'
                };
                Term::string(c.encode_utf8(&mut [0; 4]))
            })
            .collect(),
        _ => elements(l)?,
    };
    match i {
        Term::Num(n) => {
            let index = usize::try_from(java_int(n.value())).ok()?;
            Some(unified(s, &[(x, items.get(index)?)]))
        }
        Term::Var(_) => {
            let answers = items
                .iter()
                .enumerate()
                .filter_map(|(k, e)| {
                    let mut s = s.clone();
                    if !unify(x, e, &mut s) {
                        return None;
                    }
                    // Jason ignores whether the index unifies (it can fail only when the
                    // index variable is also the element: `.nth(I, [5], I)`).
                    unify(i, &Term::int(k as i64), &mut s);
                    Some(s)
                })
                .collect();
            Some(answers)
        }
        _ => None,
    }
}

/// `concat.java`. When the first argument is a list, all but the last must be lists and are
/// appended (`ListTermImpl.concat`, which appends nothing more once the result ends in an
/// unbound tail); the last must be a list or a variable. Otherwise the plain texts of all but
/// the last are joined (`getPlainValue`: a string's text, a quoted atom without its quotes,
/// any other term's Jason text) and unified with the last, itself turned into the string of
/// its text unless it is a string or a variable (so `.concat("a", "b", ab)` succeeds).
fn concat(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let (last, _) = a.split_last()?;
    // Between the first and the last (none when there are one or two arguments).
    let middle = &a[1..a.len().max(2) - 1];
    if a[0].is_list() {
        if !last.is_var() && !last.is_list() {
            return None;
        }
        let mut result = a[0].clone();
        for next in middle {
            if !next.is_list() {
                return None;
            }
            let (elems, tail) = result.list_elements().expect("a list");
            if tail.is_none() {
                result = Term::list_with_tail(elems, next.clone());
            }
        }
        return Some(unified(s, &[(&result, last)]));
    }
    let mut text = plain_value(&a[0]);
    for t in middle {
        text.push_str(&plain_value(t));
    }
    let last = match last {
        Term::Str(_) | Term::Var(_) => last.clone(),
        _ => Term::string(&jason_text(last)),
    };
    Some(unified(s, &[(&Term::string(&text), &last)]))
}

/// `concat.getPlainValue`.
fn plain_value(t: &Term) -> String {
    match t {
        Term::Str(x) => x.to_string(),
        Term::Atom(x) if x.len() >= 2 && x.starts_with('\'') && x.ends_with('\'') => {
            x[1..x.len() - 1].to_string()
        }
        _ => jason_text(t),
    }
}

/// `reverse.java`: a list reversed with its tail kept (`[a,b|T]` gives `[b,a|T]`), or a
/// string reversed by characters (`StringBuilder.reverse` keeps surrogate pairs whole).
fn reverse(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [l, r] = a else { return None };
    let reversed = match l {
        Term::Nil | Term::Cons(_) => {
            if !r.is_var() && !r.is_list() {
                return None;
            }
            let (mut elems, tail) = l.list_elements().expect("a list");
            elems.reverse();
            Term::list_with_tail(elems, tail.unwrap_or(Term::Nil))
        }
        Term::Str(x) => {
            if !r.is_var() && !matches!(r, Term::Str(_)) {
                return None;
            }
            Term::string(&x.chars().rev().collect::<String>())
        }
        _ => return None,
    };
    Some(unified(s, &[(&reversed, r)]))
}

/// `sort.java`: `Collections.sort` by Jason's term order (the model's `Ord`), duplicates
/// kept, an unbound tail dropped.
fn sort(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [l, r] = a else { return None };
    let mut elems = elements(l)?;
    elems.sort();
    Some(unified(s, &[(&Term::list(elems), r)]))
}

/// `min.java` / `max.java` with two arguments: the first element that no later one beats in
/// Jason's term order (`replace` is the ordering of the current best against an element
/// that makes the element the new best). An empty list fails.
fn extreme(a: &[Term], s: &Substitution, replace: Ordering) -> Option<Vec<Substitution>> {
    let [l, m] = a else { return None };
    let elems = elements(l)?;
    let Some(mut best) = elems.first() else {
        return Some(Vec::new());
    };
    for t in &elems[1..] {
        if best.cmp(t) == replace {
            best = t;
        }
    }
    Some(unified(s, &[(m, best)]))
}

/// The one-argument tests (`list.java`, `ground.java`, `atom.java`, ...).
fn type_test(
    a: &[Term],
    s: &Substitution,
    test: impl Fn(&Term) -> bool,
) -> Option<Vec<Substitution>> {
    let [t] = a else { return None };
    Some(truth(test(t), s))
}

/// `substring.java`. With two arguments: whether the first's text occurs in the second's.
/// With a bound position and an unbound first (or second) argument: the substring of the
/// other from that position to the fourth argument or the end. Otherwise every position
/// (UTF-16) where the first occurs in the second, unified with the third argument, and with
/// the fourth, if any, unified with `position + length - 1` (Jason's arithmetic: the index
/// of the last character, `(pos-2)+s0.length()` after `pos++`).
fn substring(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    if !(2..=4).contains(&a.len()) {
        return None;
    }
    let (s0, s1) = (string_or_text(&a[0]), string_or_text(&a[1]));
    if a.len() == 2 {
        return Some(truth(s1.contains(&s0), s));
    }
    let pos = match &a[2] {
        Term::Num(n) => Some(java_int(n.value())),
        _ => None,
    };
    if let Some(start) = pos {
        for (var, text) in [(&a[0], &s1), (&a[1], &s0)] {
            if var.is_var() {
                let end = match a.get(3) {
                    Some(Term::Num(n)) => java_int(n.value()),
                    _ => utf16_len(text) as i32,
                };
                let sub = Term::string(&java_substring(text, start, end)?);
                return Some(unified(s, &[(var, &sub)]));
            }
        }
    }
    let (hay, needle): (Vec<u16>, Vec<u16>) =
        (s1.encode_utf16().collect(), s0.encode_utf16().collect());
    let mut answers = Vec::new();
    let mut from = 0;
    while from < hay.len() {
        let Some(found) = index_of(&hay, &needle, from) else {
            break;
        };
        from = found + 1;
        let mut pairs = vec![(a[2].clone(), Term::int(found as i64))];
        if let Some(e) = a.get(3) {
            let last = found as i64 - 1 + needle.len() as i64;
            pairs.push((e.clone(), Term::int(last)));
        }
        let refs: Vec<(&Term, &Term)> = pairs.iter().map(|(x, y)| (x, y)).collect();
        answers.extend(unified(s, &refs));
    }
    Some(answers)
}

/// `term2string.java`. A bound term against a string: whether its Jason text is that string;
/// against an unbound variable: the string of its text. An unbound first argument gets the
/// second parsed as a term (the text of a non-string): here only when [`parse_simple`]
/// can read it (numbers, strings without `\`, atoms, structures and proper lists made of
/// these). Any other text has no answer here, where Jason's parser may read more (variables,
/// `~`, annotations, arithmetic, which it evaluates) or, when it cannot parse, binds the
/// variable to an atom made of the whole text (`"hello world"`). Two unbound variables are
/// unified, as Jason's parse of a variable's name gives back that variable.
fn term2string(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    let [t, st] = a else { return None };
    match (t, st) {
        (Term::Var(_), Term::Var(_)) => Some(unified(s, &[(t, st)])),
        (Term::Var(_), _) => match parse_simple(&string_or_text(st)) {
            Some(parsed) => Some(unified(s, &[(t, &parsed)])),
            None => Some(Vec::new()),
        },
        (_, Term::Str(text)) => Some(truth(jason_text(t) == **text, s)),
        (_, Term::Var(_)) => Some(unified(s, &[(&Term::string(&jason_text(t)), st)])),
        // "invalid case of term2string".
        _ => None,
    }
}

/// `range.java`: with a bound first argument, whether it lies between start and end (the
/// step is ignored); with an unbound one, start, start+step, ... while not past the end,
/// all truncated to `int`. See [`MAX_RANGE_ANSWERS`].
fn range(a: &[Term], s: &Substitution) -> Option<Vec<Substitution>> {
    if !(3..=4).contains(&a.len()) {
        return None;
    }
    let int = |t: &Term| t.as_f64().map(java_int);
    let (start, end) = (int(&a[1])?, int(&a[2])?);
    let step = match a.get(3) {
        Some(t) => int(t)?,
        None => 1,
    };
    if !a[0].is_var() {
        let v = int(&a[0])?;
        return Some(truth(v >= start && v <= end, s));
    }
    if step == 0 {
        // Jason's iterator repeats `start` forever when `start >= end`, else gives nothing.
        return Some(Vec::new());
    }
    let (start, end, step) = (i64::from(start), i64::from(end), i64::from(step));
    let count = if step > 0 && start <= end {
        (end - start) / step + 1
    } else if step < 0 && start >= end {
        (start - end) / -step + 1
    } else {
        0
    };
    // The value after the last must fit in an `int`, or Jason's `vl+step` wraps and goes on.
    let after = start + count * step;
    if count as usize > MAX_RANGE_ANSWERS || i32::try_from(after).is_err() {
        return Some(Vec::new());
    }
    let answers = (0..count)
        .flat_map(|k| unified(s, &[(&a[0], &Term::int(start + k * step))]))
        .collect();
    Some(answers)
}

#[derive(Clone, Copy)]
enum SetOp {
    Difference,
    Intersection,
    Union,
}

/// `difference.java`, `intersection.java`, `union.java` (`ListTermImpl.difference` etc.):
/// the set of the elements in a `TreeSet`, so the result is sorted by the term order and
/// has no duplicates.
fn set_op(a: &[Term], s: &Substitution, op: SetOp) -> Option<Vec<Substitution>> {
    let [x, y, r] = a else { return None };
    let (xs, ys) = (elements(x)?, elements(y)?);
    if !r.is_var() && !r.is_list() {
        return None;
    }
    let ys: BTreeSet<Term> = ys.into_iter().collect();
    let xs: BTreeSet<Term> = xs.into_iter().collect();
    let result: Vec<Term> = match op {
        SetOp::Difference => xs.difference(&ys).cloned().collect(),
        SetOp::Intersection => ys.intersection(&xs).cloned().collect(),
        SetOp::Union => xs.union(&ys).cloned().collect(),
    };
    Some(unified(s, &[(r, &Term::list(result))]))
}
