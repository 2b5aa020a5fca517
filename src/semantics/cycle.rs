//! Jason's reasoning cycle as a transition function `State -> [(notes, State)]`.
//!
//! One transition is one reasoning cycle, or the arrival of one request:
//!
//! 1. *Deliberate*: the first event of the queue is handled (Jason's default event selection
//!    is FIFO). Relevant plans are those whose trigger unifies with it; applicable ones have a
//!    context with an answer; Jason's default option selection takes the first applicable
//!    plan in source order with the first answer (`plan_selection = "any"` branches over
//!    every applicable plan). An external event starts an intention; an internal one pushes
//!    the plan on the intention that posted it, with Jason's tail-recursion optimisation (a
//!    recursive subgoal that is the last step of its plan replaces that plan's frame).
//! 2. *Act*: the first running intention executes one body step and goes to the back of the
//!    queue (round-robin). Finished plans are removed in the same cycle, and the bindings a
//!    subgoal made flow back into the plan that posted it.
//!
//! Environment actions run when their PDDL precondition holds; their effects are perceived
//! at once as `+p`/`-p` events. Events that no plan is relevant for are not queued at all:
//! Jason would queue and then discard them, which only costs cycles. A failing step (an
//! action whose precondition fails, a test goal with no answer, a subgoal with no applicable
//! plan) fails the plan as Jason does: the first goal on the intention stack, from the top,
//! with a relevant `-!g` plan gets a `-!g` event, and the frames above it go; with no such
//! goal the intention is dropped and the failure is reported.

use super::java_hash::{literal_hash, negated_literal_hash, JArg};
use super::query::{eval, relation, Beliefs};
use super::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Origin, Pending,
    State,
};
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::plans::{BodyStep, Formula, Step};
use crate::model::project::Project;
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::model::{unify, Substitution};
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::manifest::{Arrival, PlanSelection};
use crate::syntax::{Diagnostic, Span};
use std::collections::HashMap;

/// What a transition did: the material of traces and of the dynamic checks.
#[derive(Clone, Debug, PartialEq)]
pub enum Note {
    /// The user's request arrived.
    Request {
        /// Its index in [`Semantics::requests`].
        index: u8,
    },
    /// An event was taken from the queue.
    Event(EventTrigger),
    /// A plan was chosen for it.
    Plan {
        /// The plan's index.
        plan: u32,
        /// Whose intention.
        origin: Origin,
        /// The answer of its context: the frame's bindings at adoption.
        subst: Substitution,
        /// Where the frame sits on its intention's stack (0 = bottom).
        depth: u16,
    },
    /// An environment action ran.
    Action {
        /// `navigateTo(table)`.
        text: String,
        /// The ground action.
        term: Term,
        /// The intention stack when it ran, bottom first (for explanations).
        stack: Vec<FrameView>,
        /// The plan it belongs to.
        plan: u32,
        /// The step.
        span: Span,
        /// Atoms made true.
        added: Vec<AtomId>,
        /// Atoms made false.
        removed: Vec<AtomId>,
        /// Whose intention.
        origin: Origin,
    },
    /// The agent changed a mental note.
    Belief {
        /// `+visited(table)`.
        text: String,
        /// The plan.
        plan: u32,
        /// Atoms made true.
        added: Vec<AtomId>,
        /// Atoms made false.
        removed: Vec<AtomId>,
        /// Whose intention.
        origin: Origin,
    },
    /// An internal action (or test goal, or constraint) ran.
    Internal {
        /// `.print("x")`.
        text: String,
        /// The plan.
        plan: u32,
        /// Whose intention.
        origin: Origin,
    },
    /// An action was attempted whose precondition does not hold (or that is not defined).
    ActionFailed {
        /// The action.
        text: String,
        /// The plan.
        plan: u32,
        /// The step.
        span: Span,
        /// Why.
        reason: String,
    },
    /// A goal failed and nothing handled it: the intention was dropped.
    GoalFailed {
        /// The goal at the bottom of the dropped intention (the one the user or the agent
        /// set out to achieve).
        goal: EventTrigger,
        /// What failed first: the subgoal with no applicable plan, or the goal of the plan
        /// whose step failed.
        cause: EventTrigger,
        /// The plan whose step failed, if a step failed.
        plan: Option<u32>,
        /// The failing step, if any.
        span: Option<Span>,
        /// Why.
        reason: String,
        /// Whose intention.
        origin: Origin,
    },
    /// An intention ended successfully.
    Finished(Origin),
    /// A goal event had no applicable plan (whether or not a failure plan then handles it).
    NoApplicablePlan(EventTrigger),
    /// What `.print`/`.println` printed (stdlib `println.argsToString`: strings without
    /// quotes, other terms as Jason writes them, unbound variables as `X<no-value>`).
    Printed(String),
}

/// A frame of the running intention as an action saw it: the plan, its bindings, and (for
/// the top frame) the position of the step being executed.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameView {
    /// The plan's index.
    pub plan: u32,
    /// Its bindings.
    pub subst: Substitution,
    /// The block and position of the current step (meaningful for the top frame).
    pub at: (u16, u16),
}

/// One successor.
#[derive(Clone, Debug)]
pub struct Transition {
    /// What happened, in order.
    pub notes: Vec<Note>,
    /// The state after.
    pub next: State,
}

/// A compound step's sub-bodies, by block id.
#[derive(Clone, Debug, Default)]
struct Blocks<'p> {
    blocks: Vec<&'p [Step]>,
    /// For the compound step at (block, pos): its child blocks (if: one per branch, then
    /// else; while/for: one).
    children: HashMap<(u16, u16), Vec<u16>>,
}

fn index_blocks<'p>(body: &'p [Step], b: &mut Blocks<'p>) -> u16 {
    let id = b.blocks.len() as u16;
    b.blocks.push(body);
    for (pos, step) in body.iter().enumerate() {
        let kids = match &step.kind {
            BodyStep::If {
                branches,
                else_body,
            } => {
                let mut kids: Vec<u16> = branches
                    .iter()
                    .map(|(_, body)| index_blocks(body, b))
                    .collect();
                kids.push(index_blocks(else_body, b));
                kids
            }
            BodyStep::While(_, body) | BodyStep::For(_, body) => vec![index_blocks(body, b)],
            _ => continue,
        };
        b.children.insert((id, pos as u16), kids);
    }
    id
}

/// The transition system of one project.
pub struct Semantics<'p> {
    /// The project.
    pub project: &'p Project,
    /// Every ground request the user may make, in order.
    pub requests: Vec<Term>,
    environment: Vec<bool>,
    blocks: Vec<Blocks<'p>>,
    relevant: HashMap<(u8, u8, String, usize), Vec<u32>>,
    max_requests: u32,
    arrival_any: bool,
    select_any: bool,
    /// `[explanation] emitted_by`: the agent's own explanation action.
    emitted_by: Option<String>,
    /// No plan reads or changes other intentions (see [`Semantics::is_local`]).
    local: bool,
    /// Per rule head (functor, arity): every atom proving it may read.
    rule_reads: HashMap<(String, usize), AtomSet>,
    /// The agent's name: Jason names an agent run without a `.mas2j` after its source
    /// file (`kitchen.asl` is `kitchen`).
    agent_name: String,
    /// Per predicate: whether the order of its beliefs can decide an answer (some query
    /// asks it with a variable, or `-b`/`-+b` removes the first of several).
    ordered: Vec<bool>,
    /// Per atom: the `hashCode()` of the literal Jason builds for it, which places it in
    /// `Agent.buf`'s set of percepts.
    jhash: Vec<i32>,
    /// The environment's atoms.
    env_atoms: AtomSet,
    /// The most environment atoms one action changes.
    max_effect: usize,
}

fn op_key(op: TriggerOp) -> u8 {
    match op {
        TriggerOp::Add => 0,
        TriggerOp::Del => 1,
        TriggerOp::GoalState => 2,
    }
}

fn kind_key(k: TriggerKind) -> u8 {
    match k {
        TriggerKind::Belief => 0,
        TriggerKind::Achieve => 1,
        TriggerKind::Test => 2,
    }
}

/// Most plans an intention's stack may hold. Jason has no bound: a failure plan that fails
/// at the bottom of its stack has its `-!g` posted again, one plan deeper each time
/// (`Intention.findEventForFailure`), and recursion without end grows the stack too; such
/// a run is reported (a goal failure whose reason says so) instead of explored forever.
pub const MAX_STACK: usize = 64;

/// Most requests a run can track (one bit each in [`State::requested`]).
pub const MAX_REQUESTS: usize = 64;

