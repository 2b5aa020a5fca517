//! The syntax of `ltl = "..."` properties (SPEC §1): temporal and boolean operators over
//! state formulas written in Jason's logical-expression syntax.
//!
//! Jason's lexer reads `->` as a minus, `[]` as a list and `U` as a variable, so the
//! temporal layer is read here, character by character, and each state formula between
//! operators is handed whole to the AgentSpeak expression parser. Precedence, loosest
//! first: `<->`, `->` (right), `~>`, `|`, `&`, `U` `R` `W` (right), then the prefix
//! operators `not`, `[]`, `<>`, `X`. A state formula ends at one of these operators outside
//! parentheses and strings, so `U`, `R`, `W` and `X` cannot name variables outside a
//! literal's arguments.

use crate::syntax::ast::Expr;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::parser::parse_expr;
use crate::syntax::source::{FileId, Span};

/// An LTL formula as written.
#[derive(Clone, Debug, PartialEq)]
pub struct LtlExpr {
    /// What it is.
    pub kind: LtlKind,
    /// Where it is written.
    pub span: Span,
}

/// The forms of an LTL formula.
#[derive(Clone, Debug, PartialEq)]
pub enum LtlKind {
    /// A state formula (literals, `not`, `&`, `|`, comparisons, `.count`, and the
    /// modalities `believes`, `intends`, ... as literals).
    State(Expr),
    /// A prefix operator.
    Unary(LtlUnary, Box<LtlExpr>),
    /// An infix operator.
    Binary(LtlBinary, Box<LtlExpr>, Box<LtlExpr>),
}

/// Prefix operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LtlUnary {
    /// `not`.
    Not,
    /// `X`: in the next state of the run.
    Next,
    /// `[]`: in every state from here on.
    Always,
    /// `<>`: in some state from here on.
    Eventually,
}

/// Infix operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LtlBinary {
    /// `&`.
    And,
    /// `|`.
    Or,
    /// `->`.
    Implies,
    /// `<->`.
    Iff,
    /// `~>`: `[](a -> <>b)`.
    LeadsTo,
    /// `U`.
    Until,
    /// `R`.
    Release,
    /// `W`: `a U b` or `[] a`.
    WeakUntil,
}

impl LtlExpr {
    /// Every state formula in it, left to right.
    pub fn states(&self) -> Vec<&Expr> {
        let mut out = Vec::new();
        self.collect(&mut out);
        out
    }

    fn collect<'a>(&'a self, out: &mut Vec<&'a Expr>) {
        match &self.kind {
            LtlKind::State(e) => out.push(e),
            LtlKind::Unary(_, a) => a.collect(out),
            LtlKind::Binary(_, a, b) => {
                a.collect(out);
                b.collect(out);
            }
        }
    }
}

impl super::spans::Remap for LtlExpr {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span = f(self.span);
        match &mut self.kind {
            LtlKind::State(e) => e.remap(f),
            LtlKind::Unary(_, a) => a.remap(f),
            LtlKind::Binary(_, a, b) => {
                a.remap(f);
                b.remap(f);
            }
        }
    }
}

/// Nesting bound: deeper formulas are refused rather than overflowing the stack.
const MAX_DEPTH: usize = 200;

/// Parses an LTL formula that must fill `text` (spans are offsets into `text`).
pub fn parse_ltl(file: FileId, text: &str) -> Result<LtlExpr, Vec<Diagnostic>> {
    let mut p = Ltl {
        file,
        text,
        pos: 0,
        depth: 0,
    };
    let e = p.iff()?;
    p.skip_ws();
    if p.pos < text.len() {
        return Err(p.error(p.pos, p.pos + 1, "expected an LTL operator or the end"));
    }
    Ok(e)
}

struct Ltl<'t> {
    file: FileId,
    text: &'t str,
    pos: usize,
    depth: usize,
}

type R = Result<LtlExpr, Vec<Diagnostic>>;

