//! Algorithm 2 (explanation content): the key contextual factors and the intention behind an
//! action.
//!
//! For the action `a_i` at step `i` of the body of the current plan `π_i`, `Γ_i` is the union
//! of the instantiated contexts of `π_i` and of every plan below it on the intention stack
//! ([`gamma`]); the content is `(Γ_i, (a_i, …, a_k))` where `a_k` is the first step from `i`
//! on that modifies `Γ_i`, or the last step of the body when none does ([`content`]).
//!
//! What "modifies" means is a [`Modifies`] strategy:
//!
//! * [`Syntactic`], the paper's test: `(Eff+(a_t) ∪ Eff-(a_t)) ∩ atoms(Γ_i) ≠ ∅`, comparing
//!   atoms (annotations aside) after instantiation;
//! * [`Semantic`]: applying `a_t` (in the state reached by the steps before it) changes the
//!   truth of a literal of `Γ_i`. An action that deletes and re-adds an atom, or adds one
//!   that already holds, modifies `Γ_i` syntactically but not semantically.
//!
//! Decisions the paper leaves open:
//!
//! * **Order of `Γ`**: bottom frame first (the root intention's plan), each context's
//!   literals in source order, duplicates kept at their first place: the paper's example
//!   reads `used(cup1), not dishwasherDoor(open), holding(none)`, from `storeUsedCup` down to
//!   `openDishwasherIfNeed`.
//! * **Unbound variables**: a context variable that the frame's bindings leave unbound (as in
//!   `not cupAt(_, table)`, where negation binds nothing) stands for any object: syntactically
//!   the literal is touched by every instance; semantically its truth is the query's (the
//!   positive atom holds when some instance does).
//! * **Subgoal steps** (`!g` in the body, like `!openDishwasherIfNeed` in `storeUsedCup`)
//!   stay in the step sequence and may end the content. They have no `Eff` of their own, so
//!   by default they never modify `Γ` (the paper's reading); a caller that knows what a
//!   subgoal does (a summary of its plans' effects, or a run of it) passes that with
//!   `with_subgoals`. Other body steps (internal actions, belief updates, tests) are not
//!   part of the snapshot: the user does not see them.

use crate::model::plans::Formula;
use crate::model::{unify, Substitution, Term};
use std::fmt;

/// A literal of a plan context: an atom, positive or under `not`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ContextLiteral {
    /// The atom (possibly `~a`, Jason's strong negation, which is an atom of its own).
    pub atom: Term,
    /// `false` for `not atom`.
    pub positive: bool,
}

impl ContextLiteral {
    /// `atom`.
    pub fn positive(atom: Term) -> ContextLiteral {
        ContextLiteral {
            atom,
            positive: true,
        }
    }

    /// `not atom`.
    pub fn negative(atom: Term) -> ContextLiteral {
        ContextLiteral {
            atom,
            positive: false,
        }
    }

    /// The literal with `s` applied to its atom.
    pub fn instantiate(&self, s: &Substitution) -> ContextLiteral {
        ContextLiteral {
            atom: s.apply(&self.atom),
            positive: self.positive,
        }
    }

    /// The literals a plan context queries, in source order, negative under an odd number of
    /// `not`s. Relations and internal-action conditions (`X > 1`, `.count(...)`) are left
    /// out: they are not beliefs. For `a | b` both sides' literals are listed, since the
    /// context as written does not say which one held; a caller that knows the answer used
    /// can build the list itself.
    pub fn of_formula(f: &Formula) -> Vec<ContextLiteral> {
        f.literals()
            .into_iter()
            .map(|(t, negative)| ContextLiteral {
                atom: t.clone(),
                positive: !negative,
            })
            .collect()
    }
}

impl fmt::Display for ContextLiteral {
    /// `atom` or `not atom`, as in Jason.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.positive {
            write!(f, "{}", self.atom)
        } else {
            write!(f, "not {}", self.atom)
        }
    }
}

/// A step of a plan body as the user sees it: an environment action or a subgoal.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PlanStep {
    /// An environment action `a(x)`.
    Action(Term),
    /// A subgoal `!g` (the term is `g`), achieved in the same intention.
    Subgoal(Term),
}

impl PlanStep {
    /// The action or goal term.
    pub fn term(&self) -> &Term {
        match self {
            PlanStep::Action(t) | PlanStep::Subgoal(t) => t,
        }
    }

    fn instantiate(&self, s: &Substitution) -> PlanStep {
        match self {
            PlanStep::Action(t) => PlanStep::Action(s.apply(t)),
            PlanStep::Subgoal(t) => PlanStep::Subgoal(s.apply(t)),
        }
    }
}

impl fmt::Display for PlanStep {
    /// `a(x)` or `!g`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanStep::Action(t) => write!(f, "{t}"),
            PlanStep::Subgoal(t) => write!(f, "!{t}"),
        }
    }
}

