//! PDDL domains: lexer, parser and structural checks, with a [`Span`] on every node.
//!
//! bdi-check reads the robot's environment actions from a PDDL *domain*; problems are not read,
//! since the manifest gives the objects and the initial facts. We do not use the `pddl` crate
//! because its AST has no source positions, and every later type error must point at
//! `file:line:column` inside the `.pddl` file.
//!
//! [`parse_domain`] works in four stages, each collecting errors rather than stopping, so one
//! run reports every broken section:
//!
//! 1. a lexer turns the text into parentheses and atoms (names, `?variables`, `:keywords`,
//!    numbers, `-`), skipping `;` comments;
//! 2. the tokens are built into an s-expression tree. Nesting beyond [`MAX_DEPTH`] is refused
//!    (no input can exhaust the stack), and unbalanced parentheses are repaired: a section such
//!    as `(:action` that opens inside another section closes it first;
//! 3. the tree is read into a [`Domain`]; a broken section or action is reported and left out,
//!    and reading goes on with the next one;
//! 4. checks that need no other file: duplicate names, undeclared and cyclic types, undeclared
//!    predicates, arities, free variables.
//!
//! Conventions, chosen to be lenient where planners are:
//! * names are case-sensitive (Jason's `navigateTo(table)` is `(navigateTo table)`), while
//!   keywords (`define`, `and`, `forall`, `:action`, ...) ignore ASCII case as PDDL allows;
//! * features may be used without being listed in `:requirements` (typing, `or`, `forall`,
//!   ...), and sections may come in any order;
//! * constants used in actions but not declared in `(:constants ...)` are *not* errors, since in
//!   this project they may be objects listed in the manifest:
//!   [`Domain::undeclared_constants`] lists them for the caller to check;
//! * `either` types, numbers and everything numeric or temporal are refused with code `input`.

use super::diagnostic::Diagnostic;
use super::source::{FileId, Span};
use std::collections::{HashMap, HashSet};
use std::fmt;

/// Deepest nesting of parentheses accepted; real domains stay far below it, and the bound keeps
/// hostile input from overflowing the stack.
pub const MAX_DEPTH: usize = 64;
/// After this many errors in one file, further ones are dropped.
const MAX_ERRORS: usize = 50;

/// Requirements bdi-check understands (`:adl` and `:quantified-preconditions` are shorthands
/// for several of the others).
pub const SUPPORTED_REQUIREMENTS: &[&str] = &[
    ":strips",
    ":typing",
    ":negative-preconditions",
    ":equality",
    ":disjunctive-preconditions",
    ":existential-preconditions",
    ":universal-preconditions",
    ":quantified-preconditions",
    ":conditional-effects",
    ":adl",
];

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

// ===== AST =====================================================================================

/// A PDDL domain: the robot's environment actions and the vocabulary they use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Domain {
    /// The name in `(domain NAME)`.
    pub name: String,
    /// Where that name is.
    pub name_span: Span,
    /// `(:requirements ...)`, only supported ones.
    pub requirements: Vec<Requirement>,
    /// `(:types ...)`, in source order (`object` itself is implicit and not listed).
    pub types: Vec<TypeDecl>,
    /// `(:constants ...)`.
    pub constants: Vec<Constant>,
    /// `(:predicates ...)`.
    pub predicates: Vec<PredicateDecl>,
    /// Every `(:action ...)` that parsed.
    pub actions: Vec<ActionDecl>,
    /// The whole `(define ...)`.
    pub span: Span,
}

/// One requirement flag, such as `:typing`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Requirement {
    /// The flag with its colon, lower-cased: `:typing`.
    pub name: String,
    /// Where it is.
    pub span: Span,
}

/// A type declared in `(:types ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypeDecl {
    /// Its name.
    pub name: String,
    /// Its parent: the type after `-`, or `object`.
    pub parent: String,
    /// Where the parent is named (`None` when it defaults to `object`).
    pub parent_span: Option<Span>,
    /// Where the type's name is.
    pub span: Span,
}

/// A constant declared in `(:constants ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Constant {
    /// Its name.
    pub name: String,
    /// Its type (`object` when none is given).
    pub ty: String,
    /// Where the type is named (`None` when it defaults to `object`).
    pub ty_span: Option<Span>,
    /// Where the constant's name is.
    pub span: Span,
}

/// A typed variable: a parameter of a predicate or an action, or one bound by a quantifier.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypedVar {
    /// Its name without the `?`.
    pub name: String,
    /// Its type (`object` when none is given).
    pub ty: String,
    /// Where the type is named (`None` when it defaults to `object`).
    pub ty_span: Option<Span>,
    /// Where the variable is.
    pub span: Span,
}

/// A predicate declared in `(:predicates ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PredicateDecl {
    /// Its name.
    pub name: String,
    /// Where its name is.
    pub name_span: Span,
    /// Its parameters, in order.
    pub params: Vec<TypedVar>,
    /// The whole declaration `(p ?x - t)`.
    pub span: Span,
}

/// An `(:action ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActionDecl {
    /// Its name.
    pub name: String,
    /// Where its name is.
    pub name_span: Span,
    /// `:parameters`, empty when absent.
    pub params: Vec<TypedVar>,
    /// `:precondition`, if given.
    pub precondition: Option<Gd>,
    /// `:effect`, if given.
    pub effect: Option<Effect>,
    /// The whole `(:action ...)`.
    pub span: Span,
}

/// A goal description: a precondition or a part of one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Gd {
    /// What it is.
    pub kind: GdKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of goal description.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GdKind {
    /// `(and G...)`; `()` is the empty conjunction, which always holds.
    And(Vec<Gd>),
    /// `(or G...)`.
    Or(Vec<Gd>),
    /// `(not G)`.
    Not(Box<Gd>),
    /// `(imply G1 G2)`.
    Imply(Box<Gd>, Box<Gd>),
    /// `(exists (?x - t ...) G)`.
    Exists(Vec<TypedVar>, Box<Gd>),
    /// `(forall (?x - t ...) G)`.
    Forall(Vec<TypedVar>, Box<Gd>),
    /// `(p t1 t2)`.
    Atom(AtomicFormula),
    /// `(= t1 t2)`.
    Equal(PddlTerm, PddlTerm),
}

/// An effect: what an action changes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Effect {
    /// What it is.
    pub kind: EffectKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EffectKind {
    /// `(and E...)`; `()` is the empty effect.
    And(Vec<Effect>),
    /// `(p t...)`: the atom becomes true.
    Add(AtomicFormula),
    /// `(not (p t...))`: the atom becomes false.
    Delete(AtomicFormula),
    /// `(forall (?x - t ...) E)`.
    Forall(Vec<TypedVar>, Box<Effect>),
    /// `(when G E)`: `E` applies when `G` holds before the action.
    When(Box<Gd>, Box<Effect>),
}

/// `(p t1 ... tn)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AtomicFormula {
    /// The predicate's name.
    pub predicate: String,
    /// Where the predicate's name is.
    pub predicate_span: Span,
    /// The arguments.
    pub args: Vec<PddlTerm>,
    /// The whole atom.
    pub span: Span,
}

/// An argument of an atom: a variable or a constant.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PddlTerm {
    /// `?x`, stored without the `?`.
    Var {
        /// The name without `?`.
        name: String,
        /// Where it is.
        span: Span,
    },
    /// A constant or object name.
    Const {
        /// The name.
        name: String,
        /// Where it is.
        span: Span,
    },
}

impl PddlTerm {
    /// The name (without `?` for a variable).
    pub fn name(&self) -> &str {
        match self {
            PddlTerm::Var { name, .. } | PddlTerm::Const { name, .. } => name,
        }
    }

    /// Where the term is.
    pub fn span(&self) -> Span {
        match self {
            PddlTerm::Var { span, .. } | PddlTerm::Const { span, .. } => *span,
        }
    }

    /// Whether it is a `?variable`.
    pub fn is_var(&self) -> bool {
        matches!(self, PddlTerm::Var { .. })
    }
}

