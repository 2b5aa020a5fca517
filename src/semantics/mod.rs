//! Model to transition system: Jason's reasoning cycle over the finite model.
//!
//! [`Semantics`] is the transition function: [`Semantics::initial_states`] and
//! [`Semantics::successors`], each successor with the [`Note`]s that say what happened (the
//! material of counterexample traces and of the dynamic checks). [`query`] answers plan
//! contexts and test goals against the beliefs. [`Compiled`] is the same transition
//! function for search: states made of shared parts, each phase of a cycle computed once per
//! part and per value of the beliefs it reads.

mod atomic;
pub mod compiled;
pub mod cycle;
mod deliberate;
mod execute;
mod failure;
mod internal_actions;
pub mod java_hash;
mod library;
mod messages;
mod perceive;
pub mod query;
mod reads;
pub(crate) mod recent;
pub mod state;
pub mod system;
mod wait;

pub use compiled::{Compiled, Notes, Packed, PartMap};
pub use cycle::{FrameView, Note, Semantics, Transition};
pub use state::{Event, EventTrigger, Frame, InLibrary, Intention, Origin, State};
pub use system::{Message, Step, System, SystemState};