/// One plan instance on an intention stack, as Algorithm 2 needs it.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct FrameSnapshot {
    /// The plan's context literals as written (see [`ContextLiteral::of_formula`]).
    pub context: Vec<ContextLiteral>,
    /// The frame's bindings; applied to `context` and `body`.
    pub bindings: Substitution,
    /// The body's steps from the current one on, as written (or already instantiated:
    /// applying the bindings again changes nothing). In the top frame the first is the action
    /// being explained; below it, the first is the subgoal the frame waits for. Only the top
    /// frame's steps are used.
    pub body: Vec<PlanStep>,
}

/// The effects of a step: the atoms it adds and the atoms it deletes.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Effects {
    /// `Eff+`.
    pub adds: Vec<Term>,
    /// `Eff-`.
    pub dels: Vec<Term>,
}

impl Effects {
    /// `Eff+ = adds`, `Eff- = dels`.
    pub fn new(adds: Vec<Term>, dels: Vec<Term>) -> Effects {
        Effects { adds, dels }
    }

    /// No effect.
    pub fn none() -> Effects {
        Effects::default()
    }

    /// `Eff+ ∪ Eff-`.
    pub fn atoms(&self) -> impl Iterator<Item = &Term> {
        self.adds.iter().chain(&self.dels)
    }

    /// Whether some atom of `Eff+ ∪ Eff-` is an atom of `gamma` (the paper's
    /// `Eff± ∩ Γ ≠ ∅`; see [`atoms_meet`]).
    pub fn touch(&self, gamma: &[ContextLiteral]) -> bool {
        self.atoms()
            .any(|e| gamma.iter().any(|l| atoms_meet(e, &l.atom)))
    }
}

/// Whether two atoms can denote the same ground atom, annotations aside: equal when both are
/// ground, otherwise when they unify (variables of `effect` kept apart from those of
/// `context`, so a context literal with an unbound variable is touched by every instance).
pub fn atoms_meet(effect: &Term, context: &Term) -> bool {
    let (e, c) = (effect.without_annots(), context.without_annots());
    if e.is_ground() && c.is_ground() {
        return e == c;
    }
    let gen = c.vars().iter().map(|v| v.generation()).max().unwrap_or(0);
    let e = e.rename_apart(gen.wrapping_add(1));
    unify(&e, &c, &mut Substitution::new())
}

/// `Γ_i`: the union of the instantiated contexts of the frames of `stack` (bottom first, as
/// an intention stores them), in that order, each literal once at its first place.
pub fn gamma(stack: &[FrameSnapshot]) -> Vec<ContextLiteral> {
    let mut out: Vec<ContextLiteral> = Vec::new();
    for frame in stack {
        for lit in &frame.context {
            let lit = lit.instantiate(&frame.bindings);
            if !out.contains(&lit) {
                out.push(lit);
            }
        }
    }
    out
}

/// How Algorithm 2 decides which step first modifies `Γ`: [`Syntactic`] or [`Semantic`], or a
/// strategy of the caller's.
pub trait Modifies {
    /// The index in `steps` of the first step that modifies `gamma`, if any. `steps` are
    /// instantiated; `steps[0]` is the action being explained.
    fn first_modifier(&self, gamma: &[ContextLiteral], steps: &[PlanStep]) -> Option<usize>;
}

/// A subgoal's effects when the caller gives none: none, as the paper has it.
pub type NoSubgoalEffects = fn(&Term) -> Effects;

fn no_effects(_: &Term) -> Effects {
    Effects::none()
}

/// The paper's test: a step modifies `Γ` when its `Eff+ ∪ Eff-` meets `Γ`'s atoms
/// ([`Effects::touch`]).
#[derive(Clone, Copy)]
pub struct Syntactic<A, G = NoSubgoalEffects> {
    action: A,
    subgoal: G,
}

impl<A: Fn(&Term) -> Effects> Syntactic<A> {
    /// With `effects(action)` the (ground) `Eff±` of an environment action; subgoals have no
    /// effects until [`Syntactic::with_subgoals`] gives them some.
    pub fn new(effects: A) -> Syntactic<A> {
        Syntactic {
            action: effects,
            subgoal: no_effects,
        }
    }
}

impl<A, G> Syntactic<A, G> {
    /// Gives subgoal steps the effects `effects(goal)`, e.g. a summary of what the goal's
    /// plans may change, so that a subgoal can end the content.
    pub fn with_subgoals<H: Fn(&Term) -> Effects>(self, effects: H) -> Syntactic<A, H> {
        Syntactic {
            action: self.action,
            subgoal: effects,
        }
    }
}

impl<A, G> Syntactic<A, G>
where
    A: Fn(&Term) -> Effects,
    G: Fn(&Term) -> Effects,
{
    /// The effects of one step.
    pub fn effects(&self, step: &PlanStep) -> Effects {
        match step {
            PlanStep::Action(a) => (self.action)(a),
            PlanStep::Subgoal(g) => (self.subgoal)(g),
        }
    }
}

