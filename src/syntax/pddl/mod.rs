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
//!
//! One file per stage: `lexer` (1), `sexpr` (2), `read` and `read_action` (3), `check` (4);
//! the domain's tree is in `ast`, and is re-exported here.
//!
//! [`Span`]: super::source::Span

mod ast;
mod check;
mod lexer;
mod read;
mod read_action;
mod sexpr;
#[cfg(test)]
mod tests;

pub use ast::{
    print_effect, print_gd, ActionDecl, AtomicFormula, Constant, Domain, Effect, EffectKind, Gd,
    GdKind, PddlTerm, PredicateDecl, Requirement, TypeDecl, TypedVar,
};

use super::diagnostic::Diagnostic;
use super::source::FileId;
use check::Checker;
use lexer::lex;
use read::Reader;
use sexpr::build_tree;

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
