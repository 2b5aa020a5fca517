//! The small term parser of `.term2string`: it reads back the simple terms only (numbers,
//! strings, atoms, structures and lists of these), so an unbound first argument gets an
//! answer only where this model is sure to agree with Jason's parser.

use crate::model::Term;

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
