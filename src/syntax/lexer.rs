//! The AgentSpeak lexer, following the token rules of Jason's `AS2JavaParser.jj`.
//!
//! Notable rules kept from Jason: an atom may contain dots (`.print`, `time.check`,
//! `math.abs`), so `a.b` is one atom while `a.` followed by a blank is an atom and the end
//! dot; `_Name` is an (unnamed-style) variable; tokens are matched longest first, so `X<-1`
//! lexes `<-`, exactly as in Jason.

use super::diagnostic::Diagnostic;
use super::source::{FileId, Span};
use std::fmt;

/// One token kind.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// `foo`, `.print`, `time.check`, `'quoted atom'` (quotes kept).
    Atom(String),
    /// `Foo`.
    Var(String),
    /// `_`, `_Foo`, `_12`.
    UnnamedVar(String),
    /// An integer literal.
    Int(i64),
    /// A floating-point literal (or an integer too large for `i64`).
    Float(f64),
    /// A string literal, escapes decoded.
    Str(String),
    /// `true`
    True,
    /// `false`
    False,
    /// `not`
    Not,
    /// `div`
    Div,
    /// `mod`
    Mod,
    /// `begin`
    Begin,
    /// `end`
    End,
    /// `if`
    If,
    /// `else`
    Else,
    /// `elif`
    Elif,
    /// `for`
    For,
    /// `while`
    While,
    /// `@`
    At,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// `,`
    Comma,
    /// `.` ending a clause
    Dot,
    /// `;`
    Semi,
    /// `:`
    Colon,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `**`
    Pow,
    /// `^`
    Caret,
    /// `!`
    Bang,
    /// `!!`
    BangBang,
    /// `?`
    Question,
    /// `~`
    Tilde,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    EqEq,
    /// `\==`
    NotEqEq,
    /// `=`
    Eq,
    /// `=..`
    Univ,
    /// `|`
    Bar,
    /// `&`
    Amp,
    /// `|&|`
    ParAnd,
    /// `|||`
    ParOr,
    /// `<-`
    LeftArrow,
    /// `<:`
    GoalCond,
    /// `:-`
    RuleSep,
    /// `::`
    NsSep,
    /// End of input.
    Eof,
}

impl Tok {
    /// How the token reads in "found ..." messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Atom(a) => format!("atom `{a}`"),
            Tok::Var(v) | Tok::UnnamedVar(v) => format!("variable `{v}`"),
            Tok::Int(i) => format!("number `{i}`"),
            Tok::Float(x) => format!("number `{x}`"),
            Tok::Str(_) => "a string".to_string(),
            Tok::Eof => "end of file".to_string(),
            other => format!("`{other}`"),
        }
    }
}

impl fmt::Display for Tok {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Tok::Atom(a) | Tok::Var(a) | Tok::UnnamedVar(a) => return f.write_str(a),
            Tok::Int(i) => return write!(f, "{i}"),
            Tok::Float(x) => return write!(f, "{x:?}"),
            Tok::Str(s) => return write!(f, "{s:?}"),
            Tok::True => "true",
            Tok::False => "false",
            Tok::Not => "not",
            Tok::Div => "div",
            Tok::Mod => "mod",
            Tok::Begin => "begin",
            Tok::End => "end",
            Tok::If => "if",
            Tok::Else => "else",
            Tok::Elif => "elif",
            Tok::For => "for",
            Tok::While => "while",
            Tok::At => "@",
            Tok::LParen => "(",
            Tok::RParen => ")",
            Tok::LBracket => "[",
            Tok::RBracket => "]",
            Tok::LBrace => "{",
            Tok::RBrace => "}",
            Tok::Comma => ",",
            Tok::Dot => ".",
            Tok::Semi => ";",
            Tok::Colon => ":",
            Tok::Plus => "+",
            Tok::Minus => "-",
            Tok::Star => "*",
            Tok::Slash => "/",
            Tok::Pow => "**",
            Tok::Caret => "^",
            Tok::Bang => "!",
            Tok::BangBang => "!!",
            Tok::Question => "?",
            Tok::Tilde => "~",
            Tok::Lt => "<",
            Tok::Le => "<=",
            Tok::Gt => ">",
            Tok::Ge => ">=",
            Tok::EqEq => "==",
            Tok::NotEqEq => "\\==",
            Tok::Eq => "=",
            Tok::Univ => "=..",
            Tok::Bar => "|",
            Tok::Amp => "&",
            Tok::ParAnd => "|&|",
            Tok::ParOr => "|||",
            Tok::LeftArrow => "<-",
            Tok::GoalCond => "<:",
            Tok::RuleSep => ":-",
            Tok::NsSep => "::",
            Tok::Eof => "end of file",
        };
        f.write_str(s)
    }
}

