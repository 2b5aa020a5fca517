//! The integration tests, in one binary: each file a module. One binary links (and, with
//! the release profile's link-time optimization, optimizes) the crate once for all of
//! them instead of once per file.

#[path = "../common/mod.rs"]
mod common;

mod architecture;
mod cli;
mod compiled;
mod corpus;
mod explain;
mod explain_run;
mod explain_verify;
mod jason;
mod jason_mas;
mod lint;
mod ltl;
mod ltl_lbt;
mod manifest;
mod multi_agent;
mod no_panic;
mod pddl;
mod project;
mod reports;
mod resources;
mod roundtrip;
mod scale;
mod semantics;
mod typecheck;
mod unify;
mod verify;
