//! Jason's pure internal actions and arithmetic functions: those that read only their
//! arguments (no beliefs, intentions or agent state), computed exactly as Jason 3's
//! `jason.stdlib` and `jason.functions` classes compute them.
//!
//! [`call`] runs an internal action such as `.member(X, L)` and gives every answer, in
//! Jason's order, as substitutions extending the caller's; [`function`] evaluates an
//! arithmetic function such as `math.round(2.5)` inside an expression. [`PURE`] and
//! [`FUNCTIONS`] list the names with their arities for the type checker.
//!
//! Conventions shared by every action:
//!
//! * Where Jason throws (a wrong argument, an index out of bounds, `StringIndexOutOfBounds`),
//!   the action has no answer, like an action that returns `false`: in Jason the plan fails
//!   either way (only the error annotations of the failure event differ).
//! * Unifications keep Jason's argument order (`un.unifies(a, b)` is `unify(a, b, ..)`),
//!   which matters for annotations: `.member(p, [p[x]])` succeeds, `.member(p[x], [p])`
//!   does not.
//! * Strings are measured and indexed in UTF-16 code units, as Java's `String` is.
//! * A list with an unbound tail (`[a,b|T]`) is iterated over its elements, as Jason's
//!   `ListTermImpl.iterator` does; the tail is kept only where Jason keeps it (`.reverse`).
//! * Texts of terms (`.concat` on non-lists, `.substring` on non-strings, `.term2string`) are
//!   Jason's `toString`: like the model's `Display` but with strings printed between quotes
//!   without escapes (see [`jason_text`]). An unbound variable prints its name; a renamed
//!   variable prints as `_<gen><Name>`, where Jason's own number would differ.

use std::cmp::Ordering;
use std::collections::BTreeSet;

use crate::model::arith::ArithError;
use crate::model::{unify, Substitution, Term};

/// `.concat` is variadic (`concat.java` has no arity bounds); the type checker accepts up to
/// 16 arguments.
const CONCAT_ARITIES: &[usize] = &[1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];

/// The pure internal actions [`call`] implements, each with the arities Jason accepts.
pub const PURE: &[(&str, &[usize])] = &[
    (".member", &[2]),
    (".length", &[2]),
    (".nth", &[3]),
    (".concat", CONCAT_ARITIES),
    (".reverse", &[2]),
    (".sort", &[2]),
    // `.min(Var, Query, Min)` and `.max(..)` with three arguments query the beliefs.
    (".min", &[2]),
    (".max", &[2]),
    (".empty", &[1]),
    (".list", &[1]),
    (".ground", &[1]),
    (".atom", &[1]),
    (".number", &[1]),
    (".string", &[1]),
    (".structure", &[1]),
    (".literal", &[1]),
    (".substring", &[2, 3, 4]),
    (".term2string", &[2]),
    (".range", &[3, 4]),
    (".difference", &[3]),
    (".intersection", &[3]),
    (".union", &[3]),
];

/// The pure arithmetic functions [`function`] evaluates, as `(name, arity)`; a function with
/// two arities appears twice. Jason's `math.random`, `system.time` and `.count` are not pure.
pub const FUNCTIONS: &[(&str, usize)] = &[
    ("math.abs", 1),
    ("math.acos", 1),
    ("math.asin", 1),
    ("math.atan", 1),
    ("math.average", 1),
    ("math.ceil", 1),
    ("math.cos", 1),
    ("math.e", 0),
    ("math.floor", 1),
    (".length", 1),
    ("math.log", 1),
    ("math.max", 1),
    ("math.max", 2),
    ("math.mean", 1),
    ("math.median", 1),
    ("math.min", 1),
    ("math.min", 2),
    ("math.pi", 0),
    ("math.round", 1),
    ("math.sin", 1),
    ("math.sqrt", 1),
    ("math.std_dev", 1),
    ("math.sum", 1),
    ("math.tan", 1),
];

/// The most answers `.range` enumerates. Beyond it (or when Jason's iterator never ends: a
/// step of 0, or an `int` overflow that wraps around) the action has no answer here, where
/// Jason would run (practically) forever.
pub const MAX_RANGE_ANSWERS: usize = 1 << 20;

/// Runs the pure internal action `name` (with its dot: `.member`) on `args`.
///
/// `args` are evaluated (no arithmetic left) but may hold variables bound in `s`. Returns
/// `None` when `name` is not in [`PURE`]; otherwise every answer, each `s` extended, in the
/// order Jason's iterator gives them (an empty vector: the action fails, also when Jason
/// would throw, e.g. on a wrong arity or argument).
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
        _ => return None,
    };
    Some(answers.unwrap_or_default())
}

/// Evaluates the pure arithmetic function `name` on `args` (already evaluated terms).
///
/// Returns `None` when `name` with that arity is not in [`FUNCTIONS`] (Jason's
/// `FunctionRegister.getFunction` finds no function). Otherwise the number, or why there is
/// none: an argument not ground (Jason leaves the term unevaluated), an argument of the
/// wrong type (Jason's `JasonException`), or a result that is not a finite number (as in
/// [`crate::model::arith`]: `math.sqrt(-1)`, `math.log(0)`, `math.average([])`).
pub fn function(name: &str, args: &[Term]) -> Option<Result<Term, String>> {
    if !FUNCTIONS
        .iter()
        .any(|&(f, arity)| f == name && arity == args.len())
    {
        return None;
    }
    if let Some(t) = args.iter().find(|t| !t.is_ground()) {
        return Some(Err(format!("{name}: the argument {t} is not ground")));
    }
    Some(evaluate(name, args).and_then(|v| {
        if v.is_finite() {
            Ok(Term::num(v))
        } else {
            Err(format!("{name}: {}", ArithError::NotFinite))
        }
    }))
}

// ===== helpers ==================================================================================