/// A token and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it is.
    pub span: Span,
}

fn is_char(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Splits `text` into tokens. Lexical errors (a stray character, an unterminated string or
/// comment) are reported and skipped, so the parser still sees the rest of the file. The
/// result always ends with [`Tok::Eof`].
pub fn lex(file: FileId, text: &str) -> (Vec<Token>, Vec<Diagnostic>) {
    let b = text.as_bytes();
    let mut toks = Vec::new();
    let mut errs = Vec::new();
    // A byte-order mark opens some files saved on Windows: it is not part of the text.
    let mut i = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let span = |s: usize, e: usize| Span::new(file, s, e);
    while i < b.len() {
        let c = b[i];
        let start = i;
        // Whitespace and comments.
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
                i += 1;
            }
            continue;
        }
        if c == b'/' && b.get(i + 1) == Some(&b'*') {
            match text[i + 2..].find("*/") {
                Some(k) => i = i + 2 + k + 2,
                None => {
                    errs.push(Diagnostic::syntax(
                        span(start, start + 2),
                        "unterminated block comment",
                        "this comment is never closed with `*/`",
                    ));
                    i = b.len();
                }
            }
            continue;
        }
        let tok = if c.is_ascii_lowercase()
            || (c == b'.' && b.get(i + 1).is_some_and(|&d| is_char(d)) && !starts_number(b, i))
        {
            // ATOM: (lc | "." CHAR) (CHAR | "." CHAR)*
            i += if c == b'.' { 2 } else { 1 };
            loop {
                if i < b.len() && is_char(b[i]) {
                    i += 1;
                } else if i + 1 < b.len() && b[i] == b'.' && is_char(b[i + 1]) {
                    i += 2;
                } else {
                    break;
                }
            }
            let word = &text[start..i];
            match word {
                "true" => Tok::True,
                "false" => Tok::False,
                "not" => Tok::Not,
                "div" => Tok::Div,
                "mod" => Tok::Mod,
                "begin" => Tok::Begin,
                "end" => Tok::End,
                "if" => Tok::If,
                "else" => Tok::Else,
                "elif" => Tok::Elif,
                "for" => Tok::For,
                "while" => Tok::While,
                _ => Tok::Atom(word.to_string()),
            }
        } else if c.is_ascii_uppercase() {
            while i < b.len() && is_char(b[i]) {
                i += 1;
            }
            Tok::Var(text[start..i].to_string())
        } else if c == b'_' {
            while i < b.len() && is_char(b[i]) {
                i += 1;
            }
            Tok::UnnamedVar(text[start..i].to_string())
        } else if c.is_ascii_digit() || starts_number(b, i) {
            let (tok, end) = lex_number(text, i);
            i = end;
            tok
        } else if c == b'"' {
            match lex_string(text, i, &mut errs, file) {
                Ok((s, end)) => {
                    i = end;
                    Tok::Str(s)
                }
                Err((msg, end)) => {
                    errs.push(Diagnostic::syntax(span(start, end), msg, ""));
                    i = end;
                    continue;
                }
            }
        } else if c == b'\'' {
            match text[i + 1..].find('\'') {
                Some(k) => {
                    i = i + 1 + k + 1;
                    Tok::Atom(text[start..i].to_string())
                }
                None => {
                    errs.push(Diagnostic::syntax(
                        span(start, start + 1),
                        "unterminated quoted atom",
                        "this `'` is never closed",
                    ));
                    i = b.len();
                    continue;
                }
            }
        } else {
            let rest = &b[i..];
            let ops: &[(&str, Tok)] = &[
                ("|&|", Tok::ParAnd),
                ("|||", Tok::ParOr),
                ("\\==", Tok::NotEqEq),
                ("=..", Tok::Univ),
                ("**", Tok::Pow),
                ("!!", Tok::BangBang),
                ("<=", Tok::Le),
                (">=", Tok::Ge),
                ("==", Tok::EqEq),
                ("<-", Tok::LeftArrow),
                ("<:", Tok::GoalCond),
                (":-", Tok::RuleSep),
                ("::", Tok::NsSep),
                ("@", Tok::At),
                ("(", Tok::LParen),
                (")", Tok::RParen),
                ("[", Tok::LBracket),
                ("]", Tok::RBracket),
                ("{", Tok::LBrace),
                ("}", Tok::RBrace),
                (",", Tok::Comma),
                (".", Tok::Dot),
                (";", Tok::Semi),
                (":", Tok::Colon),
                ("+", Tok::Plus),
                ("-", Tok::Minus),
                ("*", Tok::Star),
                ("/", Tok::Slash),
                ("^", Tok::Caret),
                ("!", Tok::Bang),
                ("?", Tok::Question),
                ("~", Tok::Tilde),
                ("<", Tok::Lt),
                (">", Tok::Gt),
                ("=", Tok::Eq),
                ("|", Tok::Bar),
                ("&", Tok::Amp),
            ];
            match ops.iter().find(|(s, _)| rest.starts_with(s.as_bytes())) {
                Some((s, t)) => {
                    i += s.len();
                    t.clone()
                }
                None => {
                    let ch = text[i..].chars().next().unwrap_or('?');
                    i += ch.len_utf8();
                    errs.push(Diagnostic::syntax(
                        span(start, i),
                        format!("unexpected character `{}`", ch.escape_default()),
                        "not part of any AgentSpeak token",
                    ));
                    continue;
                }
            }
        };
        toks.push(Token {
            tok,
            span: span(start, i),
        });
    }
    toks.push(Token {
        tok: Tok::Eof,
        span: span(b.len(), b.len()),
    });
    (toks, errs)
}