impl Gd {
    /// Every atom in the goal, in source order (equalities are not atoms).
    pub fn atoms(&self) -> Vec<&AtomicFormula> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms<'a>(&'a self, out: &mut Vec<&'a AtomicFormula>) {
        match &self.kind {
            GdKind::And(gs) | GdKind::Or(gs) => gs.iter().for_each(|g| g.collect_atoms(out)),
            GdKind::Not(g) | GdKind::Exists(_, g) | GdKind::Forall(_, g) => g.collect_atoms(out),
            GdKind::Imply(a, b) => {
                a.collect_atoms(out);
                b.collect_atoms(out);
            }
            GdKind::Atom(a) => out.push(a),
            GdKind::Equal(..) => {}
        }
    }

    /// Every term in the goal, in source order.
    fn collect_terms<'a>(&'a self, out: &mut Vec<&'a PddlTerm>) {
        match &self.kind {
            GdKind::And(gs) | GdKind::Or(gs) => gs.iter().for_each(|g| g.collect_terms(out)),
            GdKind::Not(g) | GdKind::Exists(_, g) | GdKind::Forall(_, g) => g.collect_terms(out),
            GdKind::Imply(a, b) => {
                a.collect_terms(out);
                b.collect_terms(out);
            }
            GdKind::Atom(a) => out.extend(a.args.iter()),
            GdKind::Equal(a, b) => out.extend([a, b]),
        }
    }
}

impl Effect {
    /// Every atom the effect may add (`true`) or delete (`false`), in source order, including
    /// those under `when` and `forall` (the conditions of `when` are not included).
    pub fn atoms(&self) -> Vec<(bool, &AtomicFormula)> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms<'a>(&'a self, out: &mut Vec<(bool, &'a AtomicFormula)>) {
        match &self.kind {
            EffectKind::And(es) => es.iter().for_each(|e| e.collect_atoms(out)),
            EffectKind::Add(a) => out.push((true, a)),
            EffectKind::Delete(a) => out.push((false, a)),
            EffectKind::Forall(_, e) | EffectKind::When(_, e) => e.collect_atoms(out),
        }
    }

    fn collect_terms<'a>(&'a self, out: &mut Vec<&'a PddlTerm>) {
        match &self.kind {
            EffectKind::And(es) => es.iter().for_each(|e| e.collect_terms(out)),
            EffectKind::Add(a) | EffectKind::Delete(a) => out.extend(a.args.iter()),
            EffectKind::Forall(_, e) => e.collect_terms(out),
            EffectKind::When(g, e) => {
                g.collect_terms(out);
                e.collect_terms(out);
            }
        }
    }
}

impl Domain {
    /// Whether a requirement is declared, counting the ones `:adl` and
    /// `:quantified-preconditions` imply.
    pub fn requires(&self, flag: &str) -> bool {
        let has = |f: &str| self.requirements.iter().any(|r| r.name == f);
        has(flag)
            || (has(":adl")
                && matches!(
                    flag,
                    ":strips"
                        | ":typing"
                        | ":negative-preconditions"
                        | ":disjunctive-preconditions"
                        | ":equality"
                        | ":existential-preconditions"
                        | ":universal-preconditions"
                        | ":quantified-preconditions"
                        | ":conditional-effects"
                ))
            || (has(":quantified-preconditions")
                && matches!(
                    flag,
                    ":existential-preconditions" | ":universal-preconditions"
                ))
    }

    /// The declaration of a type, if it is declared (`object` is implicit and has none).
    pub fn type_decl(&self, name: &str) -> Option<&TypeDecl> {
        self.types.iter().find(|t| t.name == name)
    }

    /// The declaration of a constant.
    pub fn constant(&self, name: &str) -> Option<&Constant> {
        self.constants.iter().find(|c| c.name == name)
    }

    /// The declaration of a predicate.
    pub fn predicate(&self, name: &str) -> Option<&PredicateDecl> {
        self.predicates.iter().find(|p| p.name == name)
    }

    /// The action of that name.
    pub fn action(&self, name: &str) -> Option<&ActionDecl> {
        self.actions.iter().find(|a| a.name == name)
    }

    /// The proper ancestors of a type, nearest first, ending with `object` (empty for `object`
    /// itself). An undeclared type has just `object`; a cycle stops the walk.
    pub fn type_ancestors(&self, ty: &str) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mut cur = ty;
        while let Some(t) = self.type_decl(cur) {
            if t.parent == ty || out.contains(&t.parent) || t.parent == "object" {
                break;
            }
            out.push(t.parent.clone());
            cur = &t.parent;
        }
        if ty != "object" {
            out.push("object".to_string());
        }
        out
    }

    /// Whether every object of type `a` is also of type `b` (a type is a subtype of itself, and
    /// every type of `object`).
    pub fn is_subtype(&self, a: &str, b: &str) -> bool {
        a == b || b == "object" || self.type_ancestors(a).iter().any(|t| t == b)
    }

    /// Every constant term in the actions' preconditions and effects, in source order, with
    /// where it is (declared or not).
    pub fn constant_uses(&self) -> Vec<(&str, Span)> {
        let mut terms = Vec::new();
        for a in &self.actions {
            if let Some(g) = &a.precondition {
                g.collect_terms(&mut terms);
            }
            if let Some(e) = &a.effect {
                e.collect_terms(&mut terms);
            }
        }
        terms
            .into_iter()
            .filter(|t| !t.is_var())
            .map(|t| (t.name(), t.span()))
            .collect()
    }

    /// The constant terms used in actions that `(:constants ...)` does not declare, every
    /// occurrence in source order. They are not errors here: in this project they may be
    /// objects of the manifest, so the caller checks them (and reports at these spans).
    pub fn undeclared_constants(&self) -> Vec<(&str, Span)> {
        let declared: HashSet<&str> = self.constants.iter().map(|c| c.name.as_str()).collect();
        self.constant_uses()
            .into_iter()
            .filter(|(n, _)| !declared.contains(n))
            .collect()
    }
}

// ----- printing, in PDDL syntax (for messages) -------------------------------------------------

impl fmt::Display for PddlTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PddlTerm::Var { name, .. } => write!(f, "?{name}"),
            PddlTerm::Const { name, .. } => f.write_str(name),
        }
    }
}

impl fmt::Display for AtomicFormula {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}", self.predicate)?;
        for a in &self.args {
            write!(f, " {a}")?;
        }
        f.write_str(")")
    }
}

impl fmt::Display for TypedVar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "?{} - {}", self.name, self.ty)
    }
}

/// `(?x - t ?y - u)`.
fn write_vars(f: &mut fmt::Formatter<'_>, vars: &[TypedVar]) -> fmt::Result {
    f.write_str("(")?;
    for (i, v) in vars.iter().enumerate() {
        if i > 0 {
            f.write_str(" ")?;
        }
        write!(f, "{v}")?;
    }
    f.write_str(")")
}

/// `(op a b ...)` for a list of displayable parts.
fn write_list<T: fmt::Display>(f: &mut fmt::Formatter<'_>, op: &str, parts: &[T]) -> fmt::Result {
    write!(f, "({op}")?;
    for p in parts {
        write!(f, " {p}")?;
    }
    f.write_str(")")
}

impl fmt::Display for Gd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            GdKind::And(gs) => write_list(f, "and", gs),
            GdKind::Or(gs) => write_list(f, "or", gs),
            GdKind::Not(g) => write!(f, "(not {g})"),
            GdKind::Imply(a, b) => write!(f, "(imply {a} {b})"),
            GdKind::Exists(vs, g) | GdKind::Forall(vs, g) => {
                let q = if matches!(self.kind, GdKind::Exists(..)) {
                    "exists"
                } else {
                    "forall"
                };
                write!(f, "({q} ")?;
                write_vars(f, vs)?;
                write!(f, " {g})")
            }
            GdKind::Atom(a) => write!(f, "{a}"),
            GdKind::Equal(a, b) => write!(f, "(= {a} {b})"),
        }
    }
}

impl fmt::Display for Effect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            EffectKind::And(es) => write_list(f, "and", es),
            EffectKind::Add(a) => write!(f, "{a}"),
            EffectKind::Delete(a) => write!(f, "(not {a})"),
            EffectKind::Forall(vs, e) => {
                f.write_str("(forall ")?;
                write_vars(f, vs)?;
                write!(f, " {e})")
            }
            EffectKind::When(g, e) => write!(f, "(when {g} {e})"),
        }
    }
}