/// The one answer `s` extended by unifying each pair, if they all unify.
fn unified(s: &Substitution, pairs: &[(&Term, &Term)]) -> Vec<Substitution> {
    let mut s = s.clone();
    if pairs.iter().all(|(a, b)| unify(a, b, &mut s)) {
        vec![s]
    } else {
        Vec::new()
    }
}

fn truth(b: bool, s: &Substitution) -> Vec<Substitution> {
    if b {
        vec![s.clone()]
    } else {
        Vec::new()
    }
}

/// The elements of a list as Jason's `ListTermImpl.iterator` gives them (an unbound tail is
/// not an element); `None` if the term is not a list.
fn elements(t: &Term) -> Option<Vec<Term>> {
    t.list_elements().map(|(elems, _)| elems)
}

/// Java's `(int) d` cast: toward zero, saturating, NaN to 0 (exactly Rust's `as i32`).
fn java_int(v: f64) -> i32 {
    v as i32
}

fn utf16_len(s: &str) -> usize {
    s.encode_utf16().count()
}

/// Java's `s.indexOf(needle, from)` on UTF-16 code units (an empty needle is found at
/// `from` while `from <= s.length()`).
fn index_of(s: &[u16], needle: &[u16], from: usize) -> Option<usize> {
    if needle.len() > s.len() {
        return None;
    }
    (from..=s.len() - needle.len()).find(|&i| s[i..i + needle.len()] == *needle)
}

/// Java's `s.substring(start, end)` on UTF-16 code units; `None` where Java throws, and where
/// the cut splits a surrogate pair (a Rust string cannot hold the half).
fn java_substring(s: &str, start: i32, end: i32) -> Option<String> {
    let u: Vec<u16> = s.encode_utf16().collect();
    let (start, end) = (usize::try_from(start).ok()?, usize::try_from(end).ok()?);
    if start > end || end > u.len() {
        return None;
    }
    String::from_utf16(&u[start..end]).ok()
}

/// Jason's `toString` of a term (`Structure.toString`, `ListTermImpl.toString`,
/// `NumberTermImpl.toString`): the model's `Display` except that strings are printed between
/// quotes with nothing escaped (`StringTermImpl.toString`).
pub fn jason_text(t: &Term) -> String {
    let mut out = String::new();
    write_text(t, &mut out);
    out
}

fn write_text(t: &Term, out: &mut String) {
    fn seq(ts: &[Term], out: &mut String) {
        for (i, t) in ts.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            write_text(t, out);
        }
    }
    match t {
        Term::Str(s) => {
            out.push('"');
            out.push_str(s);
            out.push('"');
        }
        Term::Struct(st) => {
            if st.negated() {
                out.push('~');
            }
            out.push_str(st.functor());
            if !st.args().is_empty() {
                out.push('(');
                seq(st.args(), out);
                out.push(')');
            }
            if !st.annots().is_empty() {
                out.push('[');
                seq(st.annots(), out);
                out.push(']');
            }
        }
        Term::Cons(_) => {
            let (elems, tail) = t.list_elements().expect("a list");
            out.push('[');
            seq(&elems, out);
            if let Some(tail) = tail {
                out.push('|');
                write_text(&tail, out);
            }
            out.push(']');
        }
        // Variables, numbers, atoms and `[]` print as in the model.
        _ => out.push_str(&t.to_string()),
    }
}

/// A string's text, or any other term's Jason text (`substring.java`, `term2string.java`).
fn string_or_text(t: &Term) -> String {
    match t {
        Term::Str(s) => s.to_string(),
        _ => jason_text(t),
    }
}

// ===== the actions ==============================================================================

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

// ===== term2string's parser =====================================================================

/// Reads `text` as Jason's parser reads a term, for the simple terms only: numbers (Jason's
/// `NUMBER` token without a leading `.`), strings without `\`, atoms (`[a-z][A-Za-z0-9_]*`
/// other than the keywords Jason's parser rejects, or quoted, quotes kept as in the model),
/// structures `f(t1,...,tn)` and proper lists `[t1,...,tn]` of these, with blanks between
/// tokens. `None` for anything else.
pub fn parse_simple(text: &str) -> Option<Term> {
    let mut p = Parser { s: text, i: 0 };
    let t = p.term()?;
    p.blanks();
    (p.i == text.len()).then_some(t)
}

struct Parser<'a> {
    s: &'a str,
    i: usize,
}

/// Keywords that `AS2JavaParser` does not read as a term (`begin`, `end`, `true` and `false`
/// it does).
const KEYWORDS: &[&str] = &["not", "div", "mod", "if", "else", "elif", "for", "while"];

