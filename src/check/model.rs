//! What the explorer explores: a [`Model`] is any transition system with hashable states.
//!
//! The agent's reasoning cycle ([`Semantics`]) is one, and [`Agent`] is the same with
//! symmetry reduction; a model that also carries each user's expected successors (for the
//! explanation properties) is another. Exploration, traces and liveness work on any of
//! them, as in stateright.

use super::explore::fingerprint;
use super::symmetry::Symmetry;
use crate::semantics::{Note, Semantics, State};
use std::hash::Hash;

/// A transition system: initial states and, for each state, its labelled successors.
pub trait Model {
    /// A state; equal states are explored once.
    type State: Clone + Hash + Eq;
    /// What a transition did (for the agent: the notes of a reasoning cycle).
    type Label;

    /// Every initial state.
    fn init_states(&self) -> Vec<Self::State>;

    /// Every successor of `s`, in a fixed order, each with what the transition did.
    fn next_states(&self, s: &Self::State) -> Vec<(Self::Label, Self::State)>;

    /// The fingerprint states are stored under: states with one fingerprint are explored
    /// once. By default the state's own hash; under symmetry, its canonical member's.
    fn fingerprint(&self, s: &Self::State) -> u64 {
        fingerprint(s)
    }
}

impl Model for Semantics<'_> {
    type State = State;
    type Label = Vec<Note>;

    fn init_states(&self) -> Vec<State> {
        self.initial_states()
    }

    fn next_states(&self, s: &State) -> Vec<(Vec<Note>, State)> {
        self.successors(s)
            .into_iter()
            .map(|t| (t.notes, t.next))
            .collect()
    }
}

/// The agent's transition system, with states stored up to renaming of interchangeable
/// objects when `symmetry` is set.
pub struct Agent<'a> {
    /// The reasoning cycle.
    pub sem: &'a Semantics<'a>,
    /// The symmetry reduction, if on.
    pub symmetry: Option<Symmetry>,
}

impl Model for Agent<'_> {
    type State = State;
    type Label = Vec<Note>;

    fn init_states(&self) -> Vec<State> {
        self.sem.initial_states()
    }

    fn next_states(&self, s: &State) -> Vec<(Vec<Note>, State)> {
        self.sem.next_states(s)
    }

    fn fingerprint(&self, s: &State) -> u64 {
        match &self.symmetry {
            Some(sym) => sym.fingerprint(s),
            None => fingerprint(s),
        }
    }
}