/// A goal description in PDDL syntax, for messages (the same as its `Display`).
pub fn print_gd(gd: &Gd) -> String {
    gd.to_string()
}

/// An effect in PDDL syntax, for messages (the same as its `Display`).
pub fn print_effect(effect: &Effect) -> String {
    effect.to_string()
}

// ===== entry point =============================================================================

/// Parses and checks one PDDL domain.
///
/// The domain is `Some` when the `(define (domain NAME) ...)` frame was recognised; it then
/// holds every section and action that parsed (a broken action is left out). The diagnostics
/// hold every error, sorted by position: the domain is valid exactly when there is none.
/// Codes: `syntax` for malformed text, `input` for unsupported features and for structural
/// errors (duplicates, undeclared types or predicates, arity, free variables, type cycles).
pub fn parse_domain(file: FileId, text: &str) -> (Option<Domain>, Vec<Diagnostic>) {
    let mut errors = Vec::new();
    let toks = lex(file, text, &mut errors);
    let top = build_tree(file, &toks, text.len(), &mut errors);
    let mut r = Reader {
        file,
        errors,
        types_broken: false,
        predicates_broken: false,
    };
    let domain = r.domain(&top, text.len());
    let mut errors = r.errors;
    if let Some(d) = &domain {
        Checker::new(d, !r.types_broken, !r.predicates_broken, &mut errors).run();
    }
    errors.truncate(MAX_ERRORS);
    errors.sort_by_key(|d| d.span.map(|s| (s.file, s.start)));
    (domain, errors)
}

// ===== lexer ===================================================================================