impl<'p> Semantics<'p> {
    /// The transition system of a loaded project. Fails when the requests cannot be
    /// grounded (more than [`MAX_REQUESTS`] instances, or a goal with unknown parameters).
    pub fn new(project: &'p Project) -> Result<Semantics<'p>, Vec<Diagnostic>> {
        let environment = (0..project.atoms.pred_count())
            .map(|p| {
                let name = project
                    .atoms
                    .pred_name(crate::model::atoms::PredId(p as u32));
                project
                    .vocabulary
                    .predicate(name)
                    .is_some_and(|(_, sig)| sig.is_environment())
            })
            .collect();
        let mut blocks = Vec::new();
        let mut relevant: HashMap<(u8, u8, String, usize), Vec<u32>> = HashMap::new();
        for plan in &project.plans.plans {
            let mut b = Blocks::default();
            index_blocks(&plan.body, &mut b);
            blocks.push(b);
            let t = &plan.trigger;
            relevant
                .entry((
                    op_key(t.op),
                    kind_key(t.kind),
                    t.literal.functor().unwrap_or("").to_string(),
                    t.literal.arity(),
                ))
                .or_default()
                .push(plan.index as u32);
        }
        let requests = ground_requests(project)?;
        let m = &project.manifest;
        let mut sem = Semantics {
            project,
            requests,
            environment,
            blocks,
            relevant,
            max_requests: m.requests.max,
            arrival_any: m.requests.arrival == Arrival::Any,
            select_any: m.bounds.plan_selection == PlanSelection::Any,
            emitted_by: m
                .explanation
                .as_ref()
                .and_then(|e| e.emitted_by.as_ref())
                .map(|e| e.value.clone()),
            local: project
                .plans
                .plans
                .iter()
                .all(|p| formula_is_local(&p.context) && p.body.iter().all(step_is_local)),
            rule_reads: HashMap::new(),
            ordered: Vec::new(),
            jhash: Vec::new(),
            env_atoms: AtomSet::empty(project.atoms.len()),
            max_effect: project
                .actions
                .all()
                .iter()
                .map(|a| a.touched().len())
                .max()
                .unwrap_or(0),
            agent_name: m
                .agent
                .plans
                .path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "agent".into()),
        };
        sem.rule_reads = sem.compute_rule_reads();
        sem.ordered = ordered_predicates(project);
        let atoms = &project.atoms;
        for a in (0..atoms.len() as u32).map(AtomId) {
            let (p, args) = atoms.decode(a);
            let names: Vec<&str> = args
                .iter()
                .map(|o| project.universe.object_name(*o))
                .collect();
            let jargs: Vec<JArg> = names.iter().map(|n| JArg::Atom(n)).collect();
            sem.jhash.push(match atoms.pred_name(p).strip_prefix('~') {
                Some(positive) => negated_literal_hash(positive, &jargs),
                None => literal_hash(atoms.pred_name(p), &jargs),
            });
            if sem.environment[p.0 as usize] {
                sem.env_atoms.insert(a);
            }
        }
        Ok(sem)
    }

    /// The line of a step, for failure annotations.
    fn line_of(&self, at: Option<(u32, Span)>) -> Option<usize> {
        at.map(|(_, span)| self.project.map.location(span).line)
    }

    /// Whether the order of predicate `p`'s beliefs is kept in [`State::order`].
    pub fn is_ordered(&self, p: crate::model::atoms::PredId) -> bool {
        self.ordered[p.0 as usize]
    }

    /// How many of the environment's atoms hold in `beliefs`.
    pub fn env_count(&self, beliefs: &AtomSet) -> usize {
        let env = self.env_atoms.words();
        beliefs
            .words()
            .iter()
            .zip(env)
            .map(|(b, e)| (b & e).count_ones() as usize)
            .sum()
    }

    /// What of `env_count` an act phase depends on: the size of Jason's percept set
    /// decides the order of perceived effects ([`Semantics::java_order`]) only through its
    /// number of buckets, which is one value for every count an action can lead to, unless
    /// the count is near a resize (then the count itself).
    pub fn env_class(&self, env: usize) -> u64 {
        let lo = java_capacity(env.saturating_sub(self.max_effect));
        let hi = java_capacity(env + self.max_effect);
        if lo == hi {
            u64::from(lo)
        } else {
            1 << 40 | env as u64
        }
    }

    /// Sorts percepts as Jason's belief update meets them: `Agent.buf` puts the perceived
    /// literals (given in atom order) in a fresh `HashSet` and goes through it, so the
    /// order is the set's bucket order for a set of `size` elements
    /// (`java.util.HashMap`: 16 buckets, doubled past three quarters full; a bucket keeps
    /// insertion order). Removed percepts are taken in the same bucket order (Jason goes
    /// through its belief base's percept set, whose buckets may hold them in the order
    /// they were first perceived: where two share a bucket, atom order is used).
    fn java_order(&self, atoms: &mut [AtomId], size: usize) {
        if atoms.len() < 2 {
            return;
        }
        let cap = java_capacity(size);
        let bucket = |a: &AtomId| {
            let h = self.jhash[a.0 as usize] as u32;
            (h ^ (h >> 16)) & (cap - 1)
        };
        atoms.sort_by_key(|a| (bucket(a), a.0));
    }

    /// Applies to a whole state's `order` what an act phase did to the order of the
    /// beliefs it read: `removed` and `added` leave their places, and `front` (the added
    /// ones whose order is kept, newest first) goes in front of their predicates' beliefs.
    pub(super) fn reorder_front(
        &self,
        order: &mut Vec<AtomId>,
        front: &[AtomId],
        removed: &AtomSet,
        added: &AtomSet,
    ) {
        order.retain(|a| !removed.contains(*a) && !added.contains(*a));
        // Inserting the oldest first in front of its group leaves the newest in front.
        for &a in front.iter().rev() {
            self.put_in_front(order, a);
        }
    }

    /// Puts `a` in front of its predicate's beliefs in `order`.
    fn put_in_front(&self, order: &mut Vec<AtomId>, a: AtomId) {
        let pred = |a: AtomId| self.project.atoms.pred_of(a);
        let p = pred(a);
        let at = order
            .iter()
            .position(|x| pred(*x) >= p)
            .unwrap_or(order.len());
        order.insert(at, a);
    }

    /// Keeps [`State::order`] for a belief added (in front of its predicate's beliefs)
    /// or removed.
    fn reorder(&self, s: &mut State, added: &[AtomId], removed: &[AtomId]) {
        let pred = |a: AtomId| self.project.atoms.pred_of(a);
        for &a in removed.iter().chain(added) {
            if self.is_ordered(pred(a)) {
                s.order.retain(|x| *x != a);
            }
        }
        for &a in added {
            if self.is_ordered(pred(a)) {
                self.put_in_front(&mut s.order, a);
            }
        }
    }

    /// The atoms each rule head's proof may read: those its bodies query, and those of
    /// the rules they call, to a fixed point (bindings are not followed).
    fn compute_rule_reads(&self) -> HashMap<(String, usize), AtomSet> {
        let rules = &self.project.plans.rules;
        let key = |t: &Term| (t.functor().unwrap_or("").to_string(), t.arity());
        let mut reads: HashMap<(String, usize), AtomSet> = rules
            .iter()
            .map(|r| (key(&r.head), AtomSet::empty(self.project.atoms.len())))
            .collect();
        let empty = Substitution::new();
        loop {
            let mut changed = false;
            for r in rules {
                let mut out = AtomSet::empty(self.project.atoms.len());
                self.formula_reads_with(&r.body, &empty, &mut out, &reads);
                let k = key(&r.head);
                let mut now = reads[&k].clone();
                for a in out.iter() {
                    if !now.contains(a) {
                        now.insert(a);
                        changed = true;
                    }
                }
                reads.insert(k, now);
            }
            if !changed {
                return reads;
            }
        }
    }

    /// Whether one reasoning cycle's phases depend only on their own part of the state:
    /// deliberation on the event and the beliefs, acting on the intention and the beliefs.
    /// True unless some plan uses `.desire`, `.intend` (which read the other intentions) or
    /// `.succeed_goal`, `.fail_goal`, `.drop_desire`, `.drop_intention` (which change
    /// them). The compiled search ([`super::compiled::Compiled`]) relies on it.
    pub fn is_local(&self) -> bool {
        self.local
    }

    /// Every belief deliberating on `ev` may read: the atoms the contexts of its relevant
    /// plans may query (an over-approximation; see [`Semantics::literal_reads`]). The
    /// compiled search memoizes deliberation on the beliefs restricted to these atoms.
    pub(super) fn event_reads(&self, ev: &Event) -> AtomSet {
        let mut out = AtomSet::empty(self.project.atoms.len());
        for &pi in self.relevant_plans(&ev.trigger) {
            let plan = &self.project.plans.plans[pi as usize];
            let mut u = Substitution::new();
            if unify(&plan.trigger.literal, &ev.trigger.literal, &mut u) {
                self.formula_reads(&plan.context, &u, &mut out);
            }
            // A new frame is normalized at the first step of its body, which reads nothing
            // unless the body is empty (then there is no cursor at all).
        }
        out
    }