impl Parser<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.as_bytes().get(self.i).copied()
    }

    fn peek_at(&self, k: usize) -> Option<u8> {
        self.s.as_bytes().get(self.i + k).copied()
    }

    fn blanks(&mut self) {
        // Jason's `SKIP`: blank, tab, line breaks, form feed.
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r' | 0x0c)) {
            self.i += 1;
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        self.blanks();
        if self.peek() == Some(c) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn digits(&mut self) -> usize {
        let from = self.i;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.i += 1;
        }
        self.i - from
    }

    fn term(&mut self) -> Option<Term> {
        self.blanks();
        match self.peek()? {
            b'0'..=b'9' => self.number(),
            b'"' => {
                let rest = &self.s[self.i + 1..];
                let end = rest.find('"')?;
                let body = &rest[..end];
                if body.contains(['\\', '\n', '\r']) {
                    return None;
                }
                self.i += end + 2;
                Some(Term::string(body))
            }
            b'[' => {
                self.i += 1;
                if self.eat(b']') {
                    return Some(Term::Nil);
                }
                let elems = self.sequence(b']')?;
                Some(Term::list(elems))
            }
            b'a'..=b'z' | b'\'' => {
                let from = self.i;
                if self.peek() == Some(b'\'') {
                    let end = self.s[from + 1..].find('\'')?;
                    self.i += end + 2;
                } else {
                    while self
                        .peek()
                        .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_')
                    {
                        self.i += 1;
                    }
                    let dotted = self.peek() == Some(b'.')
                        && self
                            .peek_at(1)
                            .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_');
                    if dotted || KEYWORDS.contains(&&self.s[from..self.i]) {
                        return None;
                    }
                }
                let functor = &self.s[from..self.i];
                let args = if self.eat(b'(') {
                    self.sequence(b')')?
                } else {
                    Vec::new()
                };
                Some(Term::structure(functor, args))
            }
            _ => None,
        }
    }

    /// `t1, ..., tn` then `close`; at least one term.
    fn sequence(&mut self, close: u8) -> Option<Vec<Term>> {
        let mut ts = vec![self.term()?];
        while self.eat(b',') {
            ts.push(self.term()?);
        }
        self.eat(close).then_some(ts)
    }

    fn number(&mut self) -> Option<Term> {
        let from = self.i;
        self.digits();
        if self.peek() == Some(b'.') && self.peek_at(1).is_some_and(|c| c.is_ascii_digit()) {
            self.i += 1;
            self.digits();
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            let mark = self.i;
            self.i += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.i += 1;
            }
            if self.digits() == 0 {
                self.i = mark;
            }
        }
        let v: f64 = self.s[from..self.i].parse().ok()?;
        v.is_finite().then(|| Term::num(v))
    }
}

// ===== the functions ============================================================================

fn number_arg(name: &str, t: &Term) -> Result<f64, String> {
    t.as_f64()
        .ok_or_else(|| format!("{name}: the argument '{}' is not numeric", jason_text(t)))
}

fn list_arg(name: &str, t: &Term) -> Result<Vec<Term>, String> {
    elements(t).ok_or_else(|| format!("{name} is not implemented for type '{}'", jason_text(t)))
}

/// The numbers among a list's elements (the `math` list functions skip the others).
fn numbers(name: &str, t: &Term) -> Result<Vec<f64>, String> {
    Ok(list_arg(name, t)?.iter().filter_map(Term::as_f64).collect())
}

/// Java's `Math.round`: `floor(x + 1/2)` computed exactly (so `0.49999999999999994` rounds
/// to 0 and `-2.5` to -2), saturating at the `long` range, NaN to 0.
fn java_round(x: f64) -> f64 {
    if x.is_nan() {
        return 0.0;
    }
    let f = x.floor();
    // `x - f` is exact: for |x| >= 1 by Sterbenz's lemma, for smaller |x| the result's
    // spacing is finer than x's near 1/2.
    let r = if x - f >= 0.5 { f + 1.0 } else { f };
    r.clamp(i64::MIN as f64, i64::MAX as f64)
}

/// The function's value; `name` and the arity are known to be in [`FUNCTIONS`].
fn evaluate(name: &str, args: &[Term]) -> Result<f64, String> {
    let unary = |f: fn(f64) -> f64| number_arg(name, &args[0]).map(f);
    match name {
        "math.abs" => unary(f64::abs),
        "math.acos" => unary(f64::acos),
        "math.asin" => unary(f64::asin),
        "math.atan" => unary(f64::atan),
        "math.ceil" => unary(f64::ceil),
        "math.cos" => unary(f64::cos),
        "math.floor" => unary(f64::floor),
        "math.log" => unary(f64::ln),
        "math.round" => unary(java_round),
        "math.sin" => unary(f64::sin),
        "math.sqrt" => unary(f64::sqrt),
        "math.tan" => unary(f64::tan),
        "math.e" => Ok(std::f64::consts::E),
        "math.pi" => Ok(std::f64::consts::PI),
        ".length" => match &args[0] {
            Term::Str(x) => Ok(utf16_len(x) as f64),
            t => elements(t).map(|e| e.len() as f64).ok_or_else(|| {
                format!("the argument '{}' is not a list or a string", jason_text(t))
            }),
        },
        "math.max" | "math.min" => {
            let is_max = name == "math.max";
            if let Some(x) = args[0].as_f64() {
                // `Max.java` reads the second argument whenever the first is a number.
                let second = args.get(1).ok_or_else(|| format!("{name}: one number"))?;
                let y = number_arg(name, second)?;
                return Ok(if is_max { x.max(y) } else { x.min(y) });
            }
            // Lists: Jason starts from `Double.MIN_VALUE` (the least positive double, so
            // `math.max([-3])` is 4.9E-324) and `Double.MAX_VALUE`.
            let start = if is_max { f64::from_bits(1) } else { f64::MAX };
            Ok(numbers(name, &args[0])?.into_iter().fold(start, |acc, n| {
                if (is_max && n > acc) || (!is_max && n < acc) {
                    n
                } else {
                    acc
                }
            }))
        }
        "math.sum" => Ok(numbers(name, &args[0])?.iter().sum()),
        "math.average" => {
            // `Average.java`: 0/0 for no numbers, which is not a finite result.
            let ns = numbers(name, &args[0])?;
            Ok(ns.iter().sum::<f64>() / ns.len() as f64)
        }
        "math.mean" => {
            let ns = numbers(name, &args[0])?;
            if ns.is_empty() {
                return Err(format!("{name}: no numbers in '{}'", jason_text(&args[0])));
            }
            Ok(ns.iter().sum::<f64>() / ns.len() as f64)
        }
        "math.median" => {
            let l = list_arg(name, &args[0])?;
            let mut ns: Vec<f64> = l.iter().filter_map(Term::as_f64).collect();
            if ns.len() != l.len() || ns.is_empty() {
                return Err(format!(
                    "{name} needs a non-empty list of numbers, not '{}'",
                    jason_text(&args[0])
                ));
            }
            ns.sort_by(f64::total_cmp);
            let n = ns.len();
            Ok(if n.is_multiple_of(2) {
                (ns[n / 2 - 1] + ns[n / 2]) / 2.0
            } else {
                ns[n / 2]
            })
        }
        "math.std_dev" => {
            // `StdDev.java`: the sample deviation, NaN (not finite) for fewer than two numbers.
            let ns = numbers(name, &args[0])?;
            let n = ns.len() as f64;
            let mean = ns.iter().sum::<f64>() / n;
            let squares: f64 = ns.iter().map(|x| (x - mean) * (x - mean)).sum();
            Ok((squares / (n - 1.0)).sqrt())
        }
        _ => unreachable!("{name} is in FUNCTIONS"),
    }
}