/// A token that is not a parenthesis.
#[derive(Clone, Debug, PartialEq)]
enum Atom {
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
enum Tok {
    Open,
    Close,
    Atom(Atom),
    /// A malformed word, already reported: whatever contains it fails silently.
    Bad,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    span: Span,
}

fn lex(file: FileId, text: &str, errors: &mut Vec<Diagnostic>) -> Vec<Token> {
    let mut toks = Vec::new();
    let mut chars = text.char_indices().peekable();
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

// ===== s-expression tree =======================================================================

#[derive(Debug)]
struct SExpr {
    kind: SKind,
    span: Span,
}

#[derive(Debug)]
enum SKind {
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

fn build_tree(
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
fn describe(e: &SExpr) -> String {
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
fn head_span(e: &SExpr) -> Span {
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
fn list_end(close: Span) -> (Span, String) {
    let found = if close.is_empty() {
        "the end of the list".to_string()
    } else {
        "`)`".to_string()
    };
    (close, found)
}

fn name_of(e: &SExpr) -> Option<&str> {
    match &e.kind {
        SKind::Atom(Atom::Name(n)) => Some(n),
        _ => None,
    }
}

fn keyword_of(e: &SExpr) -> Option<&str> {
    match &e.kind {
        SKind::Atom(Atom::Keyword(k)) => Some(k),
        _ => None,
    }
}

/// A name that is also a PDDL keyword, lower-cased (keywords ignore case); other names as is.
fn keyword_name(n: &str) -> String {
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

// ===== reading the tree into a domain ==========================================================

/// `Err(())` means a diagnostic has been recorded.
type PResult<T> = Result<T, ()>;

/// One entry of a typed list: a name or variable and its type, if given.
struct Typed {
    name: String,
    span: Span,
    ty: Option<(String, Span)>,
}

impl Typed {
    fn ty(&self) -> (String, Option<Span>) {
        match &self.ty {
            Some((t, s)) => (t.clone(), Some(*s)),
            None => ("object".to_string(), None),
        }
    }

    fn into_var(self) -> TypedVar {
        let (ty, ty_span) = self.ty();
        TypedVar {
            name: self.name,
            ty,
            ty_span,
            span: self.span,
        }
    }
}

struct Reader {
    file: FileId,
    errors: Vec<Diagnostic>,
    /// A `(:types` part did not parse: undeclared types are then not reported.
    types_broken: bool,
    /// A `(:predicates` part did not parse: undeclared predicates are then not reported.
    predicates_broken: bool,
}

impl Reader {
    fn error<T>(&mut self, d: Diagnostic) -> PResult<T> {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
        Err(())
    }

    /// "expected WHAT, found FOUND" at `span`.
    fn expected<T>(&mut self, span: Span, what: &str, found: String) -> PResult<T> {
        self.error(Diagnostic::syntax(
            span,
            format!("expected {what}, found {found}"),
            format!("expected {what}"),
        ))
    }

    /// "expected WHAT" about element `e` (silent when `e` was already reported).
    fn expected_elem<T>(&mut self, e: &SExpr, what: &str) -> PResult<T> {
        if matches!(e.kind, SKind::Bad) {
            return Err(());
        }
        self.expected(head_span(e), what, describe(e))
    }

    /// Adds help to the diagnostic just reported.
    fn help_last(&mut self, help: &str) {
        if let Some(d) = self.errors.last_mut() {
            d.help = Some(help.to_string());
        }
    }

    fn unsupported<T>(&mut self, span: Span, msg: String, help: &str) -> PResult<T> {
        self.error(
            Diagnostic::error("input", msg)
                .with_label(span, "not supported by bdi-check")
                .with_help(help),
        )
    }

    fn domain(&mut self, top: &[SExpr], text_len: usize) -> Option<Domain> {
        let eof = Span::new(self.file, text_len, text_len);
        let Some(def_index) = top.iter().position(|e| matches!(e.kind, SKind::List(..))) else {
            match top.iter().find(|e| !matches!(e.kind, SKind::Bad)) {
                Some(e) => {
                    let _: PResult<()> = self.expected_elem(e, "`(define (domain NAME) ...)`");
                }
                None if top.is_empty() => {
                    let _: PResult<()> = self.expected(
                        eof,
                        "`(define (domain NAME) ...)`",
                        "the end of the file".to_string(),
                    );
                }
                None => {}
            }
            return None;
        };
        if let Some(e) = top[..def_index]
            .iter()
            .find(|e| !matches!(e.kind, SKind::Bad))
        {
            let _: PResult<()> = self.expected_elem(e, "`(define (domain NAME) ...)`");
        }
        let def = &top[def_index];
        let SKind::List(items, close) = &def.kind else {
            return None;
        };
        // `(define`
        match items.first() {
            Some(h) if name_of(h).map(keyword_name).as_deref() == Some("define") => {}
            Some(h) => {
                if !matches!(h.kind, SKind::Bad) {
                    let _: PResult<()> = self.expected_elem(def, "`(define (domain NAME) ...)`");
                }
                return None;
            }
            None => {
                let (s, f) = list_end(*close);
                let _: PResult<()> = self.expected(s, "`define`", f);
                return None;
            }
        }
        // `(domain NAME)`
        let header = self.header(items.get(1), *close);
        let mut d = Domain {
            name: String::new(),
            name_span: def.span.shrink_to_start(),
            requirements: Vec::new(),
            types: Vec::new(),
            constants: Vec::new(),
            predicates: Vec::new(),
            actions: Vec::new(),
            span: def.span,
        };
        let header_ok = match header {
            Ok(Some((name, span))) => {
                d.name = name;
                d.name_span = span;
                true
            }
            Ok(None) => return None,
            Err(()) => false,
        };
        let mut seen = HashMap::new();
        for e in items.iter().skip(2) {
            self.section(e, &mut d, &mut seen);
        }
        // After the domain: sections that an extra `)` pushed out are reported and still read,
        // anything else is reported once.
        let mut stray_reported = false;
        for e in &top[def_index + 1..] {
            let is_section = match &e.kind {
                SKind::List(items, _) => items.first().and_then(keyword_of).is_some(),
                _ => false,
            };
            if is_section {
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(
                        e.span,
                        format!("section {} is outside `(define ...)`", describe(e)),
                        "after the end of the domain",
                    )
                    .with_secondary(def.span.shrink_to_start(), "the domain starts here")
                    .with_help("an extra `)` before this section closes `(define` too early"),
                );
                self.section(e, &mut d, &mut seen);
            } else if !stray_reported && !matches!(e.kind, SKind::Bad) {
                stray_reported = true;
                let _: PResult<()> = self.expected_elem(e, "the end of the file");
                self.help_last("a file holds one domain, and nothing after it");
            }
        }
        header_ok.then_some(d)
    }

    /// Reads `(domain NAME)`: `Ok(None)` for a problem file (reported), `Err` when malformed.
    fn header(&mut self, e: Option<&SExpr>, close: Span) -> PResult<Option<(String, Span)>> {
        const WHAT: &str = "`(domain NAME)`";
        let Some(e) = e else {
            let (s, f) = list_end(close);
            return self.expected(s, WHAT, f);
        };
        let SKind::List(items, hclose) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let head = match items.first() {
            Some(h) => h,
            None => return self.expected(e.span, WHAT, "`()`".to_string()),
        };
        match name_of(head).map(keyword_name).as_deref() {
            Some("domain") => {}
            Some("problem") => {
                let _: PResult<()> = self.unsupported(
                    e.span,
                    "this is a PDDL problem, not a domain".to_string(),
                    "bdi-check reads only the domain: the manifest (bdi-check.toml) gives the \
                     objects and the initial facts",
                );
                return Ok(None);
            }
            _ => return self.expected_elem(head, "`domain`"),
        }
        let name = match items.get(1) {
            Some(n) => match name_of(n) {
                Some(s) => (s.to_string(), n.span),
                None => return self.expected_elem(n, "the domain's name"),
            },
            None => {
                let (s, f) = list_end(*hclose);
                return self.expected(s, "the domain's name", f);
            }
        };
        if let Some(extra) = items.get(2) {
            return self.expected_elem(extra, "`)` after the domain's name");
        }
        Ok(Some(name))
    }

    fn section(&mut self, e: &SExpr, d: &mut Domain, seen: &mut HashMap<String, Span>) {
        const WHAT: &str = "a section such as `(:action ...)`";
        let (items, close) = match &e.kind {
            SKind::List(items, close) => (items, *close),
            _ => {
                let _: PResult<()> = self.expected_elem(e, WHAT);
                return;
            }
        };
        let Some(head) = items.first() else {
            let _: PResult<()> = self.expected(e.span, WHAT, "`()`".to_string());
            return;
        };
        let Some(kw) = keyword_of(head) else {
            let _: PResult<()> = self.expected_elem(head, WHAT);
            return;
        };
        let args = &items[1..];
        if matches!(
            kw,
            ":requirements" | ":types" | ":constants" | ":predicates"
        ) {
            if let Some(first) = seen.get(kw) {
                // Still read it: merging loses nothing, and skipping would make every name it
                // declares look undeclared.
                let _: PResult<()> = self.error(
                    Diagnostic::error("input", format!("a second `({kw}` section"))
                        .with_label(head.span, "repeated section")
                        .with_secondary(*first, "the first one is here")
                        .with_help("merge the two sections into one"),
                );
            } else {
                seen.insert(kw.to_string(), head.span);
            }
        }
        match kw {
            ":requirements" => self.requirements(args, d),
            ":types" => {
                if self.types(args, close, d).is_err() {
                    self.types_broken = true;
                }
            }
            ":constants" => {
                if let Ok(list) = self.typed_list(args, close, false, "a constant name") {
                    d.constants.extend(list.into_iter().map(|t| {
                        let (ty, ty_span) = t.ty();
                        Constant {
                            name: t.name,
                            ty,
                            ty_span,
                            span: t.span,
                        }
                    }));
                }
            }
            ":predicates" => self.predicates(args, d),
            ":action" => {
                if let Ok(a) = self.action(e.span, args, close) {
                    d.actions.push(a);
                }
            }
            ":functions" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:functions ...)` is not supported".to_string(),
                    NUMERIC_HELP,
                );
            }
            ":durative-action" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:durative-action ...)` is not supported".to_string(),
                    TEMPORAL_HELP,
                );
            }
            ":derived" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:derived ...)` is not supported".to_string(),
                    DERIVED_HELP,
                );
            }
            ":constraints" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:constraints ...)` is not supported".to_string(),
                    CONSTRAINTS_HELP,
                );
            }
            _ => {
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(
                        head.span,
                        format!("unknown section `{kw}`"),
                        "expected a section keyword",
                    )
                    .with_help(
                        "a domain holds `(:requirements ...)`, `(:types ...)`, \
                         `(:constants ...)`, `(:predicates ...)` and `(:action ...)` sections",
                    ),
                );
            }
        }
    }

    fn requirements(&mut self, args: &[SExpr], d: &mut Domain) {
        for e in args {
            let Some(k) = keyword_of(e) else {
                let _: PResult<()> = self.expected_elem(e, "a requirement such as `:strips`");
                continue;
            };
            if SUPPORTED_REQUIREMENTS.contains(&k) {
                d.requirements.push(Requirement {
                    name: k.to_string(),
                    span: e.span,
                });
                continue;
            }
            let help = match k {
                ":numeric-fluents" | ":fluents" | ":object-fluents" | ":action-costs" => {
                    NUMERIC_HELP
                }
                ":durative-actions"
                | ":duration-inequalities"
                | ":continuous-effects"
                | ":timed-initial-literals" => TEMPORAL_HELP,
                ":derived-predicates" => DERIVED_HELP,
                ":preferences" | ":constraints" => CONSTRAINTS_HELP,
                _ => {
                    let _: PResult<()> = self.error(
                        Diagnostic::error("input", format!("unknown requirement `{k}`"))
                            .with_label(e.span, "not a requirement bdi-check knows")
                            .with_help(format!(
                                "supported requirements: {}",
                                SUPPORTED_REQUIREMENTS.join(" ")
                            )),
                    );
                    continue;
                }
            };
            let _: PResult<()> =
                self.unsupported(e.span, format!("requirement `{k}` is not supported"), help);
        }
    }

    fn types(&mut self, args: &[SExpr], close: Span, d: &mut Domain) -> PResult<()> {
        for t in self.typed_list(args, close, false, "a type name")? {
            if t.name == "object" {
                // `object` is the implicit root; declaring it is harmless unless it gets a parent.
                match &t.ty {
                    Some((p, s)) if p != "object" => {
                        return self.error(
                            Diagnostic::error("input", "`object` cannot have a parent type")
                                .with_label(*s, "`object` is the root of every type"),
                        );
                    }
                    _ => continue,
                }
            }
            let (parent, parent_span) = t.ty();
            d.types.push(TypeDecl {
                name: t.name,
                parent,
                parent_span,
                span: t.span,
            });
        }
        Ok(())
    }

    fn predicates(&mut self, args: &[SExpr], d: &mut Domain) {
        const WHAT: &str = "a predicate declaration such as `(at ?x - object)`";
        for e in args {
            let decl = (|| {
                let SKind::List(items, close) = &e.kind else {
                    return self.expected_elem(e, WHAT);
                };
                let Some(head) = items.first() else {
                    return self.expected(e.span, WHAT, "`()`".to_string());
                };
                let Some(name) = name_of(head) else {
                    return self.expected_elem(head, "a predicate name");
                };
                let params =
                    self.typed_list(&items[1..], *close, true, "a variable such as `?x`")?;
                Ok(PredicateDecl {
                    name: name.to_string(),
                    name_span: head.span,
                    params: params.into_iter().map(Typed::into_var).collect(),
                    span: e.span,
                })
            })();
            match decl {
                Ok(p) => d.predicates.push(p),
                Err(()) => self.predicates_broken = true,
            }
        }
    }

    /// A list of names (`vars` false) or variables (`vars` true), some followed by `- type`.
    fn typed_list(
        &mut self,
        items: &[SExpr],
        close: Span,
        vars: bool,
        what: &str,
    ) -> PResult<Vec<Typed>> {
        let mut out: Vec<Typed> = Vec::new();
        // Entries from here on have no type yet.
        let mut untyped_from = 0;
        let mut i = 0;
        while let Some(e) = items.get(i) {
            match &e.kind {
                SKind::Atom(Atom::Dash) => {
                    if untyped_from == out.len() {
                        return self.expected(e.span, what, "`-`".to_string());
                    }
                    let ty = self.type_name(items.get(i + 1), close)?;
                    for t in &mut out[untyped_from..] {
                        t.ty = Some(ty.clone());
                    }
                    untyped_from = out.len();
                    i += 2;
                    continue;
                }
                SKind::Atom(Atom::Var(v)) if vars => out.push(Typed {
                    name: v.clone(),
                    span: e.span,
                    ty: None,
                }),
                SKind::Atom(Atom::Name(n)) if !vars => out.push(Typed {
                    name: n.clone(),
                    span: e.span,
                    ty: None,
                }),
                _ => return self.expected_elem(e, what),
            }
            i += 1;
        }
        Ok(out)
    }

    /// The type after a `-`.
    fn type_name(&mut self, e: Option<&SExpr>, close: Span) -> PResult<(String, Span)> {
        const WHAT: &str = "a type name after `-`";
        let Some(e) = e else {
            let (s, f) = list_end(close);
            return self.expected(s, WHAT, f);
        };
        match &e.kind {
            SKind::Atom(Atom::Name(n)) => Ok((n.clone(), e.span)),
            SKind::List(items, _)
                if items.first().and_then(name_of).map(keyword_name).as_deref()
                    == Some("either") =>
            {
                self.unsupported(
                    e.span,
                    "`either` types are not supported".to_string(),
                    "declare a common parent type in `(:types ...)` and use it instead",
                )
            }
            _ => self.expected_elem(e, WHAT),
        }
    }

    fn action(&mut self, span: Span, args: &[SExpr], close: Span) -> PResult<ActionDecl> {
        let (name, name_span) = match args.first() {
            Some(e) => match name_of(e) {
                Some(n) => (n.to_string(), e.span),
                None => return self.expected_elem(e, "the action's name"),
            },
            None => {
                let (s, f) = list_end(close);
                return self.expected(s, "the action's name", f);
            }
        };
        const KEYS: &str = "`:parameters`, `:precondition` or `:effect`";
        let mut params = Vec::new();
        let mut precondition = None;
        let mut effect = None;
        let mut seen: HashMap<&str, Span> = HashMap::new();
        let mut ok = true;
        let mut i = 1;
        // Each key's value is read on its own, so a broken precondition still lets the effect
        // report its errors; the action is kept only when all are fine.
        while let Some(key) = args.get(i) {
            let Some(kw) = keyword_of(key) else {
                ok = false;
                let _: PResult<()> = self.expected_elem(key, KEYS);
                // Resynchronise at the next keyword.
                i += 1;
                while args.get(i).is_some_and(|e| keyword_of(e).is_none()) {
                    i += 1;
                }
                continue;
            };
            if !matches!(kw, ":parameters" | ":precondition" | ":effect") {
                ok = false;
                let mut d = Diagnostic::syntax(
                    key.span,
                    format!("expected {KEYS}, found keyword `{kw}`"),
                    "unknown action key",
                );
                if matches!(kw, ":duration" | ":condition") {
                    d = d.with_help(TEMPORAL_HELP);
                }
                let _: PResult<()> = self.error(d);
                i += 2;
                continue;
            }
            if let Some(first) = seen.get(kw) {
                ok = false;
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(key.span, format!("`{kw}` is given twice"), "repeated")
                        .with_secondary(*first, "first given here"),
                );
                i += 2;
                continue;
            }
            seen.insert(kw, key.span);
            let value = match args.get(i + 1) {
                Some(v) if keyword_of(v).is_none() => v,
                other => {
                    ok = false;
                    let what = format!("a value after `{kw}`");
                    let _: PResult<()> = match other {
                        Some(v) => self.expected_elem(v, &what),
                        None => {
                            let (s, f) = list_end(close);
                            self.expected(s, &what, f)
                        }
                    };
                    i += 1;
                    continue;
                }
            };
            let r = match kw {
                ":parameters" => self.var_list(value).map(|p| params = p),
                ":precondition" => self.gd(value).map(|g| precondition = Some(g)),
                _ => self.effect(value).map(|e| effect = Some(e)),
            };
            ok &= r.is_ok();
            i += 2;
        }
        if !ok {
            return Err(());
        }
        Ok(ActionDecl {
            name,
            name_span,
            params,
            precondition,
            effect,
            span,
        })
    }

    /// `(?x - t ?y)`: parameters or quantified variables.
    fn var_list(&mut self, e: &SExpr) -> PResult<Vec<TypedVar>> {
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, "a list of variables such as `(?x - type)`");
        };
        let list = self.typed_list(items, *close, true, "a variable such as `?x`")?;
        Ok(list.into_iter().map(Typed::into_var).collect())
    }

    /// Checks that `(head ...)` has exactly `N` arguments, named by `what` for the message.
    fn exact<'a, const N: usize>(
        &mut self,
        head: &str,
        args: &'a [SExpr],
        close: Span,
        what: [&str; N],
    ) -> PResult<&'a [SExpr; N]> {
        if args.len() < N {
            let (s, f) = list_end(close);
            return self.expected(s, &format!("{} in `({head} ...)`", what[args.len()]), f);
        }
        if let Some(extra) = args.get(N) {
            return self.expected_elem(extra, &format!("`)` to close `({head} ...)`"));
        }
        <&[SExpr; N]>::try_from(args).map_err(|_| ())
    }

    /// Reads every element, reporting all errors; fails if any failed.
    fn all<T>(
        &mut self,
        args: &[SExpr],
        mut f: impl FnMut(&mut Self, &SExpr) -> PResult<T>,
    ) -> PResult<Vec<T>> {
        let mut out = Vec::with_capacity(args.len());
        let mut ok = true;
        for a in args {
            match f(self, a) {
                Ok(v) => out.push(v),
                Err(()) => ok = false,
            }
        }
        if ok {
            Ok(out)
        } else {
            Err(())
        }
    }

    fn gd(&mut self, e: &SExpr) -> PResult<Gd> {
        const WHAT: &str = "a goal description such as `(p ?x)` or `(and ...)`";
        let span = e.span;
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let close = *close;
        let Some(head) = items.first() else {
            return Ok(Gd {
                kind: GdKind::And(Vec::new()),
                span,
            });
        };
        let args = &items[1..];
        let kind = match &head.kind {
            SKind::Atom(Atom::Name(h)) => match keyword_name(h).as_str() {
                "and" => GdKind::And(self.all(args, Self::gd)?),
                "or" => GdKind::Or(self.all(args, Self::gd)?),
                "not" => {
                    let [g] = self.exact("not", args, close, ["a goal description"])?;
                    GdKind::Not(Box::new(self.gd(g)?))
                }
                "imply" => {
                    let [a, b] = self.exact(
                        "imply",
                        args,
                        close,
                        ["a goal description", "a second goal description"],
                    )?;
                    let (a, b) = (self.gd(a), self.gd(b));
                    GdKind::Imply(Box::new(a?), Box::new(b?))
                }
                q @ ("exists" | "forall") => {
                    let [vs, g] = self.exact(
                        q,
                        args,
                        close,
                        ["a list of variables", "a goal description"],
                    )?;
                    let (vs, g) = (self.var_list(vs), self.gd(g));
                    let (vs, g) = (vs?, Box::new(g?));
                    if q == "exists" {
                        GdKind::Exists(vs, g)
                    } else {
                        GdKind::Forall(vs, g)
                    }
                }
                "when" => {
                    return self.error(
                        Diagnostic::syntax(
                            head.span,
                            "`when` is an effect, not a goal description",
                            "not allowed in a precondition",
                        )
                        .with_help("use `(imply CONDITION GOAL)` in a precondition"),
                    )
                }
                _ => GdKind::Atom(self.atom(head, h, args, span)?),
            },
            SKind::Atom(Atom::Op(o)) if o == "=" => {
                if args.iter().any(|a| matches!(a.kind, SKind::List(..))) {
                    return self.unsupported(
                        head.span,
                        "numeric comparisons are not supported".to_string(),
                        NUMERIC_HELP,
                    );
                }
                let [a, b] = self.exact("=", args, close, ["a term", "a second term"])?;
                let (a, b) = (self.term(a), self.term(b));
                GdKind::Equal(a?, b?)
            }
            SKind::Atom(Atom::Op(o)) if matches!(o.as_str(), "<" | ">" | "<=" | ">=") => {
                return self.unsupported(
                    head.span,
                    "numeric comparisons are not supported".to_string(),
                    NUMERIC_HELP,
                );
            }
            _ => {
                let r = self.expected_elem(head, "a predicate name or a connective such as `and`");
                self.help_last(if matches!(head.kind, SKind::List(..)) {
                    "one pair of parentheses too many? A goal description is `(p t...)`, \
                     `(and ...)`, `(or ...)`, `(not G)`, `(imply G G)`, `(exists (?x) G)`, \
                     `(forall (?x) G)` or `(= t t)`"
                } else {
                    "a goal description is `(p t...)`, `(and ...)`, `(or ...)`, `(not G)`, \
                     `(imply G G)`, `(exists (?x) G)`, `(forall (?x) G)` or `(= t t)`"
                });
                return r;
            }
        };
        Ok(Gd { kind, span })
    }

    /// `(p t...)`, the head already read.
    fn atom(
        &mut self,
        head: &SExpr,
        name: &str,
        args: &[SExpr],
        span: Span,
    ) -> PResult<AtomicFormula> {
        Ok(AtomicFormula {
            predicate: name.to_string(),
            predicate_span: head.span,
            args: self.all(args, Self::term)?,
            span,
        })
    }

    fn term(&mut self, e: &SExpr) -> PResult<PddlTerm> {
        match &e.kind {
            SKind::Atom(Atom::Var(v)) => Ok(PddlTerm::Var {
                name: v.clone(),
                span: e.span,
            }),
            SKind::Atom(Atom::Name(n)) => Ok(PddlTerm::Const {
                name: n.clone(),
                span: e.span,
            }),
            SKind::List(..) => {
                let r = self.expected_elem(e, "a variable or a constant");
                self.help_last(
                    "function terms need `:object-fluents`, which bdi-check does not support",
                );
                r
            }
            _ => self.expected_elem(e, "a variable or a constant"),
        }
    }

    fn effect(&mut self, e: &SExpr) -> PResult<Effect> {
        const WHAT: &str = "an effect such as `(p ?x)` or `(and ...)`";
        let span = e.span;
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let close = *close;
        let Some(head) = items.first() else {
            return Ok(Effect {
                kind: EffectKind::And(Vec::new()),
                span,
            });
        };
        let args = &items[1..];
        let kind = match &head.kind {
            SKind::Atom(Atom::Name(h)) => match keyword_name(h).as_str() {
                "and" => EffectKind::And(self.all(args, Self::effect)?),
                "not" => {
                    let [a] = self.exact("not", args, close, ["an atom"])?;
                    EffectKind::Delete(self.effect_atom(a)?)
                }
                "forall" => {
                    let [vs, eff] =
                        self.exact("forall", args, close, ["a list of variables", "an effect"])?;
                    let (vs, eff) = (self.var_list(vs), self.effect(eff));
                    EffectKind::Forall(vs?, Box::new(eff?))
                }
                "when" => {
                    let [g, eff] = self.exact("when", args, close, ["a condition", "an effect"])?;
                    let (g, eff) = (self.gd(g), self.effect(eff));
                    EffectKind::When(Box::new(g?), Box::new(eff?))
                }
                k @ ("or" | "imply" | "exists") => {
                    return self.error(
                        Diagnostic::syntax(
                            head.span,
                            format!("`{k}` is not allowed in an effect"),
                            "a goal description, not an effect",
                        )
                        .with_help(
                            "an effect is a conjunction of atoms, `(not ATOM)`, `(forall ...)` \
                             and `(when CONDITION EFFECT)`",
                        ),
                    )
                }
                "increase" | "decrease" | "assign" | "scale-up" | "scale-down"
                    if args
                        .first()
                        .is_some_and(|a| matches!(a.kind, SKind::List(..))) =>
                {
                    return self.unsupported(
                        head.span,
                        format!("numeric effect `{h}` is not supported"),
                        NUMERIC_HELP,
                    )
                }
                _ => EffectKind::Add(self.atom(head, h, args, span)?),
            },
            SKind::Atom(Atom::Op(o)) if o == "=" => {
                return self.error(Diagnostic::syntax(
                    head.span,
                    "an equality cannot be an effect",
                    "not an effect",
                ))
            }
            _ => {
                let r = self.expected_elem(head, "a predicate name or a connective such as `and`");
                self.help_last(if matches!(head.kind, SKind::List(..)) {
                    "one pair of parentheses too many? An effect is `(p t...)`, \
                     `(not (p t...))`, `(and ...)`, `(forall (?x) E)` or `(when G E)`"
                } else {
                    "an effect is `(p t...)`, `(not (p t...))`, `(and ...)`, `(forall (?x) E)` \
                     or `(when G E)`"
                });
                return r;
            }
        };
        Ok(Effect { kind, span })
    }

    /// The atom under `(not ...)` in an effect.
    fn effect_atom(&mut self, e: &SExpr) -> PResult<AtomicFormula> {
        const WHAT: &str = "an atom such as `(p ?x)`";
        let SKind::List(items, _) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let Some(head) = items.first() else {
            return self.expected(e.span, WHAT, "`()`".to_string());
        };
        match &head.kind {
            SKind::Atom(Atom::Name(h)) if !is_connective(h) => {
                self.atom(head, h, &items[1..], e.span)
            }
            SKind::Atom(Atom::Op(o)) if o == "=" => self.error(Diagnostic::syntax(
                head.span,
                "an equality cannot be an effect",
                "not an effect",
            )),
            _ => self.expected_elem(head, "a predicate name"),
        }
    }
}