    /// Every belief the act phase may read when `int` runs: its next step's queries and
    /// the atoms of its action (precondition, conditions and effects), or, at the end of
    /// a `while` body, the loop's condition.
    pub(super) fn intention_reads(&self, int: &Intention) -> AtomSet {
        let mut out = AtomSet::empty(self.project.atoms.len());
        let Some(f) = int.frames.last() else {
            return out;
        };
        let Some(c) = f.cursors.last() else {
            return out;
        };
        let blocks = &self.blocks[f.plan as usize];
        let Some(step) = blocks.blocks[c.block as usize].get(c.pos as usize) else {
            if let CursorKind::While { outer, at, base } = &c.kind {
                if let BodyStep::While(cond, _) = &blocks.blocks[*outer as usize][*at as usize].kind
                {
                    self.formula_reads(cond, base, &mut out);
                }
            }
            return out;
        };
        match &step.kind {
            BodyStep::Action(t) if self.is_emission(t) => {}
            BodyStep::Action(t) => {
                if let Some(ga) = eval(t, &f.subst)
                    .ok()
                    .and_then(|t| self.ground_action(&t).ok())
                {
                    let conds = std::iter::once(&ga.pre).chain(ga.effects.iter().map(|e| &e.when));
                    conds.flat_map(|c| c.atoms()).for_each(|a| out.insert(a));
                    for e in &ga.effects {
                        e.add.iter().chain(&e.del).for_each(|a| out.insert(*a));
                    }
                }
            }
            BodyStep::Internal(t) => {
                self.formula_reads(&Formula::Call(t.clone()), &f.subst, &mut out)
            }
            BodyStep::Test(cond) | BodyStep::While(cond, _) | BodyStep::For(cond, _) => {
                self.formula_reads(cond, &f.subst, &mut out)
            }
            BodyStep::If { branches, .. } => {
                for (cond, _) in branches {
                    self.formula_reads(cond, &f.subst, &mut out);
                }
            }
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                let lit = eval(t, &f.subst).unwrap_or_else(|_| f.subst.apply(t));
                if matches!(step.kind, BodyStep::DelAddBel(_)) {
                    // `-+b` removes any belief of the predicate.
                    let p = self.project.atoms.pred_of_literal(&lit);
                    for a in p.into_iter().flat_map(|p| self.project.atoms.atoms_of(p)) {
                        out.insert(a);
                    }
                } else {
                    self.literal_reads(&lit, &mut out);
                }
                if let Some(a) = self.ground_atom(&lit) {
                    out.insert(a);
                }
            }
            BodyStep::Achieve { .. } | BodyStep::Constraint(..) => {}
        }
        out
    }

    /// The atoms a formula's answers may depend on under `s` (bindings made inside the
    /// formula are not followed: their variables count as unbound).
    fn formula_reads(&self, f: &Formula, s: &Substitution, out: &mut AtomSet) {
        self.formula_reads_with(f, s, out, &self.rule_reads)
    }

    fn formula_reads_with(
        &self,
        f: &Formula,
        s: &Substitution,
        out: &mut AtomSet,
        rules: &HashMap<(String, usize), AtomSet>,
    ) {
        let literal = |t: &Term, out: &mut AtomSet| {
            let t = s.apply(t);
            self.literal_reads(&t, out);
            let k = (t.functor().unwrap_or("").to_string(), t.arity());
            if let Some(r) = rules.get(&k) {
                r.iter().for_each(|a| out.insert(a));
            }
        };
        match f {
            Formula::True | Formula::Rel(..) => {}
            Formula::Literal(t) => literal(t, out),
            Formula::Not(g) => self.formula_reads_with(g, s, out, rules),
            Formula::And(a, b) | Formula::Or(a, b) => {
                self.formula_reads_with(a, s, out, rules);
                self.formula_reads_with(b, s, out, rules);
            }
            Formula::Call(t) => match (t.functor(), t.args()) {
                (Some(".count"), [q, _])
                | (Some(".findall"), [_, q, _])
                | (Some(".abolish"), [q]) => literal(q, out),
                _ => {}
            },
        }
    }

    /// The atoms [`Beliefs::literal_answers`] may look at for `lit`: those of its
    /// predicate whose arguments agree with its object arguments.
    fn literal_reads(&self, lit: &Term, out: &mut AtomSet) {
        let atoms = &self.project.atoms;
        let Some(p) = atoms.pred_of_literal(lit) else {
            return;
        };
        if atoms.pred_params(p).len() != lit.arity() {
            return;
        }
        let fixed: Vec<Option<ObjectId>> = lit
            .args()
            .iter()
            .map(|a| self.project.universe.object_of(a))
            .collect();
        let any_fixed = fixed.iter().any(Option::is_some);
        for a in atoms.atoms_of(p) {
            if any_fixed {
                let (_, args) = atoms.decode(a);
                if fixed
                    .iter()
                    .zip(&args)
                    .any(|(f, o)| f.is_some_and(|f| f != *o))
                {
                    continue;
                }
            }
            out.insert(a);
        }
    }

    /// Whether a request may arrive in a state with these requests made and this idleness.
    pub(super) fn may_request(&self, requested: u64, idle: bool) -> bool {
        requested.count_ones() < self.max_requests && (self.arrival_any || idle)
    }

    /// The event of request `r`.
    pub fn request_event(&self, r: usize) -> Event {
        // Posted as Jason posts an initial goal (`source(self)`), or, when the manifest says
        // who asks, as that agent's `achieve` message (`source(from)`).
        let from = self.project.manifest.requests.from.as_ref();
        let source = from.map_or("self", |f| f.value.as_str());
        Event {
            trigger: EventTrigger {
                op: TriggerOp::Add,
                kind: TriggerKind::Achieve,
                literal: with_source(&self.requests[r], source),
            },
            intention: None,
            origin: Origin::Request(r as u8),
            posted_at: None,
        }
    }

    fn beliefs<'s>(&'s self, state: &'s State) -> Beliefs<'s> {
        Beliefs {
            atoms: &self.project.atoms,
            universe: &self.project.universe,
            environment: &self.environment,
            state,
            selected: None,
            rules: &self.project.plans.rules,
            depth: std::cell::Cell::new(0),
            agent_name: &self.agent_name,
            ordered: &self.ordered,
        }
    }

    fn relevant_plans(&self, t: &EventTrigger) -> &[u32] {
        self.relevant
            .get(&(
                op_key(t.op),
                kind_key(t.kind),
                t.literal.functor().unwrap_or("").to_string(),
                t.literal.arity(),
            ))
            .map_or(&[], |v| v.as_slice())
    }

    /// The initial states of the transition system: one per initial state of the project,
    /// with the agent's initial goals and the perception of every initial percept queued.
    pub fn initial_states(&self) -> Vec<State> {
        self.project
            .initial
            .states
            .iter()
            .map(|b| self.initial_state(b))
            .collect()
    }

    /// The state a run starts in when the environment is `beliefs`. Events are queued
    /// as Jason queues them before and in the first cycle: the agent's initial beliefs
    /// (`Agent.addInitialBelsInBB` adds them last first), its initial goals, then the
    /// first perception of the environment (`Agent.buf` in the first `sense`).
    pub fn initial_state(&self, beliefs: &AtomSet) -> State {
        let mut s = State {
            beliefs: beliefs.clone(),
            order: Vec::new(),
            events: Vec::new(),
            intentions: Vec::new(),
            pending: None,
            requested: 0,
        };
        let notes = &self.project.initial.agent_beliefs;
        let noted: Vec<AtomId> = notes.iter().rev().copied().collect();
        s.beliefs = AtomSet::empty(beliefs.words().len() * 64);
        noted.iter().for_each(|a| s.beliefs.insert(*a));
        self.perceive(&mut s, &noted, &[]);
        for (k, (goal, _)) in self.project.plans.initial_goals.iter().enumerate() {
            s.events.push(Event {
                trigger: EventTrigger {
                    op: TriggerOp::Add,
                    kind: TriggerKind::Achieve,
                    literal: with_source(goal, "self"),
                },
                intention: None,
                origin: Origin::InitialGoal(k as u8),
                posted_at: None,
            });
        }
        let mut perceived: Vec<AtomId> = beliefs.iter().filter(|a| !notes.contains(a)).collect();
        let n = perceived.len();
        self.java_order(&mut perceived, n);
        s.beliefs = beliefs.clone();
        self.perceive(&mut s, &perceived, &[]);
        s
    }

    /// The block of steps `block` of plan `plan` (0 is the body).
    pub fn block(&self, plan: u32, block: u16) -> &[Step] {
        self.blocks[plan as usize].blocks[block as usize]
    }

    /// The index of a ground request, if the manifest allows it.
    pub fn request_index(&self, goal: &Term) -> Option<u8> {
        self.requests
            .iter()
            .position(|r| r == goal)
            .map(|i| i as u8)
    }

    /// Records beliefs just added and removed, in the order Jason adds and removes them:
    /// [`State::order`] is updated, and `+p`/`-p` queued for those some plan is relevant
    /// for (deletions first, as `Agent.buf` does).
    fn perceive(&self, s: &mut State, added: &[AtomId], removed: &[AtomId]) {
        self.reorder(s, added, removed);
        let b = self.beliefs(s);
        let mut new_events = Vec::new();
        for (atoms, op) in [(removed, TriggerOp::Del), (added, TriggerOp::Add)] {
            for a in atoms {
                let trigger = EventTrigger {
                    op,
                    kind: TriggerKind::Belief,
                    literal: b.atom_term(*a),
                };
                if !self.relevant_plans(&trigger).is_empty() {
                    new_events.push(Event {
                        trigger,
                        intention: None,
                        origin: Origin::Spawned,
                        posted_at: None,
                    });
                }
            }
        }
        s.events.extend(new_events);
    }

    /// Every successor of `state`.
    pub fn successors(&self, state: &State) -> Vec<Transition> {
        let mut out = Vec::new();
        if self.may_request(state.requested, state.is_idle()) {
            for r in 0..self.requests.len() {
                if state.requested >> r & 1 == 1 {
                    continue;
                }
                let mut next = state.clone();
                next.requested |= 1 << r;
                next.events.push(self.request_event(r));
                out.push(Transition {
                    notes: vec![Note::Request { index: r as u8 }],
                    next,
                });
            }
        }
        if !state.is_idle() {
            out.extend(self.cycle(state));
        }
        out
    }

    /// One reasoning cycle: deliberate on the first event, then act on the first intention.
    fn cycle(&self, state: &State) -> Vec<Transition> {
        let mut options: Vec<(State, Vec<Note>)> = Vec::new();
        if state.events.is_empty() {
            options.push((state.clone(), Vec::new()));
        } else {
            let mut s = state.clone();
            let ev = s.events.remove(0);
            options = self.deliberate(s, ev);
        }
        options
            .into_iter()
            .map(|(mut s, mut notes)| {
                self.proc_act(&mut s, &mut notes);
                self.act(&mut s, &mut notes);
                Transition { notes, next: s }
            })
            .collect()
    }

    /// Handles one event (already out of the queue): every option the plan selection
    /// allows, as its own state.
    pub(super) fn deliberate(&self, s: State, ev: Event) -> Vec<(State, Vec<Note>)> {
        let mut notes = vec![Note::Event(ev.trigger.clone())];
        let applicable = self.applicable_for(&s, &ev, !self.select_any);
        if applicable.is_empty() {
            let mut s = s;
            if ev.trigger.kind != TriggerKind::Belief {
                notes.push(Note::NoApplicablePlan(ev.trigger.clone()));
            }
            if ev.trigger.op == TriggerOp::Add && ev.trigger.kind != TriggerKind::Belief {
                let reason = if self.relevant_plans(&ev.trigger).is_empty() {
                    "no relevant plan"
                } else {
                    "no applicable plan"
                };
                self.goal_failed_from_event(&mut s, ev, reason, &mut notes);
            } else if ev.trigger.op == TriggerOp::Del && ev.trigger.kind != TriggerKind::Belief {
                // A failure event nothing can handle: Jason's "Could not finish
                // intention"; the intention is gone.
                let goal = ev
                    .intention
                    .as_ref()
                    .and_then(|i| i.frames.first())
                    .map_or_else(|| ev.trigger.clone(), |f| f.trigger.clone());
                notes.push(Note::GoalFailed {
                    goal,
                    cause: ev.trigger.clone(),
                    plan: ev.posted_at.map(|(p, _)| p),
                    span: ev.posted_at.map(|(_, sp)| sp),
                    reason: "no applicable failure plan".into(),
                    origin: ev.origin,
                });
            }
            // Belief events with no applicable plan are discarded, as in Jason.
            return vec![(s, notes)];
        }
        applicable
            .into_iter()
            .map(|(pi, answer)| {
                let mut s = s.clone();
                let mut notes = notes.clone();
                let plan = &self.project.plans.plans[pi as usize];
                let mut frame = Frame {
                    plan: pi,
                    subst: answer,
                    cursors: if plan.body.is_empty() {
                        Vec::new()
                    } else {
                        vec![Cursor {
                            block: 0,
                            pos: 0,
                            kind: CursorKind::Seq,
                        }]
                    },
                    trigger: ev.trigger.clone(),
                    calling: None,
                };
                self.normalize(&mut frame);
                let origin = match &ev.intention {
                    Some(i) => i.origin,
                    None => ev.origin,
                };
                let subst = frame.subst.clone();
                let depth = match ev.intention.clone() {
                    None => {
                        s.intentions.push(Intention {
                            frames: vec![frame],
                            origin,
                        });
                        0
                    }
                    Some(int) if int.frames.len() >= MAX_STACK => {
                        let goal = int.frames.first().map(|f| f.trigger.clone());
                        notes.push(Note::GoalFailed {
                            goal: goal.unwrap_or_else(|| ev.trigger.clone()),
                            cause: ev.trigger.clone(),
                            plan: Some(pi),
                            span: Some(plan.span),
                            reason: format!(
                                "its intention would hold more than {MAX_STACK} plans (Jason grows it without bound)"
                            ),
                            origin,
                        });
                        return (s, notes);
                    }
                    Some(mut int) => {
                        let is_goal_add = ev.trigger.op == TriggerOp::Add
                            && ev.trigger.kind == TriggerKind::Achieve;
                        if let Some(top) = int.frames.last() {
                            // Jason's TRO: a recursive subgoal that is the last step of its plan.
                            if is_goal_add
                                && top.cursors.is_empty()
                                && top.calling.is_some()
                                && top.trigger.op == TriggerOp::Add
                                && top.trigger.kind == TriggerKind::Achieve
                                && top.trigger.literal.functor() == ev.trigger.literal.functor()
                                && top.trigger.literal.arity() == ev.trigger.literal.arity()
                            {
                                int.frames.pop();
                            }
                        }
                        int.frames.push(frame);
                        let depth = int.frames.len() - 1;
                        s.intentions.push(int);
                        depth
                    }
                };
                notes.push(Note::Plan {
                    plan: pi,
                    origin,
                    subst,
                    depth: depth as u16,
                });
                (s, notes)
            })
            .collect()
    }

    /// The applicable plans for an event in `s`, in source order, each with the first
    /// answer of its context; only the first one when `first_only`.
    pub fn applicable(
        &self,
        s: &State,
        trigger: &EventTrigger,
        first_only: bool,
    ) -> Vec<(u32, Substitution)> {
        self.applicable_in(self.beliefs(s), trigger, first_only)
    }

    /// As [`Semantics::applicable`], for the event just taken out of the queue of `s`.
    fn applicable_for(&self, s: &State, ev: &Event, first_only: bool) -> Vec<(u32, Substitution)> {
        let mut b = self.beliefs(s);
        b.selected = Some(ev);
        self.applicable_in(b, &ev.trigger, first_only)
    }

    fn applicable_in(
        &self,
        b: Beliefs,
        trigger: &EventTrigger,
        first_only: bool,
    ) -> Vec<(u32, Substitution)> {
        let mut out = Vec::new();
        for &pi in self.relevant_plans(trigger) {
            let plan = &self.project.plans.plans[pi as usize];
            let mut u = Substitution::new();
            if !unify(&plan.trigger.literal, &trigger.literal, &mut u) {
                continue;
            }
            if let Some(answer) = b.answers(&plan.context, &u).into_iter().next() {
                out.push((pi, answer));
                if first_only {
                    break;
                }
            }
        }
        out
    }

    /// No applicable plan for the goal addition `ev` (`+!g` or `+?g`): Jason's
    /// `generateGoalDeletionFromEvent`. The failure event is looked for from the event's
    /// own goal down the intention that waits for it; with none, that intention is
    /// dropped (an external event just fails).
    fn goal_failed_from_event(
        &self,
        s: &mut State,
        ev: Event,
        reason: &str,
        notes: &mut Vec<Note>,
    ) {
        let fail = ev
            .intention
            .as_ref()
            .and_then(|int| self.find_event_for_failure(int, &ev.trigger));
        let error = if self.relevant_plans(&ev.trigger).is_empty() {
            "no_relevant"
        } else {
            "no_applicable"
        };
        match (fail, ev.intention) {
            (Some(fail), Some(int)) => s.events.push(Event {
                trigger: with_error(fail, error, self.line_of(ev.posted_at)),
                intention: Some(int),
                origin: ev.origin,
                posted_at: ev.posted_at,
            }),
            (_, int) => notes.push(Note::GoalFailed {
                goal: int
                    .as_ref()
                    .and_then(|i| i.frames.first())
                    .map_or_else(|| ev.trigger.clone(), |f| f.trigger.clone()),
                cause: ev.trigger,
                plan: ev.posted_at.map(|(p, _)| p),
                span: ev.posted_at.map(|(_, sp)| sp),
                reason: reason.into(),
                origin: ev.origin,
            }),
        }
    }

    /// Jason's `Intention.findEventForFailure`: the failure event for `tevent`, the
    /// trigger that failed (the top plan's, or a subgoal event's that had no applicable
    /// plan). From the top of the stack down, the first goal with a relevant `-` plan gets
    /// it. When a failure plan itself failed (`tevent` is `-!g`), the search starts below
    /// the frames of `g`; if `g` is the bottom of the stack, `-!g` is posted again.
    fn find_event_for_failure(
        &self,
        int: &Intention,
        tevent: &EventTrigger,
    ) -> Option<EventTrigger> {
        let frames = &int.frames;
        // Jason's iterator over the stack, top first: `next` frames remain.
        let mut next = frames.len();
        let mut tevent = tevent.clone();
        let unifies = |f: &Frame, t: &EventTrigger| {
            crate::model::unifier(&f.trigger.literal, &t.literal).is_some()
        };
        if tevent.kind != TriggerKind::Belief && tevent.op == TriggerOp::Del && next > 0 {
            next -= 1; // the failed failure plan
            let mut im = next;
            let mut found = false;
            while next > 0 && !found {
                next -= 1;
                im = next;
                while next > 0 && unifies(&frames[im], &tevent) {
                    next -= 1;
                    im = next;
                    found = true;
                }
            }
            tevent = frames[im].trigger.clone();
        }
        let del = |t: &EventTrigger| EventTrigger {
            op: TriggerOp::Del,
            kind: t.kind,
            literal: t.literal.clone(),
        };
        let mut fail = del(&tevent);
        while self.relevant_plans(&fail).is_empty() && next > 0 {
            next -= 1;
            tevent = frames[next].trigger.clone();
            fail = del(&tevent);
        }
        (tevent.kind != TriggerKind::Belief && !self.relevant_plans(&fail).is_empty())
            .then_some(fail)
    }

    /// A step of the top plan of `int` failed: Jason's `generateGoalDeletion`. The stack
    /// stays as it is (the failed plan marked failed, its step not done) and the failure
    /// event carries it; with no failure event, the intention is dropped.
    #[allow(clippy::too_many_arguments)]
    fn fail_intention(
        &self,
        s: &mut State,
        mut int: Intention,
        failed: &EventTrigger,
        step: Option<(u32, Span)>,
        reason: &str,
        error: &str,
        notes: &mut Vec<Note>,
    ) {
        if let Some(top) = int.frames.last_mut() {
            top.calling = None;
        }
        let tevent = int
            .frames
            .last()
            .map_or_else(|| failed.clone(), |f| f.trigger.clone());
        if let Some(fail) = self.find_event_for_failure(&int, &tevent) {
            let origin = int.origin;
            s.events.push(Event {
                trigger: with_error(fail, error, self.line_of(step)),
                intention: Some(int),
                origin,
                posted_at: step,
            });
            return;
        }
        let goal = int
            .frames
            .first()
            .map(|f| f.trigger.clone())
            .unwrap_or_else(|| failed.clone());
        notes.push(Note::GoalFailed {
            goal,
            cause: failed.clone(),
            plan: step.map(|(p, _)| p),
            span: step.map(|(_, sp)| sp),
            reason: reason.into(),
            origin: int.origin,
        });
    }

    /// Moves a frame's cursors to the next step to execute, leaving blocks that have
    /// ended; a loop's body that has ended stays, its cursor past the end, until the loop
    /// is tested again ([`Semantics::loop_again`]). `cursors` is empty when the body is done.
    fn normalize(&self, f: &mut Frame) {
        let blocks = &self.blocks[f.plan as usize];
        while let Some(c) = f.cursors.last() {
            if (c.pos as usize) < blocks.blocks[c.block as usize].len()
                || !matches!(c.kind, CursorKind::Seq)
            {
                return;
            }
            f.cursors.pop();
        }
    }

    /// Tests a loop again once its body has ended: `while` restores the bindings it had
    /// when it first ran and asks its condition again (stdlib `loop`: `un.clear();
    /// un.compose(ubak)`), so variables bound in the body are free on the next pass and
    /// after the loop; `for` takes its next answer, and restores the bindings from before
    /// the loop when there is none (stdlib `foreach`). The answers of `for` are computed
    /// when it first runs.
    fn loop_again(&self, f: &mut Frame, s: &State) {
        let blocks = &self.blocks[f.plan as usize];
        let Some(c) = f.cursors.last_mut() else {
            return;
        };
        match &mut c.kind {
            CursorKind::Seq => {}
            CursorKind::While { outer, at, base } => {
                let cond = match &blocks.blocks[*outer as usize][*at as usize].kind {
                    BodyStep::While(cond, _) => cond,
                    _ => unreachable!("a while cursor points at a while step"),
                };
                let base = base.clone();
                match self.beliefs(s).answers(cond, &base).into_iter().next() {
                    Some(a) => {
                        f.subst = a;
                        c.pos = 0;
                    }
                    None => {
                        f.subst = base;
                        f.cursors.pop();
                    }
                }
            }
            CursorKind::For { rest, base } => {
                if rest.is_empty() {
                    f.subst = base.clone();
                    f.cursors.pop();
                } else {
                    f.subst = rest.remove(0);
                    c.pos = 0;
                }
            }
        }
        self.normalize(f);
    }

    /// Jason's `applyProcAct`, the act phase's first stage: the feedback of the action
    /// sent in the previous cycle. A done action's intention goes to the back of the
    /// queue (after any the deliberation of this cycle started) and its finished plans are
    /// cleared; a failed one's plan fails (`generateGoalDeletion`).
    pub(super) fn proc_act(&self, s: &mut State, notes: &mut Vec<Note>) {
        let Some(p) = s.pending.take() else {
            return;
        };
        let mut int = p.intention;
        match p.failure {
            Some(f) => {
                let failed = int
                    .frames
                    .last()
                    .map(|f| f.trigger.clone())
                    .expect("a frame");
                let reason = format!("{}: {}", f.action, f.why);
                let at = Some((f.plan, f.span));
                self.fail_intention(s, int, &failed, at, &reason, "action_failed", notes);
            }
            None => {
                if self.clear_finished(&mut int, notes) {
                    s.intentions.push(int);
                }
            }
        }
    }

    /// The act phase: the first intention runs one step.
    pub(super) fn act(&self, s: &mut State, notes: &mut Vec<Note>) {
        let env = self.env_count(&s.beliefs);
        self.act_with(s, notes, env)
    }

    /// [`Semantics::act`] on a state that may hold only some of the beliefs, `env` of the
    /// environment's atoms holding in the whole state (their number decides the order in
    /// which Jason perceives an action's effects).
    pub(super) fn act_with(&self, s: &mut State, notes: &mut Vec<Note>, env: usize) {
        if s.intentions.is_empty() {
            return;
        }
        let mut int = s.intentions.remove(0);
        let finished_top = int.frames.last().is_none_or(|f| f.cursors.is_empty());
        if !finished_top {
            match self.step(s, &mut int, notes, env) {
                Flow::Continue => {}
                Flow::Suspended | Flow::Gone => return,
            }
        }
        if self.clear_finished(&mut int, notes) {
            s.intentions.push(int);
        }
    }

    /// Pops finished plans, as Jason's `applyClrInt`; returns whether the intention is
    /// still alive. A finished subgoal's bindings flow back into the plan that posted it,
    /// which goes on after its `!g`. A finished failure plan `-!g` takes with it the
    /// plans above the one it handled, down to the plan of `g` itself or to the plan whose
    /// step posted `g`, and the plan below goes on after its current step (the `!g`, or
    /// the step that failed, when a failure plan failed at the bottom of the stack).
    fn clear_finished(&self, int: &mut Intention, notes: &mut Vec<Note>) -> bool {
        loop {
            let Some(top) = int.frames.last() else {
                notes.push(Note::Finished(int.origin));
                return false;
            };
            if !top.cursors.is_empty() {
                return true;
            }
            let depth = int.frames.len() - 1;
            let done = int.frames.pop().expect("a top frame");
            let top_literal = &done.trigger.literal;
            let unifies = |t: &Term| crate::model::unifier(t, top_literal).is_some();
            // Whether a frame's current step is `!L` for the goal just finished.
            let calls_top = |f: &Frame| f.calling.as_ref().is_some_and(&unifies);
            let handled_failure =
                done.trigger.kind != TriggerKind::Belief && done.trigger.op == TriggerOp::Del;
            if handled_failure && !int.frames.is_empty() {
                // `im` is the frame just popped; `None` when the top frame, peeked, is the
                // one whose `!g` step posted the goal.
                let top = int.frames.last().expect("a frame");
                let mut im = if calls_top(top) {
                    None
                } else {
                    int.frames.pop()
                };
                while !int.frames.is_empty() {
                    let Some(popped) = im.take() else { break };
                    let goal_frame = popped.trigger.kind != TriggerKind::Belief
                        && unifies(&popped.trigger.literal);
                    if goal_frame || calls_top(&popped) {
                        break;
                    }
                    im = int.frames.pop();
                }
                // The frame now on top goes on after its current step.
                if let Some(parent) = int.frames.last_mut() {
                    parent.calling = None;
                    self.normalize(parent);
                }
                continue;
            }
            if let Some(parent) = int.frames.last_mut() {
                // The subgoal's bindings flow back into the plan that posted it.
                let result = done.subst.apply(&done.trigger.literal).map_vars(&mut |v| {
                    if v.generation() == 0 {
                        Term::from(v.with_generation(1_000_000 + depth as u32))
                    } else {
                        Term::from(v.clone())
                    }
                });
                let asked = done.trigger.literal.map_vars(&mut |v| {
                    if v.generation() == depth as u32 {
                        Term::from(v.with_generation(0))
                    } else {
                        Term::from(v.clone())
                    }
                });
                let mut u = parent.subst.clone();
                if unify(&asked, &result, &mut u) {
                    parent.subst = u;
                }
                parent.calling = None;
                self.normalize(parent);
            }
        }
    }

    /// Executes the next step of the top frame.
    fn step(
        &self,
        s: &mut State,
        int: &mut Intention,
        notes: &mut Vec<Note>,
        env_before: usize,
    ) -> Flow {
        let depth = int.frames.len() - 1;
        // `.drop_intention(g)` may drop the very intention that runs it.
        let drops_itself = |g: &Term| {
            int.frames.iter().any(|f| {
                f.trigger.kind == TriggerKind::Achieve
                    && crate::model::unifier(g, &f.trigger.literal).is_some()
            })
        };
        let own_drop = int.frames.last().and_then(|f| {
            let c = f.cursors.last()?;
            match &self.blocks[f.plan as usize].blocks[c.block as usize]
                .get(c.pos as usize)?
                .kind
            {
                BodyStep::Internal(t)
                    if matches!(t.functor(), Some(".drop_desire" | ".drop_intention")) =>
                {
                    Some(drops_itself(&f.subst.apply(t.args().first()?)))
                }
                _ => None,
            }
        });
        // The stack an environment action runs in (for explanations); other steps need none.
        let acts = int.frames.last().is_some_and(|f| {
            f.cursors.last().is_some_and(|c| {
                matches!(
                    self.blocks[f.plan as usize].blocks[c.block as usize]
                        .get(c.pos as usize)
                        .map(|s| &s.kind),
                    Some(BodyStep::Action(_))
                )
            })
        });
        let views: Vec<FrameView> = if acts {
            int.frames
                .iter()
                .map(|f| FrameView {
                    plan: f.plan,
                    subst: f.subst.clone(),
                    at: f.cursors.last().map_or((0, 0), |c| (c.block, c.pos)),
                })
                .collect()
        } else {
            Vec::new()
        };
        let frame = int.frames.last_mut().expect("an intention has a frame");
        let plan = frame.plan;
        let blocks = &self.blocks[plan as usize];
        let Some(cursor) = frame.cursors.last_mut() else {
            return Flow::Continue;
        };
        let (block, pos) = (cursor.block, cursor.pos);
        let Some(step) = blocks.blocks[block as usize].get(pos as usize) else {
            // The end of a loop's body: testing the loop again is a step of its own, as
            // Jason's `.while`/`.foreach` internal actions run again after the body.
            self.loop_again(frame, s);
            return Flow::Continue;
        };
        cursor.pos += 1;
        let origin = int.origin;
        let fail = |sem: &Self,
                    s: &mut State,
                    int: Intention,
                    text: &str,
                    reason: String,
                    notes: &mut Vec<Note>| {
            let failed = int.frames.last().map(|f| f.trigger.clone()).expect("frame");
            // The `error(Id)` Jason's `createBasicErrorAnnots` gives the failure event.
            let error = match step.kind {
                BodyStep::Test(_) => "test_goal_failed",
                BodyStep::Constraint(..) => "constraint_failed",
                BodyStep::AddBel(_) | BodyStep::DelBel(_) | BodyStep::DelAddBel(_) => {
                    "belief_revision_failed"
                }
                _ => "ia_failed",
            };
            sem.fail_intention(
                s,
                int,
                &failed,
                Some((plan, step.span)),
                &format!("{text}: {reason}"),
                error,
                notes,
            );
            Flow::Gone
        };
        // A step whose arithmetic has no value fails, as Jason's exception fails the plan.
        macro_rules! value {
            ($t:expr) => {
                match eval($t, &frame.subst) {
                    Ok(v) => v,
                    Err(e) => {
                        let text = frame.subst.apply($t).to_string();
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(self, s, int, &text, e.to_string(), notes);
                    }
                }
            };
        }
        match &step.kind {
            BodyStep::Action(t) if self.is_emission(t) => {
                // The agent's own explanation: said, not done; the world does not change.
                let term = value!(t);
                notes.push(Note::Action {
                    text: term.to_string(),
                    term,
                    stack: views,
                    plan,
                    span: step.span,
                    added: Vec::new(),
                    removed: Vec::new(),
                    origin,
                });
                return self.wait_for_feedback(s, int, None);
            }
            BodyStep::Action(t) => {
                let term = value!(t);
                let text = term.to_string();
                // The environment runs the action now; the intention waits for the
                // feedback, which the next cycle's `ProcAct` takes (Jason's pending action).
                let ga = match self.ground_action(&term) {
                    Ok(ga) if !ga.applicable(&s.beliefs) => {
                        Err("its precondition does not hold".to_string())
                    }
                    other => other,
                };
                let ga = match ga {
                    Ok(ga) => ga,
                    Err(reason) => {
                        notes.push(Note::ActionFailed {
                            text,
                            plan,
                            span: step.span,
                            reason: reason.clone(),
                        });
                        let failure = ActionFailure {
                            plan,
                            span: step.span,
                            action: term,
                            why: reason,
                        };
                        return self.wait_for_feedback(s, int, Some(failure));
                    }
                };
                let before = s.beliefs.clone();
                s.beliefs = ga.apply(&before);
                let (mut added, mut removed) = diff(&before, &s.beliefs);
                let after = env_before + added.len() - removed.len();
                self.java_order(&mut removed, env_before);
                self.java_order(&mut added, after);
                self.perceive(s, &added, &removed);
                notes.push(Note::Action {
                    text,
                    term,
                    stack: views,
                    plan,
                    span: step.span,
                    added,
                    removed,
                    origin,
                });
                return self.wait_for_feedback(s, int, None);
            }
            BodyStep::Internal(t) => {
                let term = value!(t);
                let text = term.to_string();
                match term.functor().unwrap_or("") {
                    ".print" | ".println" => {
                        let out: String = term
                            .args()
                            .iter()
                            .map(|a| match a {
                                Term::Str(s) => s.to_string(),
                                Term::Var(_) => format!("{a}<no-value>"),
                                _ => a.to_string(),
                            })
                            .collect();
                        notes.push(Note::Printed(out));
                    }
                    f @ (".succeed_goal" | ".fail_goal") => {
                        let g = term.args().first().cloned().unwrap_or_else(Term::nil);
                        notes.push(Note::Internal { text, plan, origin });
                        self.normalize(frame);
                        let current = std::mem::replace(int, empty_intention(origin));
                        let fail = f == ".fail_goal";
                        self.goal_directive(s, current, &g, fail, (plan, step.span), notes);
                        return Flow::Gone;
                    }
                    ".abolish" => {
                        // `Agent.abolish`: every belief that unifies goes, in belief-base
                        // order, each with its `-b` event.
                        let q = term.args().first().cloned().unwrap_or_else(Term::nil);
                        let gone: Vec<AtomId> = self
                            .beliefs(s)
                            .literal_answers(&q, &Substitution::new())
                            .into_iter()
                            .map(|(a, _)| a)
                            .collect();
                        gone.iter().for_each(|a| s.beliefs.remove(*a));
                        self.perceive(s, &[], &gone);
                        notes.push(Note::Belief {
                            text: text.clone(),
                            plan,
                            added: Vec::new(),
                            removed: gone,
                            origin,
                        });
                    }
                    ".drop_desire" | ".drop_intention" => {
                        let g = term.args().first().cloned().unwrap_or_else(Term::nil);
                        let matches = |i: &Intention| {
                            i.frames.iter().any(|f| {
                                f.trigger.kind == TriggerKind::Achieve
                                    && crate::model::unifier(&g, &f.trigger.literal).is_some()
                            })
                        };
                        s.intentions.retain(|i| !matches(i));
                        s.events.retain(|e| {
                            let goal_matches = e.trigger.kind == TriggerKind::Achieve
                                && crate::model::unifier(&g, &e.trigger.literal).is_some();
                            !(goal_matches || e.intention.as_ref().is_some_and(matches))
                        });
                        if own_drop == Some(true) {
                            notes.push(Note::Internal { text, plan, origin });
                            return Flow::Gone;
                        }
                    }
                    _ => {
                        let f = Formula::Call(t.clone());
                        match self.beliefs(s).answers(&f, &frame.subst).into_iter().next() {
                            Some(a) => frame.subst = a,
                            None => {
                                notes.push(Note::Internal {
                                    text: text.clone(),
                                    plan,
                                    origin,
                                });
                                let int = std::mem::replace(int, empty_intention(origin));
                                return fail(self, s, int, &text, "it has no answer".into(), notes);
                            }
                        }
                    }
                }
                notes.push(Note::Internal { text, plan, origin });
            }
            BodyStep::Achieve { goal, new_focus } => {
                let literal = subgoal_literal(&value!(goal), depth);
                let trigger = EventTrigger {
                    op: TriggerOp::Add,
                    kind: TriggerKind::Achieve,
                    literal,
                };
                if *new_focus {
                    s.events.push(Event {
                        trigger,
                        intention: None,
                        origin: Origin::Spawned,
                        posted_at: Some((plan, step.span)),
                    });
                } else {
                    return self.post_subgoal(s, int, trigger, (plan, step.span));
                }
            }
            BodyStep::Test(f) => {
                match self.beliefs(s).answers(f, &frame.subst).into_iter().next() {
                    Some(a) => frame.subst = a,
                    None => {
                        // Jason's `applyExecInt` (test): with no answer, a literal whose
                        // `+?g` some plan is relevant for becomes that event, as a subgoal.
                        if let Formula::Literal(t) = f {
                            let trigger = EventTrigger {
                                op: TriggerOp::Add,
                                kind: TriggerKind::Test,
                                literal: subgoal_literal(&frame.subst.apply(t), depth),
                            };
                            if !self.relevant_plans(&trigger).is_empty() {
                                return self.post_subgoal(s, int, trigger, (plan, step.span));
                            }
                        }
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(self, s, int, "test goal", "it has no answer".into(), notes);
                    }
                }
            }
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                let lit = value!(t);
                let mut removed = Vec::new();
                let mut added = Vec::new();
                if matches!(step.kind, BodyStep::DelBel(_) | BodyStep::DelAddBel(_)) {
                    // `-b` removes the first belief that unifies; `-+b` the first belief of
                    // the same predicate, whatever its arguments.
                    let pattern = match step.kind {
                        BodyStep::DelAddBel(_) => {
                            let vars = (0..lit.arity())
                                .map(|i| Term::var(&format!("_DelAdd{i}")))
                                .collect();
                            Term::structure(lit.functor().unwrap_or(""), vars)
                        }
                        _ => lit.clone(),
                    };
                    let hits = self.beliefs(s).literal_answers(&pattern, &frame.subst);
                    if let Some((a, answer)) = hits.into_iter().next() {
                        s.beliefs.remove(a);
                        removed.push(a);
                        if matches!(step.kind, BodyStep::DelBel(_)) {
                            frame.subst = answer;
                        }
                    }
                }
                if matches!(step.kind, BodyStep::AddBel(_) | BodyStep::DelAddBel(_)) {
                    match self.ground_atom(&lit) {
                        Some(a) => {
                            if !s.beliefs.contains(a) {
                                s.beliefs.insert(a);
                                added.push(a);
                            }
                            removed.retain(|r| *r != a);
                            added.retain(|x| !removed.contains(x));
                        }
                        None => {
                            let int = std::mem::replace(int, empty_intention(origin));
                            let text = format!("+{lit}");
                            let why = match &self.project.manifest.bounds.numbers {
                                Some(n) => format!(
                                    "the belief is not a ground atom of the model (its numbers are {} to {}, `[bounds] numbers`)",
                                    n.value.0, n.value.1
                                ),
                                None => "the belief is not a ground atom of the model".into(),
                            };
                            return fail(self, s, int, &text, why, notes);
                        }
                    }
                }
                self.perceive(s, &added, &removed);
                let sign = match step.kind {
                    BodyStep::AddBel(_) => "+",
                    BodyStep::DelBel(_) => "-",
                    _ => "-+",
                };
                notes.push(Note::Belief {
                    text: format!("{sign}{lit}"),
                    plan,
                    added,
                    removed,
                    origin,
                });
            }
            BodyStep::Constraint(op, a, b) => {
                let (x, y) = (value!(a), value!(b));
                let text = format!("{x} {} {y}", op.symbol());
                match relation(*op, &x, &y, &frame.subst) {
                    Some(u) => frame.subst = u,
                    None => {
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(
                            self,
                            s,
                            int,
                            &text,
                            "the constraint does not hold".into(),
                            notes,
                        );
                    }
                }
            }
            BodyStep::If { branches, .. } => {
                let kids = &blocks.children[&(block, pos)];
                let b = self.beliefs(s);
                let mut chosen = kids.last().copied();
                for (k, (cond, _)) in branches.iter().enumerate() {
                    if let Some(a) = b.answers(cond, &frame.subst).into_iter().next() {
                        frame.subst = a;
                        chosen = Some(kids[k]);
                        break;
                    }
                }
                if let Some(child) = chosen {
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::Seq,
                    });
                }
            }
            BodyStep::While(cond, _) => {
                let child = blocks.children[&(block, pos)][0];
                let base = frame.subst.clone();
                if let Some(a) = self.beliefs(s).answers(cond, &base).into_iter().next() {
                    frame.subst = a;
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::While {
                            outer: block,
                            at: pos,
                            base,
                        },
                    });
                }
            }
            BodyStep::For(cond, _) => {
                let child = blocks.children[&(block, pos)][0];
                let mut answers = self.beliefs(s).answers(cond, &frame.subst);
                if !answers.is_empty() {
                    let base = std::mem::replace(&mut frame.subst, answers.remove(0));
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::For {
                            rest: answers,
                            base,
                        },
                    });
                }
            }
        }
        self.normalize(frame);
        Flow::Continue
    }

    /// `int` sent an environment action: it waits, its step done (or failed, with why),
    /// for the feedback that the next cycle's `ProcAct` takes.
    fn wait_for_feedback(
        &self,
        s: &mut State,
        int: &mut Intention,
        failure: Option<ActionFailure>,
    ) -> Flow {
        if let Some(top) = int.frames.last_mut() {
            self.normalize(top);
        }
        let origin = int.origin;
        let intention = std::mem::replace(int, empty_intention(origin));
        s.pending = Some(Pending { intention, failure });
        Flow::Gone
    }

    /// Suspends `int` on the subgoal event `trigger` (`!g`, or `?g` handled by a `+?g`
    /// plan): its top plan waits for `g` (its current step), in the event.
    fn post_subgoal(
        &self,
        s: &mut State,
        int: &mut Intention,
        trigger: EventTrigger,
        at: (u32, Span),
    ) -> Flow {
        let origin = int.origin;
        if let Some(top) = int.frames.last_mut() {
            top.calling = Some(trigger.literal.clone());
            self.normalize(top);
        }
        let suspended = std::mem::replace(int, empty_intention(origin));
        s.events.push(Event {
            trigger,
            intention: Some(suspended),
            origin,
            posted_at: Some(at),
        });
        Flow::Suspended
    }

    /// `.succeed_goal(g)` / `.fail_goal(g)` run by `current`, as Jason's
    /// `succeed_goal.drop`: in the events, then in the running intentions, then in the
    /// running one, then in the one waiting for its action, every intention pursuing `g`
    /// drops its plans down to and including `g`'s ([`Semantics::drop_goal_in`]); an event
    /// `+!g` is dropped (succeed: the intention that posted it goes on) or becomes `-!g`
    /// (fail). The running intention then goes on after its current step
    /// (`removeActionReQueue`), which, when its own `g` was dropped, is the `!g` of the plan
    /// below.
    fn goal_directive(
        &self,
        s: &mut State,
        current: Intention,
        g: &Term,
        fail: bool,
        at: (u32, Span),
        notes: &mut Vec<Note>,
    ) {
        let is_goal = |t: &EventTrigger| {
            t.op == TriggerOp::Add
                && t.kind == TriggerKind::Achieve
                && crate::model::unifier(g, &t.literal).is_some()
        };
        for ev in std::mem::take(&mut s.events) {
            if let Some(int) = &ev.intention {
                if int.frames.iter().any(|f| is_goal(&f.trigger)) {
                    let int = ev.intention.expect("checked");
                    if let Some(int) = self.drop_goal_in(s, int, g, fail, false, at, notes) {
                        s.intentions.push(int);
                    }
                    continue;
                }
            }
            if !is_goal(&ev.trigger) {
                s.events.push(ev);
            } else if fail {
                // `fail_goal.dropInEvent`: the event turns into `-!g`, in its place.
                s.events.push(Event {
                    trigger: EventTrigger {
                        op: TriggerOp::Del,
                        ..ev.trigger
                    },
                    ..ev
                });
            } else if let Some(mut int) = ev.intention {
                if let Some(top) = int.frames.last_mut() {
                    top.calling = None;
                    self.normalize(top);
                }
                if self.clear_finished(&mut int, notes) {
                    s.intentions.push(int);
                }
            } else {
                notes.push(Note::Finished(ev.origin));
            }
        }
        for int in std::mem::take(&mut s.intentions) {
            if int.frames.iter().any(|f| is_goal(&f.trigger)) {
                if let Some(int) = self.drop_goal_in(s, int, g, fail, false, at, notes) {
                    s.intentions.push(int);
                }
            } else {
                s.intentions.push(int);
            }
        }
        let mut current = Some(current);
        if let Some(int) = current.take_if(|i| i.frames.iter().any(|f| is_goal(&f.trigger))) {
            current = self.drop_goal_in(s, int, g, fail, true, at, notes);
        }
        if let Some(mut int) = current {
            // `removeActionReQueue`: the step just run is done (for a plan below a dropped
            // goal, that is its `!g`).
            if let Some(top) = int.frames.last_mut() {
                top.calling = None;
                self.normalize(top);
            }
            if self.clear_finished(&mut int, notes) {
                s.intentions.push(int);
            }
        }
        if let Some(p) = s.pending.take() {
            if p.intention.frames.iter().any(|f| is_goal(&f.trigger)) {
                if let Some(int) = self.drop_goal_in(s, p.intention, g, fail, false, at, notes) {
                    s.intentions.push(int);
                }
            } else {
                s.pending = Some(p);
            }
        }
    }

    /// Jason's `dropIntention` of `succeed_goal` and `fail_goal` on an intention pursuing
    /// `g` (`Intention.dropGoal` pops its plans down to and including the lowest plan for
    /// `g`). Succeed: the plan below goes on after its `!g` (for the running intention,
    /// the caller does that); the intention is returned to run on. Fail: the failure event
    /// for `+!g` is looked for from the plan below (`findEventForFailure`); with one, the
    /// intention waits in it (the running one with its current step done, as Jason's
    /// `removeActionReQueue` then removes it); with none, the running intention goes on
    /// and any other is dropped. Returns the intention when it runs on.
    #[allow(clippy::too_many_arguments)]
    fn drop_goal_in(
        &self,
        s: &mut State,
        mut int: Intention,
        g: &Term,
        fail: bool,
        current: bool,
        at: (u32, Span),
        notes: &mut Vec<Note>,
    ) -> Option<Intention> {
        let j = int
            .frames
            .iter()
            .position(|f| {
                f.trigger.op == TriggerOp::Add
                    && f.trigger.kind == TriggerKind::Achieve
                    && crate::model::unifier(g, &f.trigger.literal).is_some()
            })
            .expect("the intention pursues g");
        let dropped = int.frames[j].trigger.clone();
        int.frames.truncate(j);
        if !fail {
            if int.frames.is_empty() {
                notes.push(Note::Finished(int.origin));
                return None;
            }
            if current {
                return Some(int);
            }
            if let Some(top) = int.frames.last_mut() {
                top.calling = None;
                self.normalize(top);
            }
            return self.clear_finished(&mut int, notes).then_some(int);
        }
        let tevent = EventTrigger {
            op: TriggerOp::Add,
            kind: TriggerKind::Achieve,
            literal: g.clone(),
        };
        match self.find_event_for_failure(&int, &tevent) {
            Some(fail) => {
                if current {
                    if let Some(top) = int.frames.last_mut() {
                        top.calling = None;
                        self.normalize(top);
                    }
                }
                let origin = int.origin;
                s.events.push(Event {
                    trigger: fail,
                    intention: Some(int),
                    origin,
                    posted_at: Some(at),
                });
                None
            }
            None if current => Some(int),
            None => {
                let goal = int
                    .frames
                    .first()
                    .map_or(dropped.clone(), |f| f.trigger.clone());
                notes.push(Note::GoalFailed {
                    goal,
                    cause: dropped,
                    plan: Some(at.0),
                    span: Some(at.1),
                    reason: "failed by .fail_goal".into(),
                    origin: int.origin,
                });
                None
            }
        }
    }

    /// The ground action a term names, or why there is none.
    /// Whether the agent explains itself (the manifest names an `emitted_by` action).
    pub fn explains_itself(&self) -> bool {
        self.emitted_by.is_some()
    }

    /// Whether an action is the agent's own explanation (`[explanation] emitted_by`).
    pub fn is_emission(&self, t: &Term) -> bool {
        self.emitted_by.is_some() && t.functor() == self.emitted_by.as_deref()
    }

    fn ground_action(&self, t: &Term) -> Result<&crate::model::ground::GroundAction, String> {
        let name = t.functor().ok_or("it is not an action")?;
        let args = self.objects(t).ok_or("its arguments are not all objects")?;
        self.project.actions.get(name, &args).ok_or_else(|| {
            format!("`{name}` with these arguments is not an action of the PDDL domain")
        })
    }

    fn objects(&self, t: &Term) -> Option<Vec<ObjectId>> {
        t.args()
            .iter()
            .map(|a| self.project.universe.object_of(a))
            .collect()
    }

    /// The atom a ground literal names (annotations ignored).
    fn ground_atom(&self, t: &Term) -> Option<AtomId> {
        let p = self.project.atoms.pred_of_literal(t)?;
        self.project.atoms.id(p, &self.objects(t)?)
    }
}