#[cfg(test)]
mod tests {
    //! Expected values come from Jason 3 itself (`jason.stdlib` and `jason.functions` run on
    //! the parsed arguments), where there is any doubt.

    use super::*;
    use crate::model::Var;

    fn a(s: &str) -> Term {
        Term::atom(s)
    }
    fn v(s: &str) -> Term {
        Term::var(s)
    }
    fn n(x: f64) -> Term {
        Term::num(x)
    }
    fn st(s: &str) -> Term {
        Term::string(s)
    }
    fn f(name: &str, args: Vec<Term>) -> Term {
        Term::structure(name, args)
    }
    fn l(elems: Vec<Term>) -> Term {
        Term::list(elems)
    }

    /// The answers of `name(args)` from scratch, each as the bindings of the query's
    /// variables, printed: `["{X -> a}", ...]`.
    fn run(name: &str, args: Vec<Term>) -> Vec<String> {
        let vars: Vec<Var> = f("q", args.clone()).vars();
        call(name, &args, &Substitution::new())
            .unwrap_or_else(|| panic!("{name} is pure"))
            .iter()
            .map(|s| s.restrict(&vars).to_string())
            .collect()
    }

    /// The value of `X` in the one answer.
    fn one(name: &str, args: Vec<Term>) -> String {
        let answers = call(name, &args, &Substitution::new()).expect("pure");
        assert_eq!(answers.len(), 1, "{name}{args:?}");
        answers[0].resolve(&Var::named("X")).to_string()
    }

    fn holds(name: &str, args: Vec<Term>) -> bool {
        !call(name, &args, &Substitution::new())
            .expect("pure")
            .is_empty()
    }

    /// The function's value as Jason prints it.
    fn printed(name: &str, args: Vec<Term>) -> String {
        function(name, &args)
            .expect("known function")
            .unwrap()
            .to_string()
    }

    fn value(name: &str, args: Vec<Term>) -> Result<f64, String> {
        function(name, &args)
            .expect("known function")
            .map(|t| t.as_f64().unwrap())
    }

    #[test]
    fn not_pure_is_none() {
        assert!(call(".print", &[a("x")], &Substitution::new()).is_none());
        assert!(call("member", &[v("X"), l(vec![])], &Substitution::new()).is_none());
        assert!(function("math.random", &[]).is_none());
        assert!(function("math.abs", &[n(1.0), n(2.0)]).is_none());
    }

    #[test]
    fn member_in_order_and_annotation_direction() {
        assert_eq!(
            run(".member", vec![v("X"), l(vec![a("a"), a("b"), a("c")])]),
            ["{X -> a}", "{X -> b}", "{X -> c}"]
        );
        let fx = f("f", vec![v("X")]);
        let list = l(vec![
            f("f", vec![n(1.0)]),
            f("g", vec![n(2.0)]),
            f("f", vec![n(3.0)]),
        ]);
        assert_eq!(run(".member", vec![fx, list]), ["{X -> 1}", "{X -> 3}"]);
        let px = Term::literal("p", false, vec![], vec![a("x")]);
        assert!(holds(".member", vec![a("p"), l(vec![px.clone()])]));
        assert!(!holds(".member", vec![px, l(vec![a("p")])]));
        assert!(!holds(".member", vec![v("X"), a("a")]));
    }

    #[test]
    fn bindings_of_the_caller_are_applied_and_kept() {
        let mut s = Substitution::new();
        assert!(s.bind(Var::named("L"), l(vec![a("a"), a("b")])));
        let answers = call(".member", &[v("X"), v("L")], &s).unwrap();
        assert_eq!(answers.len(), 2);
        assert_eq!(answers[1].resolve(&Var::named("X")), a("b"));
        assert_eq!(answers[1].resolve(&Var::named("L")).to_string(), "[a,b]");
    }

    #[test]
    fn length_of_lists_and_strings() {
        let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
        assert_eq!(one(".length", vec![partial, v("X")]), "2");
        // UTF-16 units: "héllo" is 5, an emoji is 2.
        assert_eq!(one(".length", vec![st("héllo"), v("X")]), "5");
        assert_eq!(one(".length", vec![st("😀"), v("X")]), "2");
        assert_eq!(one(".length", vec![st(""), v("X")]), "0");
        assert!(holds(".length", vec![st("abc"), n(3.0)]));
        assert!(!holds(".length", vec![f("f", vec![a("a")]), v("X")]));
    }

