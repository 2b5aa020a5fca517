//! Stage 2: tokens to an s-expression tree, with nesting bounded by [`MAX_DEPTH`] and
//! unbalanced parentheses repaired; and how its elements read in the "expected X, found Y"
//! messages of stage 3.

use super::lexer::{Atom, Tok, Token};
use super::MAX_DEPTH;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::{FileId, Span};

/// Sections that may only appear directly inside `(define ...)`: seeing one deeper means a `)`
/// is missing, which the tree builder repairs.
const SECTIONS: &[&str] = &[
    ":requirements",
    ":types",
    ":constants",
    ":predicates",
    ":functions",
    ":action",
    ":durative-action",
    ":derived",
    ":constraints",
];

#[derive(Debug)]
pub(super) struct SExpr {
    pub(super) kind: SKind,
    pub(super) span: Span,
}

#[derive(Debug)]
pub(super) enum SKind {
    /// The elements and the closing `)` (empty when the list was closed by repair).
    List(Vec<SExpr>, Span),
    Atom(Atom),
    /// Already reported (malformed token, too deep): whatever contains it fails silently.
    Bad,
}

struct Frame {
    open: Span,
    items: Vec<SExpr>,
}

/// Closes the innermost open list, its `)` at `close`.
fn close_frame(stack: &mut Vec<Frame>, top: &mut Vec<SExpr>, close: Span) {
    if let Some(f) = stack.pop() {
        let e = SExpr {
            span: f.open.to(close),
            kind: SKind::List(f.items, close),
        };
        stack.last_mut().map_or(&mut *top, |p| &mut p.items).push(e);
    }
}

/// Where a list closed by repair ends: just after its last element.
fn repair_close(f: &Frame) -> Span {
    let end = f.items.last().map_or(f.open.end, |e| e.span.end);
    Span {
        file: f.open.file,
        start: end,
        end,
    }
}

pub(super) fn build_tree(
    file: FileId,
    toks: &[Token],
    text_len: usize,
    errors: &mut Vec<Diagnostic>,
) -> Vec<SExpr> {
    let mut top = Vec::new();
    let mut stack: Vec<Frame> = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let t = &toks[i];
        match &t.tok {
            Tok::Open if stack.len() >= MAX_DEPTH => {
                // Skip the whole over-deep list, so the tree (and every recursion over it)
                // stays within the bound.
                let mut depth = 0usize;
                let mut end = t.span;
                while let Some(u) = toks.get(i) {
                    match u.tok {
                        Tok::Open => depth += 1,
                        Tok::Close => depth -= 1,
                        _ => {}
                    }
                    end = u.span;
                    i += 1;
                    if depth == 0 {
                        break;
                    }
                }
                errors.push(
                    Diagnostic::syntax(
                        t.span,
                        format!("nesting deeper than {MAX_DEPTH} levels"),
                        "too deeply nested",
                    )
                    .with_help("no PDDL domain needs this much nesting; simplify the formula"),
                );
                if let Some(f) = stack.last_mut() {
                    f.items.push(SExpr {
                        kind: SKind::Bad,
                        span: t.span.to(end),
                    });
                }
                continue;
            }
            Tok::Open => {
                let section = match toks.get(i + 1).map(|u| &u.tok) {
                    Some(Tok::Atom(Atom::Keyword(k))) if SECTIONS.contains(&k.as_str()) => Some(k),
                    _ => None,
                };
                if let (Some(k), true) = (section, stack.len() >= 2) {
                    // A section inside a section: a `)` is missing. Close everything down to
                    // `(define`, so that this section and the rest read normally.
                    errors.push(
                        Diagnostic::syntax(
                            stack[1].open,
                            format!("unclosed `(`: expected `)` before the next section `({k}`"),
                            "this `(` is not closed",
                        )
                        .with_secondary(t.span, "the next section starts here"),
                    );
                    while stack.len() > 1 {
                        let close = stack.last().map(repair_close).unwrap_or_default();
                        close_frame(&mut stack, &mut top, close);
                    }
                }
                stack.push(Frame {
                    open: t.span,
                    items: Vec::new(),
                });
            }
            Tok::Close => {
                if stack.is_empty() {
                    errors.push(Diagnostic::syntax(
                        t.span,
                        "unexpected `)`: it closes no `(`",
                        "unmatched",
                    ));
                } else {
                    close_frame(&mut stack, &mut top, t.span);
                }
            }
            Tok::Atom(_) | Tok::Bad => {
                let kind = match &t.tok {
                    Tok::Atom(a) => SKind::Atom(a.clone()),
                    _ => SKind::Bad,
                };
                let e = SExpr { kind, span: t.span };
                stack.last_mut().map_or(&mut top, |f| &mut f.items).push(e);
            }
        }
        i += 1;
    }
    if let Some(f) = stack.last() {
        errors.push(
            Diagnostic::syntax(
                f.open,
                "unclosed `(`: expected `)` before the end of the file",
                "this `(` is never closed",
            )
            .with_secondary(Span::new(file, text_len, text_len), "the file ends here"),
        );
        while let Some(f) = stack.last() {
            let close = repair_close(f);
            close_frame(&mut stack, &mut top, close);
        }
    }
    top
}

