//! A recursive-descent parser for Jason 3 AgentSpeak, rule for rule after Jason's
//! `AS2JavaParser.jj` (the grammar productions are named in the comments).
//!
//! Errors are collected, not thrown: after an error the parser skips to the end of the item
//! (the next `.` outside brackets, or a line that starts a new item in column 1) and goes on,
//! so one run reports every broken item of a file. Nesting is bounded so that no input can
//! exhaust the stack.
//!
//! The parser's state and token access are here; the productions are grouped by what they
//! read: `agent` (items, plans, triggers), `body` (plan bodies), `plan_term`, `expr`
//! (logical and arithmetic expressions) and `term` (literals, lists).

mod agent;
mod body;
mod expr;
mod plan_term;
mod term;
#[cfg(test)]
mod tests;

use super::ast::*;
use super::diagnostic::Diagnostic;
use super::lexer::{lex, Tok, Token};
use super::source::{FileId, Span};
use std::collections::HashMap;

/// Deepest nesting of brackets and expressions accepted; Jason programs stay far below it,
/// and the bound keeps hostile input from overflowing the stack.
const MAX_DEPTH: usize = 64;
/// After this many errors in one file the rest of the file is not parsed.
const MAX_ERRORS: usize = 50;

/// `Err(())` means a diagnostic has been recorded.
type PResult<T> = Result<T, ()>;

/// Parses one `.asl` text. The tree holds every item that parsed; the diagnostics hold every
/// error (the file is valid exactly when there is none).
pub fn parse_agent(file: FileId, text: &str) -> (AgentFile, Vec<Diagnostic>) {
    let (toks, lex_errors) = lex(file, text);
    let mut p = Parser::new(file, text, toks);
    p.errors = lex_errors;
    let items = p.items_until_eof();
    let file_ast = AgentFile {
        items,
        span: Span::new(file, 0, text.len()),
    };
    (file_ast, p.errors)
}

/// Parses a logical expression (a manifest formula, a context) that must fill `text`.
pub fn parse_expr(file: FileId, text: &str) -> Result<Expr, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.log_expr())
}

/// Parses one body formula (`navigateTo(table)`, `!storeCup(C)`, `+b`) that must fill `text`.
pub fn parse_step(file: FileId, text: &str) -> Result<Step, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.body_formula())
}

/// Parses one trigger (`+!storeCup(C)`) that must fill `text`.
pub fn parse_trigger(file: FileId, text: &str) -> Result<Trigger, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.trigger())
}

fn parse_whole<T>(
    file: FileId,
    text: &str,
    f: impl FnOnce(&mut Parser) -> PResult<T>,
) -> Result<T, Vec<Diagnostic>> {
    let (toks, lex_errors) = lex(file, text);
    if !lex_errors.is_empty() {
        return Err(lex_errors);
    }
    let mut p = Parser::new(file, text, toks);
    let r = f(&mut p);
    if r.is_ok() && p.peek() != &Tok::Eof {
        let _: PResult<()> = p.error_expected("the end of the formula");
    }
    match r {
        Ok(v) if p.errors.is_empty() => Ok(v),
        _ => Err(p.errors),
    }
}

struct Parser<'t> {
    file: FileId,
    text: &'t str,
    toks: Vec<Token>,
    pos: usize,
    /// End of the last consumed token, for spans.
    prev_end: u32,
    errors: Vec<Diagnostic>,
    depth: usize,
    /// Outcome of the speculative `log_expr` at a body position starting with `(`.
    speculated: HashMap<usize, Option<(Expr, usize, u32)>>,
    /// Plan terms already parsed, by position: result, position after, end, errors.
    plan_terms: HashMap<usize, PlanTermMemo>,
}

type PlanTermMemo = (PResult<Expr>, usize, u32, Vec<Diagnostic>);

impl<'t> Parser<'t> {
    fn new(file: FileId, text: &'t str, toks: Vec<Token>) -> Parser<'t> {
        Parser {
            file,
            text,
            toks,
            pos: 0,
            prev_end: 0,
            errors: Vec::new(),
            depth: 0,
            speculated: HashMap::new(),
            plan_terms: HashMap::new(),
        }
    }

    // ----- token access -------------------------------------------------------------------

    fn peek(&self) -> &Tok {
        self.peek_at(0)
    }

    fn peek_at(&self, k: usize) -> &Tok {
        let i = (self.pos + k).min(self.toks.len() - 1);
        &self.toks[i].tok
    }

    fn span_here(&self) -> Span {
        self.toks[self.pos.min(self.toks.len() - 1)].span
    }

    fn start(&self) -> u32 {
        self.span_here().start
    }

    fn span_from(&self, start: u32) -> Span {
        Span {
            file: self.file,
            start,
            end: self.prev_end.max(start),
        }
    }

    fn bump(&mut self) -> Token {
        let t = self.toks[self.pos.min(self.toks.len() - 1)].clone();
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
        }
        self.prev_end = t.span.end;
        t
    }

    fn eat(&mut self, tok: &Tok) -> bool {
        if self.peek() == tok {
            self.bump();
            true
        } else {
            false
        }
    }

    fn expect(&mut self, tok: &Tok, what: &str) -> PResult<Span> {
        if self.peek() == tok {
            Ok(self.bump().span)
        } else {
            self.error_expected(what)
        }
    }

    fn error_expected<T>(&mut self, what: &str) -> PResult<T> {
        let found = self.peek().describe();
        let span = self.span_here();
        self.error(Diagnostic::syntax(
            span,
            format!("expected {what}, found {found}"),
            format!("expected {what}"),
        ))
    }

    fn error<T>(&mut self, d: Diagnostic) -> PResult<T> {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
        Err(())
    }

    fn error_at<T>(&mut self, span: Span, msg: impl Into<String>, label: &str) -> PResult<T> {
        self.error(Diagnostic::syntax(span, msg, label))
    }

    /// Runs `f` one nesting level deeper, refusing input nested beyond [`MAX_DEPTH`].
    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        if self.depth >= MAX_DEPTH {
            let span = self.span_here();
            return self.error_at(
                span,
                format!("nesting deeper than {MAX_DEPTH} levels"),
                "too deeply nested",
            );
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    /// Whether the current token is the first on its line, in column 1.
    fn at_line_start(&self) -> bool {
        let s = self.span_here().start as usize;
        s == 0 || self.text.as_bytes().get(s - 1) == Some(&b'\n')
    }

    /// Skips what is left of a broken item: up to and including the next `.` outside
    /// brackets, or up to a token in column 1 that can start a new item.
    fn recover(&mut self, item_start: usize) {
        let mut depth = 0usize;
        loop {
            match self.peek() {
                Tok::Eof => return,
                Tok::Dot if depth == 0 => {
                    self.bump();
                    return;
                }
                Tok::Plus
                | Tok::Minus
                | Tok::At
                | Tok::Caret
                | Tok::Bang
                | Tok::LBrace
                | Tok::Atom(_)
                    if self.pos > item_start && self.at_line_start() =>
                {
                    return
                }
                Tok::LParen | Tok::LBracket | Tok::LBrace => depth += 1,
                Tok::RParen | Tok::RBracket | Tok::RBrace => depth = depth.saturating_sub(1),
                _ => {}
            }
            self.bump();
        }
    }

    fn too_many_errors(&self) -> bool {
        self.errors.len() >= MAX_ERRORS
    }
}
