//! # bdi-check
//!
//! Verifies BDI plan libraries written in Jason AgentSpeak before they run on a robot.
//!
//! Data flows one way, one module per stage:
//!
//! * [`syntax`]: text to AST (AgentSpeak, with located diagnostics);
//! * [`model`]: the formal model: terms, substitutions, unification;
//! * [`smt`]: the static checks of `lint`, decided with z3;
//! * [`report`]: what the commands print (human text and JSON).

#![warn(missing_docs)]

pub mod check;
pub mod model;
pub mod report;
pub mod smt;
pub mod semantics;
pub mod syntax;
