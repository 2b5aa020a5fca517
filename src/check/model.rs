//! What the explorer explores: a [`Model`] is any transition system with hashable states.
//!
//! The agent's reasoning cycle ([`Semantics`]) is one, and [`Agent`] is the same with
//! symmetry reduction; [`CompiledAgent`] is the same again, compiled for speed; a model
//! that also carries each user's expected successors (for the explanation properties) is
//! another. Exploration, traces and liveness work on any of
//! them, as in stateright.

use super::explore::fingerprint;
use super::symmetry::Symmetry;
use crate::model::atoms::AtomSet;
use crate::semantics::{Compiled, Note, Notes, Packed, Semantics, State};
use std::hash::Hash;

/// A transition system: initial states and, for each state, its labelled successors.
pub trait Model {
    /// A state; equal states are explored once.
    type State: Clone + Hash + Eq;
    /// What a transition did (for the agent: the notes of a reasoning cycle).
    type Label;

    /// Every initial state, made as the search takes them (it stops taking them at its
    /// bounds).
    fn init_states(&self) -> Box<dyn Iterator<Item = Self::State> + '_>;

    /// Every successor of `s`, in a fixed order, each with what the transition did.
    fn next_states(&self, s: &Self::State) -> Vec<(Self::Label, Self::State)>;

    /// [`Model::next_states`] appended to `out`: the search collects a job's successors
    /// in one vector, and a model that makes them one by one saves a vector per state.
    fn next_states_into(&self, s: &Self::State, out: &mut Vec<(Self::Label, Self::State)>) {
        out.append(&mut self.next_states(s));
    }

    /// Whether [`Model::init_states`] gives every initial state: a project with more than
    /// its bound allows gives the first ones, and the search is then incomplete.
    fn init_complete(&self) -> bool {
        true
    }

    /// The fingerprint states are stored under: states with one fingerprint are explored
    /// once. By default the state's own hash; under symmetry, its canonical member's.
    fn fingerprint(&self, s: &Self::State) -> u64 {
        fingerprint(s)
    }

    /// [`Model::fingerprint`] of the target of a transition, which the model may note in
    /// the transition's label (how the state is stored, for checks that follow one part of
    /// it from state to state).
    fn fingerprint_labelled(&self, _label: &mut Self::Label, s: &Self::State) -> u64 {
        self.fingerprint(s)
    }

    /// Whether a transition leaves the model ([`Note::Beyond`]): the search does not follow
    /// it and is incomplete.
    fn beyond(&self, _label: &Self::Label) -> Option<(crate::syntax::Span, String)> {
        None
    }

    /// Asks the processor to bring in what expanding `s` will read, some states before
    /// the search expands it: at `stage` 0 what the state itself tells the address of,
    /// then at each next stage, closer to its turn, what the last one brought in points
    /// to. A hint: it changes no result.
    fn prefetch(&self, _s: &Self::State, _stage: usize) {}

    /// Partial-order reduction: the successors (a range of `successors`, the list
    /// [`Model::next_states`] gave for `s`) that are enough to follow from `s`, an ample
    /// set meeting conditions C0 to C2 of Clarke, Grumberg and Peled (nonempty; no
    /// transition outside it that depends on it can run before it; invisible to every
    /// checked condition). The search adds the cycle proviso (C3): it follows the range
    /// only when every target is new, deeper than `s`. `None`: follow every successor.
    fn ample(
        &self,
        _s: &Self::State,
        _successors: &[(Self::Label, Self::State)],
    ) -> Option<std::ops::Range<usize>> {
        None
    }
}

/// Whether notes leave the model.
pub fn is_beyond<'n>(notes: impl Iterator<Item = &'n Note>) -> bool {
    beyond_of(notes).is_some()
}

/// Where notes leave the model and why (the step as it would run, and what the model
/// lacks), for the first [`Note::Beyond`] among them.
pub fn beyond_of<'n>(
    mut notes: impl Iterator<Item = &'n Note>,
) -> Option<(crate::syntax::Span, String)> {
    notes.find_map(|n| match n {
        Note::Beyond {
            text, span, reason, ..
        } => Some((*span, format!("`{text}`: {reason}"))),
        _ => None,
    })
}