/// The predicates whose belief order can decide something: those some formula of a plan
/// or rule queries with a variable argument (outside `.count`), and those `-b` or `-+b`
/// removes with a variable argument (the first belief that unifies goes). A predicate
/// asked only with ground arguments has at most one answer, so its order never shows.
fn ordered_predicates(p: &Project) -> Vec<bool> {
    let mut out = vec![false; p.atoms.pred_count()];
    let mark = |t: &Term, out: &mut Vec<bool>| {
        if t.is_ground() {
            return;
        }
        if let Some(q) = p.atoms.pred_of_literal(t) {
            out[q.0 as usize] = true;
        }
    };
    fn formula(f: &Formula, mark: &mut dyn FnMut(&Term)) {
        match f {
            Formula::True | Formula::Rel(..) => {}
            Formula::Literal(t) => mark(t),
            Formula::Not(g) => formula(g, mark),
            Formula::And(a, b) | Formula::Or(a, b) => {
                formula(a, mark);
                formula(b, mark);
            }
            Formula::Call(t) => match (t.functor(), t.args()) {
                (Some(".count"), _) => {}
                (_, args) => args.iter().for_each(|a| {
                    if a.is_literal() {
                        mark(a)
                    }
                }),
            },
        }
    }
    fn steps(body: &[Step], mark: &mut dyn FnMut(&Term)) {
        for st in body {
            match &st.kind {
                BodyStep::Test(f) => formula(f, mark),
                BodyStep::Internal(t) => formula(&Formula::Call(t.clone()), mark),
                BodyStep::DelBel(t) => mark(t),
                BodyStep::DelAddBel(t) => {
                    let vars = (0..t.arity())
                        .map(|i| Term::var(&format!("_V{i}")))
                        .collect();
                    mark(&Term::structure(t.functor().unwrap_or(""), vars));
                }
                BodyStep::If {
                    branches,
                    else_body,
                } => {
                    for (c, b) in branches {
                        formula(c, mark);
                        steps(b, mark);
                    }
                    steps(else_body, mark);
                }
                BodyStep::While(c, b) | BodyStep::For(c, b) => {
                    formula(c, mark);
                    steps(b, mark);
                }
                _ => {}
            }
        }
    }
    let mut m = |t: &Term| mark(t, &mut out);
    for plan in &p.plans.plans {
        formula(&plan.context, &mut m);
        steps(&plan.body, &mut m);
    }
    for r in &p.plans.rules {
        formula(&r.body, &mut m);
    }
    out
}