    #[test]
    fn nth_bound_and_unbound() {
        let abc = l(vec![a("a"), a("b"), a("c")]);
        assert_eq!(one(".nth", vec![n(1.0), abc.clone(), v("X")]), "b");
        assert_eq!(one(".nth", vec![n(1.7), abc.clone(), v("X")]), "b");
        assert!(!holds(".nth", vec![n(3.0), abc.clone(), v("X")]));
        assert!(!holds(".nth", vec![n(-1.0), abc.clone(), v("X")]));
        assert_eq!(
            run(".nth", vec![v("I"), abc, v("X")]),
            ["{I -> 0, X -> a}", "{I -> 1, X -> b}", "{I -> 2, X -> c}"]
        );
        // The index does not unify with the element it became: Jason keeps the answer.
        let five_zero = l(vec![n(5.0), n(0.0)]);
        assert_eq!(
            run(".nth", vec![v("I"), five_zero, v("I")]),
            ["{I -> 5}", "{I -> 0}"]
        );
        let aba = l(vec![a("a"), a("b"), a("a")]);
        assert_eq!(
            run(".nth", vec![v("I"), aba, a("a")]),
            ["{I -> 0}", "{I -> 2}"]
        );
        assert_eq!(one(".nth", vec![n(1.0), st("abc"), v("X")]), "\"b\"");
        assert_eq!(
            run(".nth", vec![v("I"), st("aba"), st("a")]),
            ["{I -> 0}", "{I -> 2}"]
        );
        // Bytes of the UTF-8 form: "é" is two bytes, each U+FFFD.
        assert_eq!(one(".nth", vec![n(1.0), st("é"), v("X")]), "\"\u{FFFD}\"");
    }

    #[test]
    fn concat_lists() {
        let r = |args: Vec<Term>| one(".concat", args);
        assert_eq!(
            r(vec![l(vec![a("a")]), l(vec![a("b"), a("c")]), v("X")]),
            "[a,b,c]"
        );
        assert_eq!(
            r(vec![
                l(vec![a("a")]),
                l(vec![a("b")]),
                l(vec![a("c")]),
                v("X")
            ]),
            "[a,b,c]"
        );
        assert_eq!(r(vec![l(vec![a("a")]), v("X")]), "[a]");
        // Nothing is appended after an unbound tail.
        let partial = Term::list_with_tail(vec![a("a")], v("T"));
        assert_eq!(r(vec![partial, l(vec![a("b")]), v("X")]), "[a|T]");
        let b_t = Term::list_with_tail(vec![a("b")], v("T"));
        let abc = vec![l(vec![a("a")]), b_t, l(vec![a("c")]), v("X")];
        assert_eq!(r(abc), "[a,b|T]");
        assert!(!holds(".concat", vec![l(vec![a("a")]), a("b"), v("X")]));
        assert!(!holds(".concat", vec![l(vec![a("a")]), l(vec![]), a("b")]));
        assert!(!holds(".concat", vec![]));
    }

    #[test]
    fn concat_strings() {
        let r = |args: Vec<Term>| one(".concat", args);
        assert_eq!(r(vec![st("ab"), n(3.0), v("X")]), "\"ab3\"");
        assert!(holds(".concat", vec![st("ab"), n(3.0), st("ab3")]));
        // The last argument is compared through its text.
        assert!(holds(".concat", vec![st("a"), st("b"), a("ab")]));
        let args = vec![
            a("a"),
            a("'B c'"),
            f("f", vec![a("x"), st("s")]),
            l(vec![n(1.0), n(2.0)]),
            v("X"),
        ];
        assert_eq!(r(args), "\"aB cf(x,\\\"s\\\")[1,2]\"");
        assert_eq!(r(vec![n(2.5), v("X")]), "\"2.5\"");
        assert_eq!(r(vec![st("x"), v("X")]), "\"x\"");
        // Jason's text: the quote inside is not escaped.
        let q = r(vec![st("x\"y"), f("f", vec![st("q\"z")]), v("X")]);
        assert_eq!(q, "\"x\\\"yf(\\\"q\\\"z\\\")\"");
        let s = call(
            ".concat",
            &[st("x\"y"), f("f", vec![st("q\"z")]), v("X")],
            &Substitution::new(),
        )
        .unwrap();
        assert_eq!(
            s[0].resolve(&Var::named("X")).as_str(),
            Some("x\"yf(\"q\"z\")")
        );
    }

    #[test]
    fn reverse_lists_and_strings() {
        assert_eq!(
            one(".reverse", vec![l(vec![a("a"), a("b"), a("c")]), v("X")]),
            "[c,b,a]"
        );
        let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
        assert_eq!(one(".reverse", vec![partial, v("X")]), "[b,a|T]");
        assert_eq!(one(".reverse", vec![st("abc"), v("X")]), "\"cba\"");
        assert_eq!(one(".reverse", vec![st("a😀b"), v("X")]), "\"b😀a\"");
        assert!(!holds(".reverse", vec![st("abc"), l(vec![])]));
        assert!(!holds(".reverse", vec![a("abc"), v("X")]));
    }

    #[test]
    fn sort_by_jason_order() {
        let list = l(vec![a("c"), n(1.0), st("s"), f("f", vec![a("x")]), a("b")]);
        assert_eq!(one(".sort", vec![list, v("X")]), "[1,\"s\",b,c,f(x)]");
        let list = l(vec![
            a("b"),
            l(vec![a("a")]),
            st("b"),
            st("a"),
            n(2.0),
            n(1.5),
            Term::literal("a", true, vec![], vec![]),
            f("a", vec![n(1.0)]),
            a("a"),
            v("Y"),
            l(vec![]),
            Term::Var(Var::anonymous(1)),
        ]);
        assert_eq!(
            one(".sort", vec![list, v("X")]),
            "[1.5,2,\"a\",\"b\",[],[a],a,a(1),~a,b,Y,_1]"
        );
        let list = l(vec![
            f("f", vec![a("b")]),
            f("f", vec![a("a"), a("a")]),
            f("f", vec![a("a")]),
            a("g"),
            st("ab c"),
            st("ab"),
        ]);
        assert_eq!(
            one(".sort", vec![list, v("X")]),
            "[\"ab c\",\"ab\",f(a),f(a,a),f(b),g]"
        );
        assert_eq!(
            one(
                ".sort",
                vec![l(vec![n(1.0), n(1.0), a("a"), a("a")]), v("X")]
            ),
            "[1,1,a,a]"
        );
    }