impl Model for Semantics<'_> {
    type State = State;
    type Label = Vec<Note>;

    fn init_states(&self) -> Box<dyn Iterator<Item = State> + '_> {
        Box::new(self.initial_iter())
    }

    fn next_states(&self, s: &State) -> Vec<(Vec<Note>, State)> {
        self.successors(s)
            .into_iter()
            .map(|t| (t.notes, t.next))
            .collect()
    }

    fn beyond(&self, label: &Vec<Note>) -> Option<(crate::syntax::Span, String)> {
        beyond_of(label.iter())
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

    fn init_states(&self) -> Box<dyn Iterator<Item = State> + '_> {
        Box::new(self.sem.initial_iter())
    }

    fn next_states(&self, s: &State) -> Vec<(Vec<Note>, State)> {
        self.sem.next_states(s)
    }

    fn beyond(&self, label: &Vec<Note>) -> Option<(crate::syntax::Span, String)> {
        beyond_of(label.iter())
    }

    fn fingerprint(&self, s: &State) -> u64 {
        match &self.symmetry {
            Some(sym) => sym.fingerprint(s),
            None => fingerprint(s),
        }
    }
}

/// The compiled reasoning cycle ([`Compiled`]): the same transition system as
/// [`Semantics`] (and [`Agent`]), with the same fingerprints and notes, searched faster.
/// Its states borrow from the compiled cycle.
pub struct CompiledAgent<'c, 's, 'p> {
    /// The compiled reasoning cycle.
    pub compiled: &'c Compiled<'s, 'p>,
    /// The symmetry reduction, if on.
    pub symmetry: Option<&'c Symmetry>,
}

impl<'c> Model for CompiledAgent<'c, '_, '_> {
    type State = Packed<'c>;
    type Label = Notes<'c>;

    fn init_states(&self) -> Box<dyn Iterator<Item = Packed<'c>> + '_> {
        Box::new(self.compiled.initial_iter())
    }

    fn next_states(&self, s: &Packed<'c>) -> Vec<(Notes<'c>, Packed<'c>)> {
        self.compiled.successors(s)
    }

    fn next_states_into(&self, s: &Packed<'c>, out: &mut Vec<(Notes<'c>, Packed<'c>)>) {
        self.compiled.successors_into(s, out);
    }

    /// The state's agenda and belief base, then the first event or intention the cycle
    /// reads: reading the agenda of a state met long before was most of opening it (perf,
    /// 6-cup kitchen: a twentieth of the worker's time).
    fn prefetch(&self, s: &Packed<'c>, stage: usize) {
        use super::chunked::prefetch;
        match stage {
            0 => {
                let agenda = s.agenda_key() as *const u8;
                (0..3).for_each(|line| prefetch(agenda.wrapping_add(64 * line)));
                prefetch(s.beliefs());
            }
            1 => match s.first_event() {
                Some(e) => prefetch(e),
                None => {
                    if let Some(i) = s.intentions().next() {
                        prefetch(i);
                    }
                }
            },
            _ => {}
        }
    }

    fn beyond(&self, label: &Notes<'c>) -> Option<(crate::syntax::Span, String)> {
        beyond_of(label.iter())
    }

    fn fingerprint(&self, s: &Packed<'c>) -> u64 {
        match self.symmetry {
            // The canonical member is the reference one's, renamed part by part.
            Some(sym) => sym.fingerprint_compiled(self.compiled, s),
            None => fingerprint(s),
        }
    }
}