/// Internal actions that read or change intentions other than the one running them.
const GLOBAL_ACTIONS: [&str; 6] = [
    ".desire",
    ".intend",
    ".succeed_goal",
    ".fail_goal",
    ".drop_desire",
    ".drop_intention",
];

fn formula_is_local(f: &Formula) -> bool {
    match f {
        Formula::True | Formula::Literal(_) | Formula::Rel(..) => true,
        Formula::Not(g) => formula_is_local(g),
        Formula::And(a, b) | Formula::Or(a, b) => formula_is_local(a) && formula_is_local(b),
        Formula::Call(t) => !t.functor().is_some_and(|f| GLOBAL_ACTIONS.contains(&f)),
    }
}

fn step_is_local(s: &Step) -> bool {
    match &s.kind {
        BodyStep::Internal(t) => !t.functor().is_some_and(|f| GLOBAL_ACTIONS.contains(&f)),
        BodyStep::Test(f) => formula_is_local(f),
        BodyStep::If {
            branches,
            else_body,
        } => {
            branches
                .iter()
                .all(|(c, b)| formula_is_local(c) && b.iter().all(step_is_local))
                && else_body.iter().all(step_is_local)
        }
        BodyStep::While(c, b) | BodyStep::For(c, b) => {
            formula_is_local(c) && b.iter().all(step_is_local)
        }
        BodyStep::Action(_)
        | BodyStep::Achieve { .. }
        | BodyStep::AddBel(_)
        | BodyStep::DelBel(_)
        | BodyStep::DelAddBel(_)
        | BodyStep::Constraint(..) => true,
    }
}