/// Whether a name is one of the logical connectives (in any case).
fn is_connective(n: &str) -> bool {
    matches!(
        n.to_ascii_lowercase().as_str(),
        "and" | "or" | "not" | "imply" | "exists" | "forall" | "when"
    )
}

const NUMERIC_HELP: &str = "bdi-check's state is a finite set of ground atoms: numbers, \
    functions and action costs are not modelled; encode quantities as objects";
const TEMPORAL_HELP: &str = "bdi-check's actions are instantaneous, like Jason's environment \
    actions: use `(:action ...)` with `:precondition` and `:effect`";
const DERIVED_HELP: &str = "derived predicates are not supported: write the rule in the agent \
    (a Jason rule) or state the predicate's effect in each action";
const CONSTRAINTS_HELP: &str = "state constraints and preferences as `[invariants]` or \
    `[[property]]` in bdi-check.toml instead";

// ===== structural checks =======================================================================

struct Checker<'d, 'e> {
    d: &'d Domain,
    errors: &'e mut Vec<Diagnostic>,
    types: HashMap<&'d str, &'d TypeDecl>,
    preds: HashMap<&'d str, &'d PredicateDecl>,
    /// Report undeclared types (false when a `(:types` part did not parse).
    check_types: bool,
    /// Report undeclared predicates (false when a `(:predicates` part did not parse).
    check_preds: bool,
}