/// `.5` is a number in Jason (NUMBER is declared before ATOM and both match `.5`).
fn starts_number(b: &[u8], i: usize) -> bool {
    b[i] == b'.' && b.get(i + 1).is_some_and(|d| d.is_ascii_digit())
}

/// NUMBER: `[0-9]+ | [0-9]* "." [0-9]+ exp? | [0-9]+ exp`, exp = `[eE][+-]?[0-9]+`.
fn lex_number(text: &str, start: usize) -> (Tok, usize) {
    let b = text.as_bytes();
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let exponent = |i: usize| -> Option<usize> {
        if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
            let mut j = i + 1;
            if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                j += 1;
            }
            let k = digits(j);
            (k > j).then_some(k)
        } else {
            None
        }
    };
    let int_end = digits(start);
    let mut end = int_end;
    let mut is_float = false;
    if end < b.len() && b[end] == b'.' && b.get(end + 1).is_some_and(|d| d.is_ascii_digit()) {
        end = digits(end + 1);
        is_float = true;
        if let Some(e) = exponent(end) {
            end = e;
        }
    } else if let Some(e) = exponent(end) {
        end = e;
        is_float = true;
    }
    let s = &text[start..end];
    let tok = if is_float {
        Tok::Float(s.parse().unwrap_or(f64::INFINITY))
    } else {
        match s.parse::<i64>() {
            Ok(n) => Tok::Int(n),
            Err(_) => Tok::Float(s.parse().unwrap_or(f64::INFINITY)),
        }
    };
    (tok, end)
}

