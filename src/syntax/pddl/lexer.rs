//! Stage 1: PDDL text to tokens, parentheses and atoms, skipping `;` comments. A malformed word
//! is reported here and kept as [`Tok::Bad`], so that what contains it fails silently later.

use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::{FileId, Span};

/// A token that is not a parenthesis.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Atom {
    /// `pick-up`, `cup1`.
    Name(String),
    /// `?x`, without the `?`.
    Var(String),
    /// `:action`, lower-cased (keywords ignore case).
    Keyword(String),
    /// `3`, `-1.5`: only ever refused, but named so that the message is clear.
    Number(String),
    /// `=`, `<`, `<=`, `>`, `>=`, `+`, `*`, `/`.
    Op(String),
    /// A lone `-`: the type separator.
    Dash,
}

#[derive(Clone, Debug)]
pub(super) enum Tok {
    Open,
    Close,
    Atom(Atom),
    /// A malformed word, already reported: whatever contains it fails silently.
    Bad,
}

#[derive(Clone, Debug)]
pub(super) struct Token {
    pub(super) tok: Tok,
    pub(super) span: Span,
}

pub(super) fn lex(file: FileId, text: &str, errors: &mut Vec<Diagnostic>) -> Vec<Token> {
    let mut toks = Vec::new();
    let mut chars = text.char_indices().peekable();
    // A byte-order mark opens some files saved on Windows: it is not part of the text.
    chars.next_if(|&(_, c)| c == '\u{feff}');
    while let Some((i, c)) = chars.next() {
        let one = Span::new(file, i, i + c.len_utf8());
        match c {
            _ if c.is_whitespace() => {}
            ';' => while chars.next_if(|&(_, d)| d != '\n').is_some() {},
            '(' => toks.push(Token {
                tok: Tok::Open,
                span: one,
            }),
            ')' => toks.push(Token {
                tok: Tok::Close,
                span: one,
            }),
            _ => {
                // A word runs to the next blank, parenthesis or comment.
                let mut end = one.end as usize;
                while let Some((j, d)) =
                    chars.next_if(|&(_, d)| !(d.is_whitespace() || matches!(d, '(' | ')' | ';')))
                {
                    end = j + d.len_utf8();
                }
                let span = Span::new(file, i, end);
                let tok = match classify(&text[i..end]) {
                    Ok(a) => Tok::Atom(a),
                    Err((msg, help)) => {
                        errors.push(
                            Diagnostic::syntax(span, msg, "not a valid PDDL token").with_help(help),
                        );
                        Tok::Bad
                    }
                };
                toks.push(Token { tok, span });
            }
        }
    }
    toks
}

const NAME_RULE: &str = "a name is a letter followed by letters, digits, `-` or `_`";

fn classify(word: &str) -> Result<Atom, (String, &'static str)> {
    if let Some(rest) = word.strip_prefix('?') {
        return if is_name(rest) {
            Ok(Atom::Var(rest.to_string()))
        } else {
            Err((
                format!("invalid variable `{word}`"),
                "a variable is `?` followed by a name: a letter, then letters, digits, `-` or `_`",
            ))
        };
    }
    if let Some(rest) = word.strip_prefix(':') {
        return if is_name(rest) {
            Ok(Atom::Keyword(word.to_ascii_lowercase()))
        } else {
            Err((
                format!("invalid keyword `{word}`"),
                "a keyword is `:` followed by a name, such as `:action`",
            ))
        };
    }
    match word {
        "-" => return Ok(Atom::Dash),
        "=" | "<" | ">" | "<=" | ">=" | "+" | "*" | "/" => return Ok(Atom::Op(word.to_string())),
        _ => {}
    }
    if is_number(word) {
        return Ok(Atom::Number(word.to_string()));
    }
    if is_name(word) {
        return Ok(Atom::Name(word.to_string()));
    }
    Err((format!("invalid name `{word}`"), NAME_RULE))
}

fn is_name(s: &str) -> bool {
    let mut cs = s.chars();
    matches!(cs.next(), Some(c) if c.is_alphabetic())
        && cs.all(|c| c.is_alphanumeric() || c == '-' || c == '_')
}

fn is_number(s: &str) -> bool {
    let s = s.strip_prefix('-').unwrap_or(s);
    s.starts_with(|c: char| c.is_ascii_digit())
        && !s.ends_with('.')
        && s.chars().all(|c| c.is_ascii_digit() || c == '.')
        && s.matches('.').count() <= 1
}