impl<'d, 'e> Checker<'d, 'e> {
    fn new(
        d: &'d Domain,
        check_types: bool,
        check_preds: bool,
        errors: &'e mut Vec<Diagnostic>,
    ) -> Self {
        Checker {
            d,
            errors,
            types: HashMap::new(),
            preds: HashMap::new(),
            check_types,
            check_preds,
        }
    }

    fn report(&mut self, d: Diagnostic) {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
    }

    fn duplicate(&mut self, what: &str, name: &str, span: Span, first: Span) {
        self.report(
            Diagnostic::error("input", format!("{what} `{name}` is declared twice"))
                .with_label(span, "declared again here")
                .with_secondary(first, "first declared here"),
        );
    }

    fn run(mut self) {
        let d = self.d;
        // Types: duplicates, then parents, then cycles.
        for t in &d.types {
            match self.types.get(t.name.as_str()) {
                Some(first) => self.duplicate("type", &t.name, t.span, first.span),
                None => {
                    self.types.insert(&t.name, t);
                }
            }
        }
        for t in &d.types {
            self.declared_type(&t.parent, t.parent_span);
        }
        self.type_cycles();
        let mut consts: HashMap<&str, Span> = HashMap::new();
        for c in &d.constants {
            match consts.get(c.name.as_str()) {
                Some(&first) => self.duplicate("constant", &c.name, c.span, first),
                None => {
                    consts.insert(&c.name, c.span);
                }
            }
            self.declared_type(&c.ty, c.ty_span);
        }
        for p in &d.predicates {
            match self.preds.get(p.name.as_str()) {
                Some(first) => self.duplicate("predicate", &p.name, p.name_span, first.name_span),
                None => {
                    self.preds.insert(&p.name, p);
                }
            }
            self.params(&p.params);
        }
        let mut actions: HashMap<&str, Span> = HashMap::new();
        for a in &d.actions {
            match actions.get(a.name.as_str()) {
                Some(&first) => self.duplicate("action", &a.name, a.name_span, first),
                None => {
                    actions.insert(&a.name, a.name_span);
                }
            }
            self.params(&a.params);
            let mut scope: Vec<&str> = a.params.iter().map(|v| v.name.as_str()).collect();
            if let Some(g) = &a.precondition {
                self.gd(g, &mut scope, &a.name);
            }
            if let Some(e) = &a.effect {
                self.effect(e, &mut scope, &a.name);
            }
        }
    }