/// A string literal with Jason's escapes: `\n \t \b \r \f \\ \' \"` and octal `\0`..`\377`.
/// A bad escape is reported and kept as written, so the string still ends at its closing
/// quote and one mistake gives one error.
fn lex_string(
    text: &str,
    start: usize,
    errs: &mut Vec<Diagnostic>,
    file: FileId,
) -> Result<(String, usize), (String, usize)> {
    let mut out = String::new();
    let mut chars = text[start + 1..].char_indices().peekable();
    while let Some((k, c)) = chars.next() {
        let pos = start + 1 + k;
        match c {
            '"' => return Ok((out, pos + 1)),
            '\n' | '\r' => {
                return Err((
                    "unterminated string: a string cannot span lines".into(),
                    pos,
                ));
            }
            '\\' => match chars.next() {
                Some((_, e)) => match e {
                    'n' => out.push('\n'),
                    't' => out.push('\t'),
                    'b' => out.push('\u{8}'),
                    'r' => out.push('\r'),
                    'f' => out.push('\u{c}'),
                    '\\' => out.push('\\'),
                    '\'' => out.push('\''),
                    '"' => out.push('"'),
                    '0'..='7' => {
                        let mut v = e as u32 - '0' as u32;
                        let max_len = if e <= '3' { 3 } else { 2 };
                        for _ in 1..max_len {
                            match chars.peek() {
                                Some(&(_, d @ '0'..='7')) => {
                                    v = v * 8 + (d as u32 - '0' as u32);
                                    chars.next();
                                }
                                _ => break,
                            }
                        }
                        out.push(char::from_u32(v).unwrap_or('\u{fffd}'));
                    }
                    other => {
                        errs.push(Diagnostic::syntax(
                            Span::new(file, pos, pos + 1 + other.len_utf8()),
                            format!("unknown escape `\\{}` in string", other.escape_default()),
                            "Jason knows \\n \\t \\b \\r \\f \\\\ \\' \\\" and octal escapes",
                        ));
                        out.push('\\');
                        out.push(other);
                    }
                },
                None => return Err(("unterminated string".into(), text.len())),
            },
            c => out.push(c),
        }
    }
    Err(("unterminated string".into(), text.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok> {
        let (t, e) = lex(FileId(0), s);
        assert!(e.is_empty(), "{e:?}");
        t.into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn atoms_with_dots_and_clause_end() {
        assert_eq!(
            toks("a(X). .print time.check"),
            vec![
                Tok::Atom("a".into()),
                Tok::LParen,
                Tok::Var("X".into()),
                Tok::RParen,
                Tok::Dot,
                Tok::Atom(".print".into()),
                Tok::Atom("time.check".into()),
                Tok::Eof
            ]
        );
        assert_eq!(
            toks("a.\nb"),
            vec![
                Tok::Atom("a".into()),
                Tok::Dot,
                Tok::Atom("b".into()),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn numbers() {
        assert_eq!(
            toks("12 1.5 .5 2e3 1.5E-2 1."),
            vec![
                Tok::Int(12),
                Tok::Float(1.5),
                Tok::Float(0.5),
                Tok::Float(2000.0),
                Tok::Float(0.015),
                Tok::Int(1),
                Tok::Dot,
                Tok::Eof
            ]
        );
    }

    #[test]
    fn operators_longest_first() {
        assert_eq!(
            toks("|&| ||| | \\== =.. == = <- <= <: :- :: :"),
            vec![
                Tok::ParAnd,
                Tok::ParOr,
                Tok::Bar,
                Tok::NotEqEq,
                Tok::Univ,
                Tok::EqEq,
                Tok::Eq,
                Tok::LeftArrow,
                Tok::Le,
                Tok::GoalCond,
                Tok::RuleSep,
                Tok::NsSep,
                Tok::Colon,
                Tok::Eof
            ]
        );
    }

    #[test]
    fn strings_and_comments() {
        assert_eq!(
            toks("\"a\\n\\\"b\\101\" // c\n /* d \n */ 'q a'"),
            vec![
                Tok::Str("a\n\"bA".into()),
                Tok::Atom("'q a'".into()),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn errors_are_located_and_skipped() {
        let (t, e) = lex(FileId(0), "a # b \"x");
        assert_eq!(e.len(), 2);
        assert_eq!(e[0].span.unwrap().start, 2);
        assert_eq!(t.len(), 3);
    }
}