impl<A, G> Modifies for Syntactic<A, G>
where
    A: Fn(&Term) -> Effects,
    G: Fn(&Term) -> Effects,
{
    fn first_modifier(&self, gamma: &[ContextLiteral], steps: &[PlanStep]) -> Option<usize> {
        steps.iter().position(|s| self.effects(s).touch(gamma))
    }
}

/// What a subgoal does to the state when the caller gives nothing: nothing.
pub type KeepState<S> = fn(&S, &Term) -> S;

fn keep_state<S: Clone>(s: &S, _: &Term) -> S {
    s.clone()
}

/// The semantic test: starting from `state` (the state in which the explanation is given,
/// before `a_i`), the steps are applied in turn, and a step modifies `Γ` when some literal of
/// `Γ` holds before it and not after, or the other way round. `holds(state, atom)` must
/// answer for an atom with variables whether some instance holds (as a Jason query does).
#[derive(Clone, Copy)]
pub struct Semantic<'s, S, H, A, G = KeepState<S>> {
    state: &'s S,
    holds: H,
    apply: A,
    subgoal: G,
}

impl<'s, S, H, A> Semantic<'s, S, H, A>
where
    S: Clone,
    H: Fn(&S, &Term) -> bool,
    A: Fn(&S, &Term) -> S,
{
    /// With `apply(state, action)` the state after an environment action; subgoals leave the
    /// state unchanged until [`Semantic::with_subgoals`] says otherwise.
    pub fn new(state: &'s S, holds: H, apply: A) -> Semantic<'s, S, H, A> {
        Semantic {
            state,
            holds,
            apply,
            subgoal: keep_state::<S>,
        }
    }
}

impl<'s, S, H, A, G> Semantic<'s, S, H, A, G> {
    /// Gives subgoal steps an effect on the state: `apply(state, goal)`, e.g. the state after
    /// the sub-intention runs.
    pub fn with_subgoals<K: Fn(&S, &Term) -> S>(self, apply: K) -> Semantic<'s, S, H, A, K> {
        Semantic {
            state: self.state,
            holds: self.holds,
            apply: self.apply,
            subgoal: apply,
        }
    }
}

impl<S, H, A, G> Modifies for Semantic<'_, S, H, A, G>
where
    H: Fn(&S, &Term) -> bool,
    A: Fn(&S, &Term) -> S,
    G: Fn(&S, &Term) -> S,
{
    fn first_modifier(&self, gamma: &[ContextLiteral], steps: &[PlanStep]) -> Option<usize> {
        let mut before: Option<S> = None;
        for (t, step) in steps.iter().enumerate() {
            let s = before.as_ref().unwrap_or(self.state);
            let after = match step {
                PlanStep::Action(a) => (self.apply)(s, a),
                PlanStep::Subgoal(g) => (self.subgoal)(s, g),
            };
            // A literal and its atom flip together, so comparing atoms is enough.
            if gamma
                .iter()
                .any(|l| (self.holds)(s, &l.atom) != (self.holds)(&after, &l.atom))
            {
                return Some(t);
            }
            before = Some(after);
        }
        None
    }
}

/// An explanation's content `E(a_i) = (Γ_i, (a_i, …, a_k))`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Content {
    /// `Γ_i`, ordered as [`gamma`] orders it.
    pub context: Vec<ContextLiteral>,
    /// `a_i, …, a_k`: the explained action first, the step that modifies `Γ_i` (or the
    /// body's last) last.
    pub actions: Vec<PlanStep>,
}

impl fmt::Display for Content {
    /// The paper's tuple: `({used(cup1), not dishwasherDoor(open)}, (navigateTo(dishwasher),
    /// openDoor(dishwasher)))`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("({")?;
        for (i, l) in self.context.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{l}")?;
        }
        f.write_str("}, (")?;
        for (i, s) in self.actions.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{s}")?;
        }
        f.write_str("))")
    }
}

/// Algorithm 2 for the action that the top frame of `stack` (its last element) is about to
/// execute: `Γ` from every frame ([`gamma`]), and the top frame's steps from that action up
/// to the first one that `modifies` says changes `Γ`, or all of them.
///
/// `None` when there is nothing to explain: an empty stack, or a top frame whose current step
/// is not an environment action.
pub fn content(stack: &[FrameSnapshot], modifies: &impl Modifies) -> Option<Content> {
    let top = stack.last()?;
    let steps: Vec<PlanStep> = top
        .body
        .iter()
        .map(|s| s.instantiate(&top.bindings))
        .collect();
    if !matches!(steps.first(), Some(PlanStep::Action(_))) {
        return None;
    }
    let context = gamma(stack);
    let k = modifies
        .first_modifier(&context, &steps)
        .unwrap_or(steps.len() - 1);
    let mut actions = steps;
    actions.truncate(k + 1);
    Some(Content { context, actions })
}