    /// A type named in a declaration must be `object` or declared.
    fn declared_type(&mut self, ty: &str, span: Option<Span>) {
        let Some(span) = span else { return };
        if !self.check_types || ty == "object" || self.types.contains_key(ty) {
            return;
        }
        let mut d = Diagnostic::error("input", format!("undefined type `{ty}`"))
            .with_label(span, "not declared in `(:types ...)`");
        d = match suggest(ty, self.types.keys().copied()) {
            Some(s) => d.with_help(format!("did you mean `{s}`? (names are case-sensitive)")),
            None => d.with_help(format!("declare it: `(:types ... {ty})`")),
        };
        self.report(d);
    }

    /// Reports each cycle of the parent relation once, at its first-declared type.
    fn type_cycles(&mut self) {
        let mut reported: HashSet<&str> = HashSet::new();
        for t in &self.d.types {
            if reported.contains(t.name.as_str()) {
                continue;
            }
            let mut path: Vec<&str> = vec![&t.name];
            let mut cur = self.types.get(t.parent.as_str()).copied();
            while let Some(p) = cur {
                if p.name == t.name || path.contains(&p.name.as_str()) {
                    break;
                }
                path.push(&p.name);
                cur = self.types.get(p.parent.as_str()).copied();
            }
            let Some(p) = cur else { continue };
            if p.name != t.name {
                // `t` leads into a cycle but is not on it; that cycle is reported from one of
                // its own members.
                continue;
            }
            reported.extend(path.iter().copied());
            let mut chain = path.join(" - ");
            chain.push_str(&format!(" - {}", t.name));
            let mut d =
                Diagnostic::error("input", format!("type `{}` is its own ancestor", t.name))
                    .with_label(t.span, format!("cycle: {chain}"))
                    .with_help(
                        "the parent relation of `(:types ...)` must form a tree rooted at `object`",
                    );
            if let Some(s) = t.parent_span {
                d = d.with_secondary(s, "parent given here");
            }
            self.report(d);
        }
    }

    /// Parameters: declared types, no name twice.
    fn params(&mut self, params: &[TypedVar]) {
        let mut seen: HashMap<&str, Span> = HashMap::new();
        for v in params {
            self.declared_type(&v.ty, v.ty_span);
            match seen.get(v.name.as_str()) {
                Some(&first) => self.report(
                    Diagnostic::error("input", format!("variable `?{}` is declared twice", v.name))
                        .with_label(v.span, "declared again here")
                        .with_secondary(first, "first declared here"),
                ),
                None => {
                    seen.insert(&v.name, v.span);
                }
            }
        }
    }

    fn gd(&mut self, g: &'d Gd, scope: &mut Vec<&'d str>, action: &str) {
        match &g.kind {
            GdKind::And(gs) | GdKind::Or(gs) => {
                for g in gs {
                    self.gd(g, scope, action);
                }
            }
            GdKind::Not(g) => self.gd(g, scope, action),
            GdKind::Imply(a, b) => {
                self.gd(a, scope, action);
                self.gd(b, scope, action);
            }
            GdKind::Exists(vs, g) | GdKind::Forall(vs, g) => {
                self.params(vs);
                let n = scope.len();
                scope.extend(vs.iter().map(|v| v.name.as_str()));
                self.gd(g, scope, action);
                scope.truncate(n);
            }
            GdKind::Atom(a) => self.atom(a, scope, action),
            GdKind::Equal(a, b) => {
                self.term(a, scope, action);
                self.term(b, scope, action);
            }
        }
    }

    fn effect(&mut self, e: &'d Effect, scope: &mut Vec<&'d str>, action: &str) {
        match &e.kind {
            EffectKind::And(es) => {
                for e in es {
                    self.effect(e, scope, action);
                }
            }
            EffectKind::Add(a) | EffectKind::Delete(a) => self.atom(a, scope, action),
            EffectKind::Forall(vs, e) => {
                self.params(vs);
                let n = scope.len();
                scope.extend(vs.iter().map(|v| v.name.as_str()));
                self.effect(e, scope, action);
                scope.truncate(n);
            }
            EffectKind::When(g, e) => {
                self.gd(g, scope, action);
                self.effect(e, scope, action);
            }
        }
    }

    fn atom(&mut self, a: &AtomicFormula, scope: &[&str], action: &str) {
        match self.preds.get(a.predicate.as_str()) {
            Some(p) if p.params.len() != a.args.len() => {
                let n = p.params.len();
                self.report(
                    Diagnostic::error(
                        "input",
                        format!(
                            "predicate `{}` takes {n} argument{}, found {}",
                            a.predicate,
                            if n == 1 { "" } else { "s" },
                            a.args.len()
                        ),
                    )
                    .with_label(a.span, format!("{} given", a.args.len()))
                    .with_secondary(p.span, "declared here"),
                );
            }
            Some(_) => {}
            None if self.check_preds => {
                let mut d =
                    Diagnostic::error("input", format!("undefined predicate `{}`", a.predicate))
                        .with_label(a.predicate_span, "not declared in `(:predicates ...)`");
                if let Some(s) = suggest(&a.predicate, self.preds.keys().copied()) {
                    d = d.with_help(format!("did you mean `{s}`? (names are case-sensitive)"));
                }
                self.report(d);
            }
            None => {}
        }
        for t in &a.args {
            self.term(t, scope, action);
        }
    }

    fn term(&mut self, t: &PddlTerm, scope: &[&str], action: &str) {
        if let PddlTerm::Var { name, span } = t {
            if !scope.contains(&name.as_str()) {
                self.report(
                    Diagnostic::error("input", format!("undefined variable `?{name}`")).with_label(
                        *span,
                        format!("not a parameter of `{action}` nor bound by `exists` or `forall`"),
                    ),
                );
            }
        }
    }
}