/// How an element reads in "found ..." messages.
pub(super) fn describe(e: &SExpr) -> String {
    match &e.kind {
        SKind::List(items, _) => match items.first().map(|h| &h.kind) {
            Some(SKind::Atom(a)) => format!("`({}`", atom_text(a)),
            _ => "`(`".to_string(),
        },
        SKind::Atom(Atom::Name(n)) => format!("name `{n}`"),
        SKind::Atom(Atom::Var(v)) => format!("variable `?{v}`"),
        SKind::Atom(Atom::Keyword(k)) => format!("keyword `{k}`"),
        SKind::Atom(Atom::Number(n)) => format!("number `{n}`"),
        SKind::Atom(a) => format!("`{}`", atom_text(a)),
        SKind::Bad => "an invalid token".to_string(),
    }
}

fn atom_text(a: &Atom) -> String {
    match a {
        Atom::Name(s) | Atom::Keyword(s) | Atom::Number(s) | Atom::Op(s) => s.clone(),
        Atom::Var(v) => format!("?{v}"),
        Atom::Dash => "-".to_string(),
    }
}

/// Where "found ..." points for an element: a list by its `(` and head, which is what
/// [`describe`] shows (the whole list may span many lines).
pub(super) fn head_span(e: &SExpr) -> Span {
    match &e.kind {
        SKind::List(items, _) => match items.first() {
            Some(h) if !matches!(h.kind, SKind::List(..)) => e.span.shrink_to_start().to(h.span),
            _ => Span {
                end: e.span.start + 1,
                ..e.span
            },
        },
        _ => e.span,
    }
}

/// The span and description of a list's end, for "expected X, found `)`".
pub(super) fn list_end(close: Span) -> (Span, String) {
    let found = if close.is_empty() {
        "the end of the list".to_string()
    } else {
        "`)`".to_string()
    };
    (close, found)
}

pub(super) fn name_of(e: &SExpr) -> Option<&str> {
    match &e.kind {
        SKind::Atom(Atom::Name(n)) => Some(n),
        _ => None,
    }
}

pub(super) fn keyword_of(e: &SExpr) -> Option<&str> {
    match &e.kind {
        SKind::Atom(Atom::Keyword(k)) => Some(k),
        _ => None,
    }
}

/// A name that is also a PDDL keyword, lower-cased (keywords ignore case); other names as is.
pub(super) fn keyword_name(n: &str) -> String {
    const KW: &[&str] = &[
        "and", "or", "not", "imply", "exists", "forall", "when", "define", "domain", "problem",
        "either",
    ];
    let l = n.to_ascii_lowercase();
    if KW.contains(&l.as_str()) {
        l
    } else {
        n.to_string()
    }
}