    #[test]
    fn min_and_max() {
        let l312 = l(vec![n(3.0), n(1.0), n(2.0)]);
        assert_eq!(one(".min", vec![l312.clone(), v("X")]), "1");
        assert_eq!(one(".max", vec![l312, v("X")]), "3");
        let mixed = l(vec![a("b"), st("a"), n(3.0), l(vec![a("x")])]);
        assert_eq!(one(".min", vec![mixed.clone(), v("X")]), "3");
        assert_eq!(one(".max", vec![mixed, v("X")]), "b");
        assert_eq!(one(".min", vec![l(vec![v("Y"), n(1.0)]), v("X")]), "1");
        assert!(!holds(".min", vec![l(vec![]), v("X")]));
    }

    #[test]
    fn type_tests() {
        let neg = Term::literal("p", true, vec![], vec![]);
        let annotated = Term::literal("p", false, vec![], vec![a("x")]);
        let fa = f("f", vec![a("a")]);
        let cases: Vec<(&str, Term, bool)> = vec![
            (".structure", a("a"), false),
            (".structure", fa.clone(), true),
            (".structure", l(vec![a("a")]), true),
            (".structure", l(vec![]), true),
            (".structure", st("s"), false),
            (".structure", n(1.0), false),
            (".structure", v("X"), false),
            (".structure", neg.clone(), true),
            (".structure", annotated.clone(), true),
            (".atom", a("a"), true),
            (".atom", l(vec![]), false),
            (".atom", neg.clone(), false),
            (".atom", annotated, false),
            (".atom", fa.clone(), false),
            (".atom", st("a"), false),
            (".atom", v("X"), false),
            (".literal", a("a"), true),
            (".literal", neg, true),
            (".literal", l(vec![a("a")]), false),
            (".literal", st("s"), false),
            (".literal", n(1.0), false),
            (".literal", f("f", vec![v("X")]), true),
            (".list", l(vec![]), true),
            (".list", Term::list_with_tail(vec![a("a")], v("T")), true),
            (".list", a("a"), false),
            (".ground", f("f", vec![v("X")]), false),
            (".ground", l(vec![a("a"), st("s"), n(1.0)]), true),
            (".ground", v("X"), false),
            (".number", n(1.5), true),
            (".number", st("1"), false),
            (".string", st("s"), true),
            (".string", a("s"), false),
            (".empty", l(vec![]), true),
            (".empty", st(""), true),
            (".empty", l(vec![a("a")]), false),
            (".empty", a("a"), false),
        ];
        for (name, t, expected) in cases {
            assert_eq!(holds(name, vec![t.clone()]), expected, "{name}({t})");
        }
    }

    #[test]
    fn substring_answers() {
        let r = |args: Vec<Term>| run(".substring", args);
        assert_eq!(
            r(vec![st("b"), st("abcb"), v("P")]),
            ["{P -> 1}", "{P -> 3}"]
        );
        // The end is the index of the last character (Jason's arithmetic).
        assert_eq!(
            r(vec![st("b"), st("abcb"), v("P"), v("E")]),
            ["{E -> 1, P -> 1}", "{E -> 3, P -> 3}"]
        );
        assert_eq!(
            r(vec![st("bc"), st("abcbc"), v("P"), v("E")]),
            ["{E -> 2, P -> 1}", "{E -> 4, P -> 3}"]
        );
        assert_eq!(
            r(vec![st(""), st("abc"), v("P")]),
            ["{P -> 0}", "{P -> 1}", "{P -> 2}"]
        );
        assert!(r(vec![st(""), st(""), v("P")]).is_empty());
        assert_eq!(r(vec![st("b"), st("abcb"), n(3.0)]), ["{}"]);
        assert_eq!(r(vec![st("b"), st("abcb"), n(1.0), v("E")]), ["{E -> 1}"]);
        assert_eq!(r(vec![st("é"), st("aéb"), v("P")]), ["{P -> 1}"]);
        // Texts of non-strings: "b" in "f(a,b)".
        assert_eq!(
            r(vec![a("b"), f("f", vec![a("a"), a("b")]), v("P")]),
            ["{P -> 4}"]
        );
        assert!(holds(".substring", vec![st("b"), st("abcb")]));
        assert!(!holds(".substring", vec![st("d"), st("abcb")]));
        let sub = |args: Vec<Term>| one(".substring", args);
        assert_eq!(sub(vec![v("X"), st("abcdef"), n(2.0), n(4.0)]), "\"cd\"");
        assert_eq!(sub(vec![v("X"), st("abcdef"), n(2.0)]), "\"cdef\"");
        assert_eq!(sub(vec![st("abcdef"), v("X"), n(2.0), n(4.0)]), "\"cd\"");
        assert!(!holds(
            ".substring",
            vec![v("X"), st("abcdef"), n(4.0), n(2.0)]
        ));
        // A fourth argument that is not a number means "to the end".
        assert_eq!(sub(vec![v("X"), st("abc"), n(1.0), v("E")]), "\"bc\"");
    }

