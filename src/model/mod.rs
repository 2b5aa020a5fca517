//! The formal model.
//!
//! The paper's model of an agent, `M = <S, B, G, Pi>` (states, beliefs, goals, plans), will
//! live here, built from the syntax tree and explored by the model checker. This first part
//! provides what everything else is made of:
//!
//! * [`term`]: Jason terms ([`Term`]), cheap to clone and shareable between threads, with
//!   Jason's canonical forms and term order;
//! * [`print`](mod@print): terms printed exactly as Jason prints them (the `Display` of
//!   [`Term`]); every term shown in a report goes through it;
//! * [`subst`]: substitutions and unification, with Jason's asymmetric rule for annotations
//!   and an occurs check (so no cyclic term is ever built);
//! * [`from_ast`]: conversion from AST expressions, with fresh anonymous variables and
//!   evaluation of ground arithmetic.

pub mod arith;
pub mod atoms;
pub mod cond;
pub mod formula;
pub mod from_ast;
pub mod ground;
pub mod initial;
pub mod internal;
pub mod know_how;
pub mod kqml;
pub mod library;
pub mod ltl;
pub mod plans;
pub mod print;
pub mod project;
pub mod property;
pub mod subst;
pub mod term;
pub mod universe;
pub mod vocabulary;

pub use from_ast::{term_from_expr, ConvertError, ConvertErrorKind, Converter};
pub use subst::{match_pattern, unifier, unify, Substitution};
pub use term::{Cons, Num, Struct, Term, Var};
pub use universe::{ObjectId, Origin, TypeId, Universe};