/// The literal of a subgoal posted by the plan at `depth` of its stack: Jason's
/// `prepareBodyForEvent` gives it `source(self)`, and its plan's variables are renamed to
/// the next generation (the subgoal's plan has variables of its own).
fn subgoal_literal(t: &Term, depth: usize) -> Term {
    with_source(t, "self").map_vars(&mut |v| {
        if v.generation() == 0 {
            Term::from(v.with_generation(depth as u32 + 1))
        } else {
            Term::from(v.clone())
        }
    })
}

/// The number of buckets of a `java.util.HashSet` after `size` insertions into a new one:
/// 16, doubled whenever it is more than three quarters full (`HashMap.resize`).
fn java_capacity(size: usize) -> u32 {
    let mut cap: u32 = 16;
    while size as u64 > u64::from(cap / 4 * 3) {
        cap *= 2;
    }
    cap
}

/// `t` annotated `source(who)`, unless it names a source already.
fn with_source(t: &Term, who: &str) -> Term {
    let has_source = t.annots().iter().any(|a| a.functor() == Some("source"));
    if has_source {
        return t.clone();
    }
    let annot = Term::structure("source", vec![Term::atom(who)]);
    t.add_annots([annot]).unwrap_or_else(|| t.clone())
}

/// A failure event's trigger with Jason's `error(Id)` and `code_line(Line)` annotations
/// (`setDefaultFailureAnnots`; `error_msg`, `code` and `code_src` are not given). The line
/// matters beyond plans that read it: when a failure plan ends, Jason drops the plans above
/// down to one whose goal unifies with the handled one, annotations included, so two
/// failures at different lines do not unify.
fn with_error(mut t: EventTrigger, error: &str, line: Option<usize>) -> EventTrigger {
    let mut annots = vec![Term::structure("error", vec![Term::atom(error)])];
    if let Some(n) = line {
        annots.push(Term::structure("code_line", vec![Term::int(n as i64)]));
    }
    if let Some(l) = t.literal.add_annots(annots) {
        t.literal = l;
    }
    t
}

