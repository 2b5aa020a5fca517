//! Terms printed exactly as Jason's `toString` prints them (`jason.asSyntax`), because every
//! term in a report comes from here and users compare it with what Jason shows.
//!
//! * literals: `~functor(arg1,arg2)[annot1,annot2]`, no blank after commas, annotations in
//!   their sorted order (`Structure.toString`);
//! * lists: `[a,b]`, `[a,b|T]`, `[]` (`ListTermImpl.toString`);
//! * numbers: an integral value within `long` prints as an integer (`3`, `-2`), any other as
//!   Java's `Double.toString` (`1.5`, `0.1`, `1.0E20`, `1.5E-5`, `Infinity`)
//!   (`NumberTermImpl.toString`);
//! * variables by name; a renamed variable (generation `g > 0`) as `_gName`, the form of
//!   Jason's renamed variables (`UnnamedVar`: `"_" + id + name`), but for those of a
//!   message's content, which print by name as Jason prints its copy of the content;
//! * strings in double quotes. Jason's `StringTermImpl.toString` prints the text between
//!   quotes without escaping anything; we escape `\`, `"`, newline (`\n`) and carriage
//!   return (`\r`) so that a printed string reads back as the same string (Jason's lexer
//!   does not accept a raw line break in a string). The two agree on every string without
//!   those four characters.

use super::term::{Num, Struct, Term, Var};
use std::fmt::{self, Display, Formatter, Write};

impl Display for Var {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        // A message's variables keep their names, as Jason's copy of the content does.
        if self.generation() == 0 || self.generation() >= super::term::MESSAGE_GENERATION {
            f.write_str(self.name())
        } else {
            write!(f, "_{}{}", self.generation(), self.name())
        }
    }
}

impl fmt::Debug for Var {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        Display::fmt(self, f)
    }
}

impl Display for Num {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        f.write_str(&java_number_string(self.value()))
    }
}

impl fmt::Debug for Num {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        Display::fmt(self, f)
    }
}

/// `v` as Jason's `NumberTermImpl.toString` prints it: the `long` `Math.round(v)` when that
/// equals `v`, otherwise Java's `Double.toString(v)`.
pub fn java_number_string(v: f64) -> String {
    // 2^63: `Math.round` saturates at `Long.MAX_VALUE`, which converts back to 2^63.
    const TWO_63: f64 = 9_223_372_036_854_775_808.0;
    if v.fract() == 0.0 && (-TWO_63..=TWO_63).contains(&v) {
        if v == TWO_63 {
            i64::MAX.to_string()
        } else {
            (v as i64).to_string()
        }
    } else {
        java_double_string(v)
    }
}

/// Java's `Double.toString(v)` (JDK 19 and later: the shortest decimal that reads back as
/// `v`): plain notation with at least one fractional digit when `10^-3 <= |v| < 10^7`,
/// otherwise `d.dddE±n`.
pub fn java_double_string(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "Infinity" } else { "-Infinity" }.into();
    }
    if v == 0.0 {
        return if v.is_sign_negative() { "-0.0" } else { "0.0" }.into();
    }
    let abs = v.abs();
    if (1e-3..1e7).contains(&abs) {
        // Rust's `Display` is the shortest round-trip decimal, never in exponent form.
        let s = v.to_string();
        return if s.contains('.') { s } else { s + ".0" };
    }
    // `{:e}` gives the shortest digits as `d.ddde-n`; lay them out as Java does.
    let mut s = format!("{v:e}");
    if !s.split_once('e').expect("exponent form").0.contains('.') {
        // One significant digit: Java then also considers two-digit decimals and takes the
        // closest to `v` (`4.9E-324`, not `5.0E-324`); only subnormals can differ.
        let two = format!("{v:.1e}");
        if two.parse::<f64>() == Ok(v) {
            s = two;
        }
    }
    let (mantissa, exp) = s.split_once('e').expect("exponent form");
    let mut out = String::with_capacity(s.len() + 3);
    out.push_str(mantissa);
    if !mantissa.contains('.') {
        out.push_str(".0");
    }
    out.push('E');
    out.push_str(exp);
    out
}