    #[test]
    fn term2string_both_ways() {
        let fa1 = f("f", vec![a("a"), n(1.0)]);
        assert_eq!(one(".term2string", vec![fa1.clone(), v("X")]), "\"f(a,1)\"");
        assert!(holds(".term2string", vec![fa1.clone(), st("f(a,1)")]));
        assert!(holds(".term2string", vec![n(1.0), st("1")]));
        assert!(holds(".term2string", vec![st("s"), st("\"s\"")]));
        let q = call(
            ".term2string",
            &[f("f", vec![a("a"), st("x\"y")]), v("X")],
            &Substitution::new(),
        )
        .unwrap();
        assert_eq!(
            q[0].resolve(&Var::named("X")).as_str(),
            Some("f(a,\"x\"y\")")
        );
        assert_eq!(
            one(".term2string", vec![a("'Hello'"), v("X")]),
            "\"'Hello'\""
        );
        let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
        assert_eq!(one(".term2string", vec![partial, v("X")]), "\"[a,b|T]\"");
        let parse = |text: &str| one(".term2string", vec![v("X"), st(text)]);
        assert_eq!(parse("f(a,1)"), "f(a,1)");
        assert_eq!(parse("f( a , 1 )"), "f(a,1)");
        assert_eq!(parse("f (a)"), "f(a)");
        assert_eq!(parse(" abc "), "abc");
        assert_eq!(parse("1.5"), "1.5");
        assert_eq!(parse("007"), "7");
        assert_eq!(parse("1e3"), "1000");
        assert_eq!(parse("1.5e-3"), "0.0015");
        assert_eq!(parse("3000000000"), "3000000000");
        assert_eq!(parse("[a ,b]"), "[a,b]");
        assert_eq!(parse("[ ]"), "[]");
        assert_eq!(parse("f(a,[1,2])"), "f(a,[1,2])");
        assert_eq!(parse("\"s\""), "\"s\"");
        assert_eq!(parse("f(\"a b\")"), "f(\"a b\")");
        assert_eq!(parse("'a b'"), "'a b'");
        assert_eq!(parse("begin"), "begin");
        assert_eq!(parse("f(true)"), "f(true)");
        // Not simple: Jason gives an atom of the whole text, a variable, annotations, or
        // evaluates arithmetic; here there is no answer.
        for text in [
            "hello world",
            "Abc",
            "~p[x]",
            "-1",
            "1+2",
            "",
            "f(",
            "not",
            "f(if)",
            "a.b",
            "1.",
            ".5",
            "f()",
            "[a|b]",
        ] {
            assert!(!holds(".term2string", vec![v("X"), st(text)]), "{text}");
        }
        // A non-string second argument is read through its text.
        assert_eq!(one(".term2string", vec![v("X"), a("a")]), "a");
        assert_eq!(run(".term2string", vec![v("X"), v("Y")]), ["{X -> Y}"]);
        assert!(!holds(".term2string", vec![a("a"), a("b")]));
    }

    #[test]
    fn range_in_order() {
        let r = |args: Vec<Term>| run(".range", args);
        assert_eq!(
            r(vec![v("X"), n(1.0), n(3.0)]),
            ["{X -> 1}", "{X -> 2}", "{X -> 3}"]
        );
        assert_eq!(
            r(vec![v("X"), n(1.0), n(10.0), n(3.0)]),
            ["{X -> 1}", "{X -> 4}", "{X -> 7}", "{X -> 10}"]
        );
        assert_eq!(
            r(vec![v("X"), n(5.0), n(1.0), n(-2.0)]),
            ["{X -> 5}", "{X -> 3}", "{X -> 1}"]
        );
        assert!(r(vec![v("X"), n(3.0), n(1.0)]).is_empty());
        assert_eq!(
            r(vec![v("X"), n(1.9), n(3.9)]),
            ["{X -> 1}", "{X -> 2}", "{X -> 3}"]
        );
        assert!(holds(".range", vec![n(2.0), n(1.0), n(3.0)]));
        assert!(!holds(".range", vec![n(5.0), n(1.0), n(3.0)]));
        // The step is ignored when the value is bound.
        assert!(holds(".range", vec![n(2.0), n(1.0), n(9.0), n(4.0)]));
        // Endless in Jason.
        assert!(r(vec![v("X"), n(3.0), n(1.0), n(0.0)]).is_empty());
        assert!(r(vec![v("X"), n(1.0), n(f64::from(i32::MAX))]).is_empty());
        assert!(!holds(".range", vec![v("X"), a("a"), n(3.0)]));
    }

    #[test]
    fn set_operations() {
        let caba = l(vec![a("c"), a("a"), a("b"), a("a")]);
        let r = |name: &str, x: Term, y: Term| one(name, vec![x, y, v("X")]);
        assert_eq!(
            r(".difference", caba.clone(), l(vec![a("b"), a("d")])),
            "[a,c]"
        );
        let bda = l(vec![a("b"), a("d"), a("a")]);
        assert_eq!(r(".intersection", caba.clone(), bda.clone()), "[a,b]");
        assert_eq!(r(".union", caba, bda), "[a,b,c,d]");
        assert_eq!(
            r(".union", l(vec![n(1.0), n(1.0), st("1")]), l(vec![])),
            "[1,\"1\"]"
        );
        let partial = Term::list_with_tail(vec![a("b"), a("a")], v("T"));
        assert_eq!(r(".union", partial, l(vec![a("c")])), "[a,b,c]");
        assert!(!holds(".union", vec![a("a"), l(vec![]), v("X")]));
    }

    #[test]
    fn every_pure_action_answers_something() {
        let abc = || l(vec![a("a"), a("b"), a("c")]);
        let samples: Vec<(&str, Vec<Term>)> = vec![
            (".member", vec![v("X"), abc()]),
            (".length", vec![abc(), v("X")]),
            (".nth", vec![n(0.0), abc(), v("X")]),
            (".concat", vec![abc(), abc(), v("X")]),
            (".reverse", vec![abc(), v("X")]),
            (".sort", vec![abc(), v("X")]),
            (".min", vec![abc(), v("X")]),
            (".max", vec![abc(), v("X")]),
            (".empty", vec![l(vec![])]),
            (".list", vec![abc()]),
            (".ground", vec![abc()]),
            (".atom", vec![a("a")]),
            (".number", vec![n(1.0)]),
            (".string", vec![st("s")]),
            (".structure", vec![f("f", vec![a("a")])]),
            (".literal", vec![a("a")]),
            (".substring", vec![st("b"), st("abc"), v("X")]),
            (".term2string", vec![a("a"), v("X")]),
            (".range", vec![v("X"), n(1.0), n(3.0)]),
            (".difference", vec![abc(), abc(), v("X")]),
            (".intersection", vec![abc(), abc(), v("X")]),
            (".union", vec![abc(), abc(), v("X")]),
        ];
        for (name, arities) in PURE {
            let (_, args) = samples
                .iter()
                .find(|(n, _)| n == name)
                .unwrap_or_else(|| panic!("no sample for {name}"));
            assert!(arities.contains(&args.len()), "{name}");
            assert!(holds(name, args.clone()), "{name}");
        }
        assert_eq!(samples.len(), PURE.len());
    }

