//! Mapping the contents of a TOML string back into the TOML text: formulas are parsed from the
//! string's value, then every span of the tree and of its diagnostics is rewritten to point
//! into the manifest file.

use crate::syntax::ast::*;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::{FileId, Span};
use std::ops::Range;

/// Where each byte of a TOML string's value lies in the TOML text.
///
/// Formulas are parsed from the string's *value* and every span of the resulting AST is then
/// mapped through this table ([`Remap`]). We chose that over parsing a copy of the manifest in
/// which everything but the string is blanked out, because blanking only works when the raw
/// text between the quotes equals the value byte for byte: with escapes (`"a \"b\""`,
/// `\u00e9`) or a multi-line string's line-ending backslash the two differ in length, while the
/// table maps every byte exactly, whatever the string form (basic, literal, multi-line, a
/// quoted key). Should the table ever disagree with `toml`'s own decoding, every span falls
/// back to the whole string value: coarse but never wrong.
pub(super) struct StrMap {
    /// The string value's range in the TOML text, quotes included.
    whole: Range<usize>,
    /// For each byte of the value: the raw range it came from (an escape maps all the bytes
    /// of its character to the whole escape). `None` when falling back.
    bytes: Option<Vec<(u32, u32)>>,
    /// Where the content ends in the raw text (the closing delimiter), for end-of-input spans.
    content_end: u32,
}

impl StrMap {
    pub(super) fn new(text: &str, whole: Range<usize>, value: &str) -> StrMap {
        let raw = text.get(whole.clone()).unwrap_or("");
        let base = whole.start as u32;
        match decode_raw(raw) {
            Some((decoded, bytes, end)) if decoded == value => StrMap {
                bytes: Some(
                    bytes
                        .into_iter()
                        .map(|(s, e)| (base + s as u32, base + e as u32))
                        .collect(),
                ),
                content_end: base + end as u32,
                whole,
            },
            _ => StrMap {
                content_end: whole.end as u32,
                whole,
                bytes: None,
            },
        }
    }

    /// Maps a span in the value to the TOML text.
    pub(super) fn map(&self, s: Span) -> Span {
        let Some(bytes) = &self.bytes else {
            return Span {
                file: s.file,
                start: self.whole.start as u32,
                end: self.whole.end as u32,
            };
        };
        let at = |i: u32| bytes.get(i as usize).map_or(self.content_end, |b| b.0);
        let start = at(s.start);
        let end = if s.end > s.start {
            bytes
                .get(s.end as usize - 1)
                .map_or(self.content_end, |b| b.1)
        } else {
            start
        };
        Span {
            file: s.file,
            start,
            end: end.max(start),
        }
    }

    /// Maps a byte range of the value.
    pub(super) fn map_range(&self, file: FileId, r: Range<usize>) -> Span {
        self.map(Span::new(file, r.start, r.end))
    }
}

/// Decodes a TOML string or key as written (delimiters included): its value, the raw range of
/// each value byte (relative to `raw`), and where the content ends. `None` for anything not
/// understood, which makes [`StrMap`] fall back.
#[allow(clippy::type_complexity)]
pub(super) fn decode_raw(raw: &str) -> Option<(String, Vec<(usize, usize)>, usize)> {
    let (delim, multi, basic) = if raw.starts_with("\"\"\"") {
        (3, true, true)
    } else if raw.starts_with("'''") {
        (3, true, false)
    } else if raw.starts_with('"') {
        (1, false, true)
    } else if raw.starts_with('\'') {
        (1, false, false)
    } else {
        (0, false, false) // a bare key
    };
    if raw.len() < 2 * delim {
        return None;
    }
    let end = raw.len() - delim;
    let mut i = delim;
    if multi {
        // TOML trims a newline right after the opening delimiter.
        if raw[i..end].starts_with("\r\n") {
            i += 2;
        } else if raw[i..end].starts_with('\n') {
            i += 1;
        }
    }
    let mut out = String::new();
    let mut map = Vec::new();
    while i < end {
        let c = raw.get(i..end)?.chars().next()?;
        if basic && c == '\\' {
            let e = raw.get(i + 1..end)?.chars().next()?;
            let hex = |n: usize| -> Option<char> {
                let h = raw.get(i + 2..i + 2 + n)?;
                if !h.bytes().all(|b| b.is_ascii_hexdigit()) {
                    return None;
                }
                char::from_u32(u32::from_str_radix(h, 16).ok()?)
            };
            let (ch, len) = match e {
                'b' => ('\u{8}', 2),
                't' => ('\t', 2),
                'n' => ('\n', 2),
                'f' => ('\u{c}', 2),
                'r' => ('\r', 2),
                'e' => ('\u{1b}', 2),
                '"' => ('"', 2),
                '\\' => ('\\', 2),
                'x' => (hex(2)?, 4),
                'u' => (hex(4)?, 6),
                'U' => (hex(8)?, 10),
                ' ' | '\t' | '\r' | '\n' if multi => {
                    // A line-ending backslash eats the whitespace and newlines that follow.
                    let rest = &raw[i + 1..end];
                    let skip = rest.len() - rest.trim_start_matches([' ', '\t', '\r', '\n']).len();
                    if !rest[..skip].contains('\n') {
                        return None;
                    }
                    i += 1 + skip;
                    continue;
                }
                _ => return None,
            };
            out.push(ch);
            map.extend(std::iter::repeat_n((i, i + len), ch.len_utf8()));
            i += len;
        } else {
            out.push(c);
            map.extend((i..i + c.len_utf8()).map(|k| (k, k + 1)));
            i += c.len_utf8();
        }
    }
    Some((out, map, end))
}

