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

use crate::model::{unify, Substitution, Term};

mod actions;
mod functions;
mod parse;
#[cfg(test)]
mod tests;

pub use actions::{call, nested_source};
pub use functions::function;
pub use parse::parse_simple;

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
    (".add_nested_source", &[3]),
    (".remove_source_annot", &[2]),
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