    #[test]
    fn functions_as_jason_computes_them() {
        assert_eq!(value("math.round", vec![n(2.5)]), Ok(3.0));
        assert_eq!(value("math.round", vec![n(-2.5)]), Ok(-2.0));
        assert_eq!(value("math.round", vec![n(0.49999999999999994)]), Ok(0.0));
        assert_eq!(value("math.round", vec![n(-0.5)]), Ok(0.0));
        let big = function("math.round", &[n(1e19)]).unwrap().unwrap();
        assert_eq!(big.to_string(), "9223372036854775807");
        assert_eq!(value("math.abs", vec![n(-3.0)]), Ok(3.0));
        assert_eq!(value("math.max", vec![n(3.0), n(7.0)]), Ok(7.0));
        assert_eq!(value("math.min", vec![n(3.0), n(7.0)]), Ok(3.0));
        assert_eq!(
            value("math.max", vec![l(vec![n(-3.0), n(-5.0)])]),
            Ok(4.9e-324)
        );
        assert_eq!(value("math.max", vec![l(vec![])]), Ok(4.9e-324));
        assert_eq!(value("math.min", vec![l(vec![])]), Ok(f64::MAX));
        assert_eq!(
            value("math.min", vec![l(vec![n(4.0), n(2.0), a("a"), n(9.0)])]),
            Ok(2.0)
        );
        assert_eq!(value("math.max", vec![l(vec![n(1.0)]), n(5.0)]), Ok(1.0));
        assert!(value("math.min", vec![n(2.0), l(vec![n(1.0)])]).is_err());
        assert!(value("math.max", vec![n(2.0)]).is_err());
        assert_eq!(printed("math.sqrt", vec![n(2.0)]), "1.4142135623730951");
        assert!(value("math.sqrt", vec![n(-1.0)]).is_err());
        assert_eq!(value("math.floor", vec![n(-1.5)]), Ok(-2.0));
        assert_eq!(value("math.ceil", vec![n(-1.5)]), Ok(-1.0));
        let mixed = l(vec![n(1.0), n(2.0), a("a"), n(3.5)]);
        assert_eq!(value("math.sum", vec![mixed]), Ok(6.5));
        assert_eq!(value("math.sum", vec![l(vec![])]), Ok(0.0));
        assert_eq!(
            value("math.average", vec![l(vec![n(1.0), n(2.0)])]),
            Ok(1.5)
        );
        assert!(value("math.average", vec![l(vec![])]).is_err());
        assert!(value("math.mean", vec![l(vec![])]).is_err());
        assert_eq!(
            value("math.mean", vec![l(vec![n(1.0), n(2.0), n(4.0)])]),
            Ok(2.3333333333333335)
        );
        assert_eq!(
            value("math.median", vec![l(vec![n(3.0), n(1.0), n(2.0)])]),
            Ok(2.0)
        );
        let four = l(vec![n(4.0), n(1.0), n(3.0), n(2.0)]);
        assert_eq!(value("math.median", vec![four]), Ok(2.5));
        assert!(value("math.median", vec![l(vec![n(1.0), a("a")])]).is_err());
        let four = l(vec![n(1.0), n(2.0), n(3.0), n(4.0)]);
        assert_eq!(value("math.std_dev", vec![four]), Ok(1.2909944487358056));
        assert!(value("math.std_dev", vec![l(vec![n(1.0)])]).is_err());
        assert_eq!(printed("math.log", vec![n(10.0)]), "2.302585092994046");
        assert!(value("math.log", vec![n(0.0)]).is_err());
        assert_eq!(printed("math.e", vec![]), "2.718281828459045");
        assert_eq!(printed("math.pi", vec![]), "3.141592653589793");
        assert_eq!(value("math.sin", vec![n(1.0)]), Ok(0.8414709848078965));
        assert_eq!(value("math.cos", vec![n(1.0)]), Ok(0.5403023058681398));
        assert_eq!(value("math.tan", vec![n(1.0)]), Ok(1.5574077246549023));
        assert_eq!(printed("math.asin", vec![n(0.5)]), "0.5235987755982989");
        assert_eq!(printed("math.acos", vec![n(0.5)]), "1.0471975511965979");
        assert_eq!(printed("math.atan", vec![n(1.0)]), "0.7853981633974483");
        assert_eq!(value(".length", vec![l(vec![a("a"), a("b")])]), Ok(2.0));
        assert_eq!(value(".length", vec![st("abc")]), Ok(3.0));
        assert!(value(".length", vec![a("a")]).is_err());
        assert!(value("math.abs", vec![a("a")]).is_err());
        assert!(value("math.abs", vec![v("X")]).is_err());
    }

    #[test]
    fn every_function_evaluates() {
        for (name, arity) in FUNCTIONS {
            let args = match (*name, *arity) {
                (_, 0) => vec![],
                ("math.acos" | "math.asin", _) => vec![n(0.5)],
                (
                    "math.average" | "math.mean" | "math.median" | "math.std_dev" | "math.sum"
                    | ".length",
                    _,
                )
                | ("math.max" | "math.min", 1) => vec![l(vec![n(1.0), n(2.0)])],
                (_, 1) => vec![n(2.0)],
                _ => vec![n(2.0), n(3.0)],
            };
            assert!(
                matches!(function(name, &args), Some(Ok(_))),
                "{name}/{arity}"
            );
        }
    }
}