impl Ltl<'_> {
    fn error(&self, start: usize, end: usize, label: &str) -> Vec<Diagnostic> {
        let end = end.min(self.text.len()).max(start);
        let found = if start >= self.text.len() {
            "the end of the formula".to_string()
        } else {
            format!("`{}`", &self.text[start..end])
        };
        vec![Diagnostic::error(
            "syntax",
            format!("in an LTL formula: {label}, found {found}"),
        )
        .with_label(Span::new(self.file, start, end.max(start + 1)), label)]
    }

    fn skip_ws(&mut self) {
        let rest = &self.text[self.pos..];
        self.pos += rest.len() - rest.trim_start().len();
    }

    fn rest(&self) -> &str {
        &self.text[self.pos..]
    }

    /// Whether an operator word (`U`, `not`, ...) starts at the current position.
    fn word(&self, w: &str) -> bool {
        let r = self.rest();
        r.starts_with(w)
            && !r[w.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_alphanumeric() || c == '_')
    }

    fn node(&self, start: usize, kind: LtlKind) -> LtlExpr {
        LtlExpr {
            kind,
            span: Span::new(self.file, start, self.pos),
        }
    }

    fn binary(&self, op: LtlBinary, start: usize, a: LtlExpr, b: LtlExpr) -> LtlExpr {
        self.node(start, LtlKind::Binary(op, Box::new(a), Box::new(b)))
    }

    /// `a <-> b`, left-associative.
    fn iff(&mut self) -> R {
        let start = self.start();
        let mut a = self.implies()?;
        loop {
            self.skip_ws();
            if !self.rest().starts_with("<->") {
                return Ok(a);
            }
            self.pos += 3;
            let b = self.implies()?;
            a = self.binary(LtlBinary::Iff, start, a, b);
        }
    }

    /// `a -> b`, right-associative.
    fn implies(&mut self) -> R {
        let start = self.start();
        let a = self.leads_to()?;
        self.skip_ws();
        if !self.rest().starts_with("->") {
            return Ok(a);
        }
        self.pos += 2;
        let b = self.nested(|p| p.implies())?;
        Ok(self.binary(LtlBinary::Implies, start, a, b))
    }

    /// `a ~> b`, right-associative.
    fn leads_to(&mut self) -> R {
        let start = self.start();
        let a = self.or()?;
        self.skip_ws();
        if !self.rest().starts_with("~>") {
            return Ok(a);
        }
        self.pos += 2;
        let b = self.nested(|p| p.leads_to())?;
        Ok(self.binary(LtlBinary::LeadsTo, start, a, b))
    }

    fn or(&mut self) -> R {
        let start = self.start();
        let mut a = self.and()?;
        loop {
            self.skip_ws();
            if !self.rest().starts_with('|') {
                return Ok(a);
            }
            self.pos += 1;
            let b = self.and()?;
            a = self.binary(LtlBinary::Or, start, a, b);
        }
    }

    fn and(&mut self) -> R {
        let start = self.start();
        let mut a = self.until()?;
        loop {
            self.skip_ws();
            if !self.rest().starts_with('&') {
                return Ok(a);
            }
            self.pos += 1;
            let b = self.until()?;
            a = self.binary(LtlBinary::And, start, a, b);
        }
    }

    /// `a U b`, `a R b`, `a W b`, right-associative.
    fn until(&mut self) -> R {
        let start = self.start();
        let a = self.unary()?;
        self.skip_ws();
        let op = if self.word("U") {
            LtlBinary::Until
        } else if self.word("R") {
            LtlBinary::Release
        } else if self.word("W") {
            LtlBinary::WeakUntil
        } else {
            return Ok(a);
        };
        self.pos += 1;
        let b = self.nested(|p| p.until())?;
        Ok(self.binary(op, start, a, b))
    }

    fn start(&mut self) -> usize {
        self.skip_ws();
        self.pos
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self) -> R) -> R {
        if self.depth >= MAX_DEPTH {
            return Err(self.error(self.pos, self.pos + 1, "formula nested too deeply"));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn unary(&mut self) -> R {
        let start = self.start();
        let op = if self.word("not") {
            Some((LtlUnary::Not, 3))
        } else if self.rest().starts_with("[]") {
            Some((LtlUnary::Always, 2))
        } else if self.rest().starts_with("<>") {
            Some((LtlUnary::Eventually, 2))
        } else if self.word("X") {
            Some((LtlUnary::Next, 1))
        } else {
            None
        };
        if let Some((op, len)) = op {
            self.pos += len;
            let a = self.nested(|p| p.unary())?;
            return Ok(self.node(start, LtlKind::Unary(op, Box::new(a))));
        }
        if self.rest().starts_with('(') {
            self.pos += 1;
            let inner = self.nested(|p| p.iff())?;
            self.skip_ws();
            if !self.rest().starts_with(')') {
                return Err(self.error(self.pos, self.pos + 1, "expected `)`"));
            }
            self.pos += 1;
            // Keep the parentheses in the span, so a message points at what was written.
            return Ok(LtlExpr {
                span: Span::new(self.file, start, self.pos),
                ..inner
            });
        }
        self.state(start)
    }

    /// A state formula: everything up to the next LTL operator outside parentheses,
    /// brackets and strings.
    fn state(&mut self, start: usize) -> R {
        let bytes = self.text.as_bytes();
        let mut depth = 0usize;
        let mut i = start;
        let mut quote: Option<u8> = None;
        while i < bytes.len() {
            let c = bytes[i];
            if let Some(q) = quote {
                if c == b'\\' {
                    i += 1;
                } else if c == q {
                    quote = None;
                }
                i += 1;
                continue;
            }
            let rest = &self.text[i..];
            let boundary = |k: usize| {
                !self.text[..k]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_')
            };
            let is_word = |w: &str| {
                rest.starts_with(w)
                    && boundary(i)
                    && !rest[w.len()..]
                        .chars()
                        .next()
                        .is_some_and(|c| c.is_alphanumeric() || c == '_')
            };
            match c {
                b'"' | b'\'' => quote = Some(c),
                b'(' | b'[' => depth += 1,
                b')' | b']' if depth == 0 => break,
                b')' | b']' => depth -= 1,
                _ if depth > 0 => {}
                b'&' | b'|' => break,
                _ if rest.starts_with("->")
                    || rest.starts_with("<->")
                    || rest.starts_with("~>")
                    || rest.starts_with("<>") =>
                {
                    break
                }
                _ if is_word("U") || is_word("R") || is_word("W") || is_word("X") => break,
                _ => {}
            }
            i += 1;
        }
        let chunk = &self.text[start..i];
        let trimmed = chunk.trim_end();
        if trimmed.is_empty() {
            return Err(self.error(start, start + 1, "expected a state formula"));
        }
        let expr = parse_expr(self.file, trimmed).map_err(|ds| {
            ds.into_iter()
                .map(|mut d| {
                    super::spans::Remap::remap(&mut d, &|sp: Span| {
                        Span::new(sp.file, sp.start as usize + start, sp.end as usize + start)
                    });
                    d
                })
                .collect::<Vec<_>>()
        })?;
        let mut expr = expr;
        super::spans::Remap::remap(&mut expr, &|sp: Span| {
            Span::new(sp.file, sp.start as usize + start, sp.end as usize + start)
        });
        self.pos = start + trimmed.len();
        Ok(LtlExpr {
            kind: LtlKind::State(expr),
            span: Span::new(self.file, start, self.pos),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(e: &LtlExpr) -> String {
        match &e.kind {
            LtlKind::State(x) => format!("{{{}}}", crate::syntax::printer::print_expr(x)),
            LtlKind::Unary(op, a) => format!("{op:?}({})", show(a)),
            LtlKind::Binary(op, a, b) => format!("{op:?}({}, {})", show(a), show(b)),
        }
    }

    fn parse(text: &str) -> String {
        match parse_ltl(FileId(0), text) {
            Ok(e) => show(&e),
            Err(ds) => format!("error: {}", ds[0].message),
        }
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(
            parse("requested(storeCup(C)) ~> cupAt(C, dishwasher)"),
            "LeadsTo({requested(storeCup(C))}, {cupAt(C,dishwasher)})"
        );
        assert_eq!(
            parse("[](p -> <> q)"),
            "Always(Implies({p}, Eventually({q})))"
        );
        assert_eq!(parse("a -> b -> c"), "Implies({a}, Implies({b}, {c}))");
        assert_eq!(parse("a U b U c"), "Until({a}, Until({b}, {c}))");
        assert_eq!(parse("a & b | c"), "Or(And({a}, {b}), {c})");
        assert_eq!(parse("not a U b"), "Until(Not({a}), {b})");
        assert_eq!(parse("X X p <-> q"), "Iff(Next(Next({p})), {q})");
        assert_eq!(parse("p W q R r"), "WeakUntil({p}, Release({q}, {r}))");
        assert_eq!(
            parse("[]( holding(C) -> not wiping )"),
            "Always(Implies({holding(C)}, Not({wiping})))"
        );
    }

    #[test]
    fn state_formulas_keep_their_own_syntax() {
        assert_eq!(
            parse("<> .count(cupAt(C, _), 1)"),
            "Eventually({.count(cupAt(C,_),1)})"
        );
        assert_eq!(parse("[] ~p(a)"), "Always({~p(a)})");
        assert_eq!(parse("<>(X_1 > 2)"), "Eventually({X_1 > 2})");
        assert_eq!(parse("[] p(\"a -> b\")"), "Always({p(\"a -> b\")})");
        assert_eq!(parse("Xp"), "{Xp}");
    }

    #[test]
    fn errors_point_into_the_formula() {
        let e = parse_ltl(FileId(0), "[] (p -> ").unwrap_err();
        assert!(e[0].message.contains("expected a state formula"), "{e:?}");
        let e = parse_ltl(FileId(0), "[] p)").unwrap_err();
        assert!(e[0].message.contains("expected an LTL operator"), "{e:?}");
        let e = parse_ltl(FileId(0), "<> cupAt(C,, x)").unwrap_err();
        // The second comma.
        assert_eq!(e[0].span.map(|s| s.start), Some(11), "{e:?}");
        let deep = "not ".repeat(5000) + "p";
        assert!(parse_ltl(FileId(0), &deep).is_err());
    }
}