/// What became of the intention after a step.
enum Flow {
    /// It goes on (and goes to the back of the queue).
    Continue,
    /// It waits in an event for a subgoal's plan.
    Suspended,
    /// It was dropped or handed to a failure event.
    Gone,
}

fn empty_intention(origin: Origin) -> Intention {
    Intention {
        frames: Vec::new(),
        origin,
    }
}

fn diff(before: &AtomSet, after: &AtomSet) -> (Vec<AtomId>, Vec<AtomId>) {
    let added = after.iter().filter(|a| !before.contains(*a)).collect();
    let removed = before.iter().filter(|a| !after.contains(*a)).collect();
    (added, removed)
}

/// Every ground instance of the manifest's request goals, in manifest order then object
/// order; a variable ranges over its goal parameter's type.
fn ground_requests(p: &Project) -> Result<Vec<Term>, Vec<Diagnostic>> {
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for f in &p.manifest.requests.goals {
        let mut conv = crate::model::Converter::new();
        let term = match &f.expr.kind {
            crate::syntax::ast::ExprKind::Literal(l) => match conv.literal(l) {
                Ok(t) => t,
                Err(e) => {
                    errors.push(Diagnostic::error("input", e.message).with_label(e.span, "here"));
                    continue;
                }
            },
            _ => {
                errors.push(
                    Diagnostic::error("input", "a request must be a goal literal")
                        .with_label(f.span, "here"),
                );
                continue;
            }
        };
        let name = term.functor().unwrap_or("");
        let params: Vec<_> = match p.vocabulary.goal(name, term.arity()) {
            Some((_, g)) => g.params.clone(),
            None => vec![crate::model::TypeId::OBJECT; term.arity()],
        };
        let vars: Vec<(usize, crate::model::TypeId)> = term
            .args()
            .iter()
            .enumerate()
            .filter(|(_, a)| a.is_var())
            .map(|(i, _)| {
                (
                    i,
                    params
                        .get(i)
                        .copied()
                        .unwrap_or(crate::model::TypeId::OBJECT),
                )
            })
            .collect();
        let types: Vec<_> = vars.iter().map(|(_, t)| *t).collect();
        for objs in crate::model::ground::product(&p.universe, &types) {
            let mut args = term.args().to_vec();
            for ((i, _), o) in vars.iter().zip(objs) {
                args[*i] = Term::atom(p.universe.object_name(o));
            }
            let g = Term::structure(name, args);
            if !out.contains(&g) {
                out.push(g);
            }
        }
    }
    if out.len() > MAX_REQUESTS {
        errors.push(
            Diagnostic::error(
                "input",
                format!(
                    "the requests have {} ground instances; at most {MAX_REQUESTS} are supported",
                    out.len()
                ),
            )
            .in_file(p.manifest.path.display().to_string()),
        );
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}
