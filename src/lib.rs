//! # bdi-check
//!
//! Verifies BDI plan libraries written in Jason AgentSpeak before they run on a robot.
//!
//! ## Model checking a plan library, in one example
//!
//! A *model checker* does not run the robot once: it runs it in every way it can run. Here
//! the robot is a Jason agent whose plans react to requests, and its world is a PDDL model
//! of the kitchen. The paper this tool comes from (Wang, Calandra, Klös, "Effective
//! Explanations for BDI Robots") stores a used cup with two plans:
//!
//! ```text
//! +!storeCup(C) : used(C)
//!    <- !openDishwasherIfNeed; navigateTo(table); pickUp(C); navigateTo(dishwasher); putDown(C).
//! +!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)
//!    <- navigateTo(dishwasher); openDoor(dishwasher).
//! ```
//!
//! Tests would try the story the paper tells (the door is closed) and pass. The model
//! checker takes every *initial state* the manifest allows (here the door open or closed),
//! every *request* the user may make, and follows Jason's reasoning cycle step by step:
//! each state is the robot's beliefs, its event queue and its intentions; each transition
//! is one reasoning cycle. Exploring breadth-first, it visits every reachable state once
//! and keeps, for each, the step that first reached it, so the run to any violation it finds
//! is a shortest one:
//!
//! ```
//! use bdi_check::check::{explore::Limits, verify};
//! use bdi_check::model::project::load_project;
//! use bdi_check::findings::Status;
//!
//! let project = load_project(std::path::Path::new("specs/paper")).expect("the project loads");
//! let limits = Limits { max_states: 10_000, max_depth: 100, timeout: None };
//! let result = verify(&project, limits, |_, _, _| {}, &[]).expect("the project can be checked");
//!
//! // Every reachable state was visited...
//! assert!(result.stats.complete);
//! assert_eq!(result.stats.states, 14);
//!
//! // ...and when the door is already open, no plan for +!openDishwasherIfNeed applies.
//! let failure = result
//!     .findings
//!     .iter()
//!     .find(|f| f.check == "goal-failure" && f.status == Status::Fail)
//!     .expect("the paper's gap is found");
//! let run = failure.counterexample.as_ref().unwrap();
//! assert!(run.initial.contains(&"dishwasherDoor(open)".to_string()));
//! assert_eq!(run.requests, ["storeCup(cup1)"]);
//! ```
//!
//! The same exploration proves the completed kitchen of `specs/kitchen` correct for all 100
//! initial states and every pair of requests: `cargo run --release -- verify specs/kitchen`.
//!
//! ## Explanations, checked on every run
//!
//! The robot explains itself to each user when an action surprises them (Algorithm 1), and
//! says which beliefs and which later action it acted for (Algorithm 2). What a user expects
//! changes as they watch, so `verify` explores the runs once more with each user's expected
//! successors in the state, and checks the explanations of every run. The owner of the
//! paper's example expects the robot to go to the table first; the paper's own version of
//! Algorithm 1, which marks a plan's actions when the plan is adopted, does not see that the
//! owner watches the robot open the dishwasher before it goes to the table:
//!
//! ```
//! # use bdi_check::check::{explore::Limits, verify};
//! # use bdi_check::model::project::load_project;
//! # use bdi_check::findings::Status;
//! # let project = load_project(std::path::Path::new("specs/paper")).unwrap();
//! # let limits = Limits { max_states: 10_000, max_depth: 100, timeout: None };
//! let result = verify(&project, limits, |_, _, _| {}, &[]).unwrap();
//! let status = |id: &str| result.findings.iter().find(|f| f.id == id).map(|f| f.status);
//! // The content of every explanation covers the action that changes its context...
//! assert_eq!(status("content-covers:owner"), Some(Status::Pass));
//! // ...but marking at adoption misses the surprising walk back to the table.
//! assert_eq!(
//!     status("demand-adoption:owner:specs/paper/paper.asl:13"),
//!     Some(Status::Fail)
//! );
//! ```
//!
//! ## Stages
//!
//! Data flows one way, one module per stage:
//!
//! * [`syntax`]: text to AST: the AgentSpeak and PDDL parsers, the manifest, located
//!   diagnostics;
//! * [`model`]: the formal model `M = <S, B, G, Pi>`: terms and unification, types and
//!   objects, type checking, ground atoms and states, ground actions, plans;
//! * [`smt`]: the static checks of `lint`, decided with z3;
//! * [`findings`]: what every stage reports (findings, counterexamples, statistics);
//! * [`semantics`]: Jason's reasoning cycle as a transition function, and compiled for search;
//! * [`explain`]: the paper's two explanation algorithms (when to explain, what to say),
//!   as pure functions a robot can call at run time;
//! * [`check`]: exhaustive exploration and the dynamic checks;
//! * [`report`]: rendering only: human text, JSON, SARIF, JUnit, DOT, scenario files;
//! * [`commands`]: each command of SPEC §2: load, run the stages, hand the result to `report`.

#![warn(missing_docs)]

pub mod check;
pub mod commands;
pub mod explain;
pub mod findings;
pub mod model;
#[cfg(kani)]
#[path = "../proofs/mod.rs"]
mod proofs;
pub mod report;
pub mod semantics;
pub mod smt;
pub mod syntax;