/// A declared name close to `name`: equal ignoring case, or at most two edits away.
fn suggest<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let dist = if c.eq_ignore_ascii_case(name) {
            0
        } else {
            edit_distance(name, c)
        };
        if dist <= 2 && dist < name.chars().count() && best.is_none_or(|(b, s)| (dist, c) < (b, s))
        {
            best = Some((dist, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Levenshtein distance; long names count as far apart, to keep this cheap.
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    if a.len() > 64 || b.len() > 64 {
        return usize::MAX;
    }
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> (Option<Domain>, Vec<Diagnostic>) {
        parse_domain(FileId(0), text)
    }

    fn ok(text: &str) -> Domain {
        let (d, errs) = parse(text);
        assert!(errs.is_empty(), "{errs:#?}");
        d.expect("a domain")
    }

    #[test]
    fn lexes_names_with_dashes_and_comments() {
        let mut errs = Vec::new();
        let toks = lex(FileId(0), "(pick-up ?x_1 - t) ; c\n:Action 3 =", &mut errs);
        assert!(errs.is_empty());
        let atoms: Vec<_> = toks
            .iter()
            .filter_map(|t| match &t.tok {
                Tok::Atom(a) => Some(a.clone()),
                _ => None,
            })
            .collect();
        assert_eq!(
            atoms,
            vec![
                Atom::Name("pick-up".into()),
                Atom::Var("x_1".into()),
                Atom::Dash,
                Atom::Name("t".into()),
                Atom::Keyword(":action".into()),
                Atom::Number("3".into()),
                Atom::Op("=".into()),
            ]
        );
        assert_eq!(toks[1].span, Span::new(FileId(0), 1, 8));
    }

    #[test]
    fn typed_lists_default_to_object_and_share_types() {
        let d = ok("(define (domain d) (:types a b - p c p) \
                    (:predicates (q ?x ?y - a ?z)))");
        let ty = |n: &str| d.type_decl(n).unwrap().parent.clone();
        assert_eq!(
            (ty("a"), ty("b"), ty("c"), ty("p")),
            ("p".into(), "p".into(), "object".into(), "object".into())
        );
        let p = d.predicate("q").unwrap();
        let tys: Vec<_> = p.params.iter().map(|v| v.ty.as_str()).collect();
        assert_eq!(tys, ["a", "a", "object"]);
    }

    #[test]
    fn ancestors_and_subtypes() {
        let d = ok("(define (domain d) (:types cup plate - dish dish - item item))");
        assert_eq!(d.type_ancestors("cup"), ["dish", "item", "object"]);
        assert_eq!(d.type_ancestors("object"), Vec::<String>::new());
        assert_eq!(d.type_ancestors("unknown"), ["object"]);
        assert!(d.is_subtype("cup", "item"));
        assert!(d.is_subtype("cup", "cup"));
        assert!(d.is_subtype("item", "object"));
        assert!(!d.is_subtype("item", "cup"));
    }

    #[test]
    fn ancestors_terminate_on_cycles() {
        let (d, errs) = parse("(define (domain d) (:types a - b b - a))");
        assert_eq!(errs.len(), 1, "{errs:#?}");
        assert!(errs[0].message.contains("own ancestor"));
        let d = d.unwrap();
        assert_eq!(d.type_ancestors("a"), ["b", "object"]);
    }

    #[test]
    fn display_round_trips() {
        let src = "(define (domain d) (:predicates (p ?x) (q ?x ?y))
          (:action a :parameters (?x ?y)
            :precondition (and (p ?x) (not (= ?x ?y)) (or (q ?x c) (imply (p ?y) (p ?x)))
                               (exists (?z - object) (q ?z ?x)) (forall (?z) (p ?z)) ())
            :effect (and (p ?x) (not (q ?x ?y)) (forall (?z) (when (p ?z) (not (p ?z)))) ())))";
        let d = ok(src);
        let a = &d.actions[0];
        let pre = print_gd(a.precondition.as_ref().unwrap());
        let eff = print_effect(a.effect.as_ref().unwrap());
        assert_eq!(
            pre,
            "(and (p ?x) (not (= ?x ?y)) (or (q ?x c) (imply (p ?y) (p ?x))) \
             (exists (?z - object) (q ?z ?x)) (forall (?z - object) (p ?z)) (and))"
        );
        assert_eq!(
            eff,
            "(and (p ?x) (not (q ?x ?y)) (forall (?z - object) (when (p ?z) (not (p ?z)))) (and))"
        );
        let again = ok(&format!(
            "(define (domain d) (:predicates (p ?x) (q ?x ?y)) \
             (:action a :parameters (?x ?y) :precondition {pre} :effect {eff}))"
        ));
        assert_eq!(
            print_gd(again.actions[0].precondition.as_ref().unwrap()),
            pre
        );
        assert_eq!(print_effect(again.actions[0].effect.as_ref().unwrap()), eff);
        assert_eq!(
            d.undeclared_constants()
                .iter()
                .map(|c| c.0)
                .collect::<Vec<_>>(),
            ["c"]
        );
        let eff_atoms = a.effect.as_ref().unwrap().atoms();
        assert_eq!(eff_atoms.len(), 3);
        assert!(eff_atoms[0].0 && !eff_atoms[1].0);
    }

    #[test]
    fn keywords_ignore_case_names_do_not() {
        let (_, errs) =
            parse("(DEFINE (DOMAIN d) (:PREDICATES (p)) (:Action a :Effect (AND (P))))");
        assert_eq!(errs.len(), 1, "{errs:#?}");
        assert!(errs[0].message.contains("undefined predicate `P`"));
        assert_eq!(
            errs[0].help.as_deref(),
            Some("did you mean `p`? (names are case-sensitive)")
        );
    }

    #[test]
    fn deep_nesting_is_refused_without_overflow() {
        for n in [65, 1000, 100_000] {
            let text = format!(
                "(define (domain d) (:predicates (p)) (:action a :precondition {}(p){}))",
                "(not ".repeat(n),
                ")".repeat(n)
            );
            let (_, errs) = parse(&text);
            assert_eq!(errs.len(), 1, "{errs:#?}");
            assert!(errs[0].message.contains("nesting deeper than 64"));
            let (_, errs) = parse(&"(".repeat(n));
            assert!(!errs.is_empty());
        }
        // Just below the bound is fine.
        let text = format!(
            "(define (domain d) (:predicates (p)) (:action a :precondition {}(p){}))",
            "(not ".repeat(60),
            ")".repeat(60)
        );
        ok(&text);
    }

    #[test]
    fn missing_paren_is_repaired_at_next_section() {
        let (d, errs) = parse(
            "(define (domain d) (:predicates (p))\n(:action a :effect (and (p))\n(:action b :effect (p)))",
        );
        assert_eq!(errs.len(), 1, "{errs:#?}");
        assert!(errs[0].message.contains("unclosed"));
        assert_eq!(errs[0].span.unwrap().start, 37);
        assert_eq!(d.unwrap().actions.len(), 2);
    }

    #[test]
    fn problem_files_are_refused() {
        let (d, errs) = parse("(define (problem p) (:domain d))");
        assert!(d.is_none());
        assert_eq!(errs.len(), 1);
        assert_eq!(errs[0].code, "input");
    }

    #[test]
    fn empty_input_is_an_error() {
        let (d, errs) = parse("  ; nothing\n");
        assert!(d.is_none());
        assert_eq!(errs.len(), 1);
        assert!(errs[0].message.contains("found the end of the file"));
    }

    #[test]
    fn a_broken_action_is_left_out_and_the_rest_is_read() {
        let (d, errs) = parse(
            "(define (domain d) (:predicates (p))
               (:action a :precondition (not) :effect (and (p) 3))
               (:action b :effect (p)))",
        );
        // Both values of `a` are reported, then `b` is read.
        assert_eq!(errs.len(), 2, "{errs:#?}");
        let d = d.unwrap();
        assert_eq!(d.actions.len(), 1);
        assert_eq!(d.actions[0].name, "b");
    }

    #[test]
    fn a_file_without_define_or_with_two_domains() {
        let (d, errs) = parse("(:action a :effect (p))");
        assert!(d.is_none());
        assert_eq!(errs.len(), 1);
        assert_eq!(
            errs[0].message,
            "expected `(define (domain NAME) ...)`, found `(:action`"
        );
        assert_eq!(errs[0].span.unwrap().len(), "(:action".len());
        let (d, errs) = parse("(define (domain d))\n(define (domain e))");
        assert_eq!(d.unwrap().name, "d");
        assert_eq!(errs.len(), 1);
        assert!(errs[0].message.contains("expected the end of the file"));
    }

    #[test]
    fn suggestions() {
        assert_eq!(suggest("cupat", ["cupAt", "at"].into_iter()), Some("cupAt"));
        assert_eq!(suggest("holdng", ["holding"].into_iter()), Some("holding"));
        assert_eq!(suggest("xyz", ["holding"].into_iter()), None);
    }
}