/// What the agent's checks read of a state, in either representation.
pub trait AgentState {
    /// The beliefs.
    fn beliefs(&self) -> &AtomSet;
    /// An identity of the beliefs within one search, when they are shared between states
    /// (equal keys, equal beliefs), so that what depends on the beliefs alone can be
    /// computed once per belief base.
    fn beliefs_key(&self) -> Option<usize> {
        None
    }
    /// Where a memo may keep what it derives from the beliefs, with them, when they are
    /// shared between states ([`Annex`](crate::semantics::compiled::Annex)).
    fn beliefs_annex(&self) -> Option<&crate::semantics::compiled::Annex> {
        None
    }
    /// The requests still being served.
    fn pending_requests(&self) -> u64;
    /// Whether the agent has nothing to do.
    fn is_idle(&self) -> bool;
    /// The goals of its intentions, and with `events` those of its achievement-goal
    /// events: what Jason's `.intend` (without) and `.desire` (with) look among.
    fn goals(&self, events: bool) -> Vec<&crate::model::term::Term>;
}

/// The goals of `intentions` and, with `events`, of the `+!g` events among `queue`.
fn goals_of<'a>(
    intentions: impl Iterator<Item = &'a crate::semantics::Intention>,
    queue: impl Iterator<Item = &'a crate::semantics::Event>,
    events: bool,
) -> Vec<&'a crate::model::term::Term> {
    use crate::syntax::ast::{TriggerKind, TriggerOp};
    let mut out: Vec<&crate::model::term::Term> = intentions.flat_map(|i| i.goals()).collect();
    if events {
        out.extend(
            queue
                .filter(|e| {
                    e.trigger.op == TriggerOp::Add && e.trigger.kind == TriggerKind::Achieve
                })
                .map(|e| &e.trigger.literal),
        );
    }
    out
}

impl<T: AgentState> AgentState for &T {
    fn beliefs(&self) -> &AtomSet {
        T::beliefs(self)
    }
    fn beliefs_key(&self) -> Option<usize> {
        T::beliefs_key(self)
    }
    fn beliefs_annex(&self) -> Option<&crate::semantics::compiled::Annex> {
        T::beliefs_annex(self)
    }
    fn pending_requests(&self) -> u64 {
        T::pending_requests(self)
    }
    fn is_idle(&self) -> bool {
        T::is_idle(self)
    }
    fn goals(&self, events: bool) -> Vec<&crate::model::term::Term> {
        T::goals(self, events)
    }
}

impl AgentState for State {
    fn beliefs(&self) -> &AtomSet {
        &self.beliefs
    }
    fn pending_requests(&self) -> u64 {
        State::pending_requests(self)
    }
    fn is_idle(&self) -> bool {
        State::is_idle(self)
    }
    fn goals(&self, events: bool) -> Vec<&crate::model::term::Term> {
        goals_of(self.all_intentions(), self.events.iter(), events)
    }
}

impl AgentState for Packed<'_> {
    fn beliefs(&self) -> &AtomSet {
        Packed::beliefs(self)
    }
    fn beliefs_key(&self) -> Option<usize> {
        Some(Packed::beliefs_key(self))
    }
    fn beliefs_annex(&self) -> Option<&crate::semantics::compiled::Annex> {
        Some(Packed::beliefs_annex(self))
    }
    fn pending_requests(&self) -> u64 {
        Packed::pending_requests(self)
    }
    fn is_idle(&self) -> bool {
        Packed::is_idle(self)
    }
    fn goals(&self, events: bool) -> Vec<&crate::model::term::Term> {
        goals_of(self.all_intentions(), self.events(), events)
    }
}

/// A transition label made of reasoning-cycle notes, in either representation.
pub trait CycleNotes {
    /// The notes in order.
    fn notes(&self) -> impl Iterator<Item = &Note>;

    /// While the search lasts, equal for the same notes only ([`Notes::short_key`]), when
    /// they have such an identity: what is read of the notes alone can be kept by it.
    fn identity(&self) -> Option<[usize; 4]> {
        None
    }
}

impl CycleNotes for Vec<Note> {
    fn notes(&self) -> impl Iterator<Item = &Note> {
        self.iter()
    }
}

impl CycleNotes for Notes<'_> {
    fn notes(&self) -> impl Iterator<Item = &Note> {
        self.iter()
    }

    fn identity(&self) -> Option<[usize; 4]> {
        self.short_key()
    }
}