impl Display for Term {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Term::Var(v) => Display::fmt(v, f),
            Term::Num(n) => Display::fmt(n, f),
            Term::Str(s) => write_string(s, f),
            Term::Atom(a) => f.write_str(a),
            Term::Struct(s) => Display::fmt(&**s, f),
            Term::Nil | Term::Cons(_) => write_list(self, f),
        }
    }
}

impl fmt::Debug for Term {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        Display::fmt(self, f)
    }
}

impl Display for Struct {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        if self.negated() {
            f.write_char('~')?;
        }
        f.write_str(self.functor())?;
        if !self.args().is_empty() {
            f.write_char('(')?;
            write_seq(self.args(), f)?;
            f.write_char(')')?;
        }
        if !self.annots().is_empty() {
            f.write_char('[')?;
            write_seq(self.annots(), f)?;
            f.write_char(']')?;
        }
        Ok(())
    }
}

impl fmt::Debug for Struct {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        Display::fmt(self, f)
    }
}

fn write_seq(ts: &[Term], f: &mut Formatter<'_>) -> fmt::Result {
    for (i, t) in ts.iter().enumerate() {
        if i > 0 {
            f.write_char(',')?;
        }
        Display::fmt(t, f)?;
    }
    Ok(())
}

/// `[a,b]`, `[a,b|T]`; iterative along the spine so long lists do not deepen the stack.
fn write_list(t: &Term, f: &mut Formatter<'_>) -> fmt::Result {
    f.write_char('[')?;
    let mut t = t;
    let mut first = true;
    loop {
        match t {
            Term::Cons(c) => {
                if !first {
                    f.write_char(',')?;
                }
                first = false;
                Display::fmt(c.head(), f)?;
                t = c.tail();
            }
            Term::Nil => break,
            tail => {
                f.write_char('|')?;
                Display::fmt(tail, f)?;
                break;
            }
        }
    }
    f.write_char(']')
}