/// Rewrites every span of an AST node through a function. Exhaustive over the AST on purpose:
/// a new node kind is then a compile error here rather than a span left pointing at the
/// string's value instead of the TOML file.
pub(super) trait Remap {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span);
}

impl<T: Remap> Remap for Vec<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.iter_mut().for_each(|x| x.remap(f));
    }
}

impl<T: Remap> Remap for Option<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        if let Some(x) = self {
            x.remap(f);
        }
    }
}

impl<T: Remap> Remap for Box<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        (**self).remap(f);
    }
}

impl Remap for Span {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        *self = f(*self);
    }
}

impl Remap for Expr {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            ExprKind::Literal(l) => l.remap(f),
            ExprKind::Var(v) => v.remap(f),
            ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) => {}
            ExprKind::List(l) => l.remap(f),
            ExprKind::Unary(_, e) | ExprKind::Not(e) => e.remap(f),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                a.remap(f);
                b.remap(f);
            }
            ExprKind::PlanTerm(p) => p.remap(f),
        }
    }
}

impl Remap for Literal {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.namespace.remap(f);
        self.args.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Var {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.namespace.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Namespace {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
    }
}

impl Remap for ListExpr {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.elems.remap(f);
        self.tail.remap(f);
    }
}

impl Remap for PlanTerm {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            PlanTermKind::Plan(p) => p.remap(f),
            PlanTermKind::Trigger(t) => t.remap(f),
            PlanTermKind::Body(b) => b.remap(f),
            PlanTermKind::Rule(r) => r.remap(f),
        }
    }
}

impl Remap for Plan {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.label.remap(f);
        self.trigger.remap(f);
        self.context.remap(f);
        self.goal_condition.remap(f);
        self.body.remap(f);
        self.sub_plans.remap(f);
    }
}

impl Remap for Label {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Trigger {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.literal.remap(f);
    }
}

impl Remap for Rule {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.head.remap(f);
        self.body.remap(f);
    }
}

impl Remap for Body {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.steps.remap(f);
    }
}

impl Remap for Step {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            StepKind::Action(e)
            | StepKind::Achieve(e)
            | StepKind::AchieveNewFocus(e)
            | StepKind::Test(e)
            | StepKind::AddBel(e)
            | StepKind::AddBelEnd(e)
            | StepKind::AddBelNewFocus(e)
            | StepKind::DelBel(e)
            | StepKind::DelAddBel(e)
            | StepKind::DelBelNewFocus(e)
            | StepKind::Constraint(e) => e.remap(f),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    c.remap(f);
                    b.remap(f);
                }
                else_body.remap(f);
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                cond.remap(f);
                body.remap(f);
            }
            StepKind::Fork { branches, .. } => branches.remap(f),
            StepKind::Group(b) => b.remap(f),
        }
    }
}

impl Remap for Diagnostic {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        for l in &mut self.secondary {
            l.span.remap(f);
        }
    }
}
