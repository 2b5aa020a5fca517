//! The static checks of `bdi-check lint`, decided by the z3 SMT solver.
//!
//! # The encoding: grounded atoms, symbolic plan variables
//!
//! A state is **one z3 Boolean per ground atom** of the [`AtomTable`](crate::model::atoms::AtomTable):
//! exactly the model the explorer runs on, so `lint` and `verify` cannot disagree about what
//! a state is. Invariants, preconditions and conditional effects are already ground
//! ([`Cond`](crate::model::cond::Cond)) and map onto these Booleans one to one, `.count` as a
//! pseudo-Boolean constraint. A **plan variable is a z3 integer** holding an object id,
//! constrained to the objects of its type: a literal `cupAt(C, table)` with `C` symbolic is
//! the disjunction over the cups `c` of `C = c ∧ cupAt(c,table)`, linear in the number of
//! objects. A variable local to a negated or disjoined part of a context is expanded over its
//! type instead (see [`encode`]), so every query is quantifier-free and decidable, and the
//! model z3 returns *is* a concrete state and binding, printed as the counterexample.
//!
//! We chose this over a lifted encoding (one finite sort per PDDL type, predicates as
//! uninterpreted functions, contexts with quantifiers) because the lifted one needs
//! quantifiers for every `not` over a variable, every `.count` and every `forall`/`when`
//! effect, where z3's answers become `unknown` or slow in ways a budget cannot predict, and
//! its models must be decoded back into atoms; the domains of a plan library are small and
//! finite by construction (the explorer enumerates them anyway). The cost that matters is
//! growth with the number of objects: the grounded formulas grow linearly in the atoms a
//! check touches. Measured with `cargo bench --bench lint` on the kitchen (86 checks, 2
//! cores): 0.10 s with 2 cups (19 atoms), 0.11 s with 10 (59 atoms), 0.28 s with 50 (259
//! atoms), and 1.8 s with 200 (1009 atoms). Every check gets a deterministic z3 resource budget (`rlimit`), and an answer
//! z3 cannot give within it is a finding with status `unknown`, never a pass.
//!
//! # Modules
//!
//! * [`encode`]: states, conditions, plan contexts, triggers and rules in z3;
//! * [`summary`]: what each goal may change, for subgoal steps;
//! * [`lint`](mod@lint): the checks and their findings (the table of checks and severities is there);
//! * [`solve`]: one solver with its budget, models and minimal unsat cores;
//! * [`text`]: formulas and literals as Jason text.

pub mod encode;
mod exec;
pub mod lint;
pub mod solve;
pub mod summary;
pub mod text;

pub use lint::{lint, LintFinding, LintOptions, CHECKS, MAX_LINT_ATOMS};