fn write_string(s: &str, f: &mut Formatter<'_>) -> fmt::Result {
    f.write_char('"')?;
    for c in s.chars() {
        match c {
            '"' => f.write_str("\\\"")?,
            '\\' => f.write_str("\\\\")?,
            '\n' => f.write_str("\\n")?,
            '\r' => f.write_str("\\r")?,
            c => f.write_char(c)?,
        }
    }
    f.write_char('"')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(s: &str) -> Term {
        Term::atom(s)
    }

    fn s(f: &str, args: Vec<Term>) -> Term {
        Term::structure(f, args)
    }

    #[test]
    fn literals() {
        assert_eq!(
            s("cupAt", vec![a("cup1"), a("table")]).to_string(),
            "cupAt(cup1,table)"
        );
        assert_eq!(a("table").to_string(), "table");
        assert_eq!(a(".print").to_string(), ".print");
        assert_eq!(a("'quoted atom'").to_string(), "'quoted atom'");
        assert_eq!(
            s("f", vec![s("g", vec![Term::var("X")]), Term::int(1)]).to_string(),
            "f(g(X),1)"
        );
    }

    #[test]
    fn strong_negation() {
        assert_eq!(Term::literal("p", true, vec![], vec![]).to_string(), "~p");
        assert_eq!(
            Term::literal("at", true, vec![a("home")], vec![]).to_string(),
            "~at(home)"
        );
    }

    #[test]
    fn annotations() {
        let t = Term::literal(
            "p",
            false,
            vec![a("a")],
            vec![a("x"), s("source", vec![a("self")])],
        );
        assert_eq!(t.to_string(), "p(a)[source(self),x]");
        let t = Term::literal("q", true, vec![], vec![Term::var("A"), a("b")]);
        assert_eq!(t.to_string(), "~q[b,A]");
    }

    #[test]
    fn lists() {
        assert_eq!(Term::nil().to_string(), "[]");
        assert_eq!(Term::list(vec![a("a"), a("b")]).to_string(), "[a,b]");
        assert_eq!(
            Term::list_with_tail(vec![a("a"), a("b")], Term::var("T")).to_string(),
            "[a,b|T]"
        );
        assert_eq!(
            Term::list(vec![Term::list(vec![]), Term::list(vec![Term::int(1)])]).to_string(),
            "[[],[1]]"
        );
        // A tail that is neither a list nor a variable (only unification can build one).
        assert_eq!(Term::cons(a("a"), a("b")).to_string(), "[a|b]");
    }

    #[test]
    fn strings() {
        assert_eq!(Term::string("a string").to_string(), "\"a string\"");
        assert_eq!(Term::string("").to_string(), "\"\"");
        assert_eq!(Term::string("say \"hi\"").to_string(), r#""say \"hi\"""#);
        assert_eq!(Term::string("a\\b").to_string(), r#""a\\b""#);
        assert_eq!(Term::string("l1\nl2").to_string(), r#""l1\nl2""#);
        assert_eq!(Term::string("tab\there").to_string(), "\"tab\there\"");
    }

    #[test]
    fn integral_numbers() {
        assert_eq!(Term::int(3).to_string(), "3");
        assert_eq!(Term::int(-2).to_string(), "-2");
        assert_eq!(Term::int(0).to_string(), "0");
        assert_eq!(Term::num(-0.0).to_string(), "0");
        assert_eq!(Term::num(3.0).to_string(), "3");
        assert_eq!(Term::num(1e15).to_string(), "1000000000000000");
        assert_eq!(Term::num(1e18).to_string(), "1000000000000000000");
        // Beyond `long`, Jason falls back to `Double.toString`.
        assert_eq!(Term::num(1e19).to_string(), "1.0E19");
        assert_eq!(Term::num(-1e19).to_string(), "-1.0E19");
        // `Math.round(2^63)` saturates to `Long.MAX_VALUE`, which equals 2^63 as a double.
        assert_eq!(Term::num(2f64.powi(63)).to_string(), "9223372036854775807");
        assert_eq!(
            Term::num(-(2f64.powi(63))).to_string(),
            "-9223372036854775808"
        );
    }

    #[test]
    fn fractional_numbers() {
        assert_eq!(Term::num(1.5).to_string(), "1.5");
        assert_eq!(Term::num(0.1).to_string(), "0.1");
        assert_eq!(Term::num(-0.25).to_string(), "-0.25");
        assert_eq!(Term::num(0.001).to_string(), "0.001");
        assert_eq!(Term::num(0.1 + 0.2).to_string(), "0.30000000000000004");
        assert_eq!(Term::num(1234567.5).to_string(), "1234567.5");
        assert_eq!(Term::num(1.5e-5).to_string(), "1.5E-5");
        assert_eq!(Term::num(0.0001).to_string(), "1.0E-4");
        assert_eq!(Term::num(-2.5e-7).to_string(), "-2.5E-7");
        assert_eq!(Term::num(1.2345e20).to_string(), "1.2345E20");
        assert_eq!(Term::num(f64::INFINITY).to_string(), "Infinity");
        assert_eq!(Term::num(f64::NEG_INFINITY).to_string(), "-Infinity");
    }

    #[test]
    fn java_double_string_cases() {
        assert_eq!(java_double_string(1.0), "1.0");
        assert_eq!(java_double_string(100.0), "100.0");
        assert_eq!(java_double_string(1e7), "1.0E7");
        assert_eq!(java_double_string(9999999.0), "9999999.0");
        assert_eq!(java_double_string(0.0), "0.0");
        assert_eq!(java_double_string(-0.0), "-0.0");
        assert_eq!(java_double_string(f64::MAX), "1.7976931348623157E308");
        assert_eq!(
            java_double_string(f64::MIN_POSITIVE),
            "2.2250738585072014E-308"
        );
        assert_eq!(java_double_string(4.9e-324), "4.9E-324");
    }

    #[test]
    fn variables() {
        assert_eq!(Term::var("X").to_string(), "X");
        assert_eq!(Term::var("_Name").to_string(), "_Name");
        assert_eq!(Term::Var(Var::anonymous(3)).to_string(), "_3");
        assert_eq!(Term::var("X").rename_apart(5).to_string(), "_5X");
        assert_eq!(
            Term::Var(Var::anonymous(3)).rename_apart(5).to_string(),
            "_5_3"
        );
    }

    #[test]
    fn debug_is_jason_form() {
        assert_eq!(format!("{:?}", s("f", vec![a("a")])), "f(a)");
    }
}
