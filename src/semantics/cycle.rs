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
//!    subgoal made flow back into the plan that posted it. (An intention with an `[atomic]`
//!    plan runs alone instead: see `atomic.rs`.)
//!
//! Environment actions run when their PDDL precondition holds; their effects are perceived
//! at once as `+p`/`-p` events. Events that no plan is relevant for are not queued at all:
//! Jason would queue and then discard them, which only costs cycles. A failing step (an
//! action whose precondition fails, a test goal with no answer, a subgoal with no applicable
//! plan) fails the plan as Jason does: the first goal on the intention stack, from the top,
//! with a relevant `-!g` plan gets a `-!g` event, and the frames above it go; with no such
//! goal the intention is dropped and the failure is reported.
//!
//! This file holds the [`Semantics`] type, its construction, the initial states, the
//! requests and the driver ([`Semantics::successors`]: one reasoning cycle's phases in
//! Jason's order). Each phase has a file of its own beside it, laid out as Jason's
//! `TransitionSystem.java`: `perceive.rs` (perception and belief updates), `deliberate.rs`
//! (`applySelEv` to `applyAddIM`), `execute.rs` (`applyProcAct`, `applySelInt`,
//! `applyExecInt`), `failure.rs` (`generateGoalDeletion`, `applyClrInt`),
//! `internal_actions.rs` (`.succeed_goal`/`.fail_goal`), and `atomic.rs` for the atomic
//! intention and event that decide which event and which intention a cycle takes
//! (`Circumstance.AI`, `AE`); `reads.rs` says what each phase may read, for the compiled
//! search.

use super::java_hash::{literal_hash, negated_literal_hash, JArg};
use super::query::Beliefs;
use super::reads::{formula_is_local, ordered_predicates, step_is_local};
use super::state::{Event, EventTrigger, Origin, State};
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::plans::{BodyStep, Step};
use crate::model::project::Project;
use crate::model::term::Term;
use crate::model::Substitution;
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
    /// `.send` or `.broadcast`: the message goes to the mailboxes of these agents
    /// (indices in [`super::System`]).
    Sent {
        /// The receivers.
        to: Vec<u8>,
        /// The performative.
        performative: Performative,
        /// The goal, belief or query, as written in the message.
        content: Term,
        /// For an ask whose answer the intention waits for: its id (`samidN`).
        ask: Option<u8>,
        /// For an answer to such an ask: the ask's id (the `.send`'s fourth argument).
        reply_to: Option<u8>,
    },
    /// Among several agents: what the agent perceived at the start of its cycle (the
    /// environment changed since its last sense).
    Perceived {
        /// Atoms it now believes.
        added: Vec<AtomId>,
        /// Atoms it no longer believes.
        removed: Vec<AtomId>,
    },
    /// Among several agents: the message the agent read at the start of its cycle.
    Received {
        /// The sender's index.
        from: u8,
        /// The performative.
        performative: Performative,
        /// The goal or belief.
        content: Term,
    },
    /// An intention ended successfully.
    Finished(Origin),
    /// A goal event had no applicable plan (whether or not a failure plan then handles it).
    NoApplicablePlan(EventTrigger),
    /// The step needs what the finite model does not have (a mental note with a number
    /// outside `[bounds] numbers`, or with a free variable): the run leaves the model here,
    /// and the search does not follow it (it is incomplete, never failed).
    Beyond {
        /// The step, as it would run.
        text: String,
        /// The plan.
        plan: u32,
        /// The step.
        span: Span,
        /// What the model lacks.
        reason: String,
    },
    /// What `.print`/`.println` printed (stdlib `println.argsToString`: strings without
    /// quotes, other terms as Jason writes them, unbound variables as `X<no-value>`).
    Printed(String),
}

/// The KQML performatives bdi-check delivers (the others are refused where written).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Performative {
    /// `achieve g`: the receiver gets the external event `+!g[source(sender)]`.
    Achieve,
    /// `tell b`: the receiver believes `b[source(sender)]`.
    Tell,
    /// `untell b`: the sender is no longer a source of the receiver's `b`.
    Untell,
    /// `unachieve g`: the receiver drops the desire `g`.
    Unachieve,
    /// `askOne q`: the receiver answers with the first belief that unifies (`tell`), or
    /// `untell` when it has none and no `+?q` plan finds one.
    AskOne,
    /// `askAll q`: the receiver answers with the list of every belief that unifies.
    AskAll,
    /// `tellHow p`: the receiver adds the plans, with the sender as their source.
    TellHow,
    /// `untellHow l`: the sender is no longer a source of the receiver's plans labelled so.
    UntellHow,
    /// `askHow t`: the receiver tells back its plans relevant for the trigger.
    AskHow,
}

impl Performative {
    /// Every performative bdi-check delivers.
    pub const ALL: [Performative; 9] = [
        Performative::Achieve,
        Performative::Tell,
        Performative::Untell,
        Performative::Unachieve,
        Performative::AskOne,
        Performative::AskAll,
        Performative::TellHow,
        Performative::UntellHow,
        Performative::AskHow,
    ];

    /// Its name, as a `.send` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Performative::Achieve => "achieve",
            Performative::Tell => "tell",
            Performative::Untell => "untell",
            Performative::Unachieve => "unachieve",
            Performative::AskOne => "askOne",
            Performative::AskAll => "askAll",
            Performative::TellHow => "tellHow",
            Performative::UntellHow => "untellHow",
            Performative::AskHow => "askHow",
        }
    }

    /// The performative a `.send` names, if bdi-check delivers it.
    pub fn named(name: &str) -> Option<Performative> {
        Performative::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Whether it asks for an answer.
    pub fn is_ask(self) -> bool {
        matches!(self, Performative::AskOne | Performative::AskAll)
    }
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
pub(super) struct Blocks<'p> {
    pub(super) blocks: Vec<&'p [Step]>,
    /// For the compound step at (block, pos): its child blocks (if: one per branch, then
    /// else; while/for: one).
    pub(super) children: HashMap<(u16, u16), Vec<u16>>,
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
    pub(super) blocks: Vec<Blocks<'p>>,
    /// Per trigger signature: every plan that may be relevant, in index order (the agent's
    /// own in source order, then those steps may add).
    pub(super) relevant: HashMap<(u8, u8, String, usize), Vec<u32>>,
    /// How many plans are the agent's own (the library a run starts with).
    pub(super) own_plans: usize,
    max_requests: u32,
    arrival_any: bool,
    pub(super) select_any: bool,
    /// `[explanation] emitted_by`: the agent's own explanation action.
    pub(super) emitted_by: Option<String>,
    /// No plan reads or changes other intentions (see [`Semantics::is_local`]).
    pub(super) local: bool,
    /// Per rule head (functor, arity): every atom proving it may read.
    pub(super) rule_reads: HashMap<(String, usize), AtomSet>,
    /// The agent's name ([`Project::name`]).
    pub(super) agent_name: String,
    /// Every agent of the system, by index (this one alone, outside a [`super::System`]).
    pub(super) agents: Vec<String>,
    /// This agent's index in `agents`.
    pub(super) me: u8,
    /// Whether the environment is shared with other agents: an action's effects are then
    /// perceived at the agent's next sense, not queued when it acts.
    pub(super) shared_world: bool,
    /// Per predicate: whether the order of its beliefs can decide an answer (some query
    /// asks it with a variable, or `-b`/`-+b` removes the first of several).
    pub(super) ordered: Vec<bool>,
    /// Per atom: the `hashCode()` of the literal Jason builds for it, which places it in
    /// `Agent.buf`'s set of percepts.
    pub(super) jhash: Vec<i32>,
    /// The environment's atoms.
    pub(super) env_atoms: AtomSet,
    /// The most environment atoms one action changes.
    pub(super) max_effect: usize,
}

pub(super) fn op_key(op: TriggerOp) -> u8 {
    match op {
        TriggerOp::Add => 0,
        TriggerOp::Del => 1,
        TriggerOp::GoalState => 2,
    }
}

pub(super) fn kind_key(k: TriggerKind) -> u8 {
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
        // The agent's plans, then Jason's for messages (`Agent.loadKqmlPlans` puts them at
        // the end of the library).
        let kqml = crate::model::kqml::plans();
        for (i, plan) in project.plans.plans.iter().chain(kqml).enumerate() {
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
                .push(i as u32);
        }
        let requests = ground_requests(project)?;
        let m = &project.manifest;
        let mut sem = Semantics {
            project,
            requests,
            environment,
            blocks,
            relevant,
            own_plans: project
                .plans
                .changes
                .as_ref()
                .map_or(project.plans.plans.len(), |c| c.initial),
            max_requests: m.requests.max,
            arrival_any: m.requests.arrival == Arrival::Any,
            select_any: m.bounds.plan_selection == PlanSelection::Any,
            emitted_by: m
                .explanation
                .as_ref()
                .and_then(|e| e.emitted_by.as_ref())
                .map(|e| e.value.clone()),
            // A library that changes makes deliberation depend on more than the event; an
            // atomic plan makes every phase depend on where the atomic intention is.
            local: project.plans.changes.is_none()
                && project.plans.plans.iter().all(|p| {
                    !p.atomic && formula_is_local(&p.context) && p.body.iter().all(step_is_local)
                }),
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
            agent_name: project.name.clone(),
            agents: vec![project.name.clone()],
            me: 0,
            shared_world: false,
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
            sem.jhash.push(match atoms.pred_literal(p) {
                (name, true) => negated_literal_hash(name, &jargs),
                (name, false) => literal_hash(name, &jargs),
            });
            if sem.environment[p.0 as usize] {
                sem.env_atoms.insert(a);
            }
        }
        Ok(sem)
    }

    /// Whether a request may arrive in a state with these requests made and this idleness.
    /// Whether a request may still come in a run that has made `requested`.
    pub fn requests_remain(&self, requested: u64) -> bool {
        requested.count_ones() < self.max_requests
    }

    /// The environment's atoms, which the agent perceives.
    pub fn env_atoms(&self) -> &AtomSet {
        &self.env_atoms
    }

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

    /// [`Semantics::beliefs`] for a step of an intention out of `state`, whose goals are
    /// `running`.
    pub(super) fn beliefs_running<'s>(
        &'s self,
        state: &'s State,
        running: &'s [Term],
    ) -> Beliefs<'s> {
        Beliefs {
            running,
            ..self.beliefs(state)
        }
    }

    /// The query view of `state`.
    pub(super) fn beliefs<'s>(&'s self, state: &'s State) -> Beliefs<'s> {
        Beliefs {
            atoms: &self.project.atoms,
            universe: &self.project.universe,
            environment: &self.environment,
            state,
            selected: None,
            running: &[],
            rules: &self.project.plans.rules,
            depth: std::cell::Cell::new(0),
            agent_name: &self.agent_name,
            agents: &self.agents,
            ordered: &self.ordered,
        }
    }

    /// The initial states of the transition system: one per initial state of the project,
    /// with the agent's initial goals and the perception of every initial percept queued.
    pub fn initial_states(&self) -> Vec<State> {
        self.project
            .initial
            .states()
            .iter()
            .map(|b| self.initial_state(b))
            .collect()
    }

    /// [`Semantics::initial_states`] made one at a time, as a search takes them (from
    /// [`crate::model::project::InitialStates::iter`]: with no bound on how many).
    pub fn initial_iter(&self) -> impl Iterator<Item = State> + '_ {
        self.project.initial.iter().map(|b| self.initial_state(&b))
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
            waiting: Vec::new(),
            requested: 0,
            library: None,
            told: Vec::new(),
            asked: 0,
            atomic: false,
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

    /// Plan `plan`: one of the project's, or after them one of Jason's plans for messages
    /// ([`crate::model::kqml`]).
    pub fn plan(&self, plan: u32) -> &'p crate::model::plans::Plan {
        let own = &self.project.plans.plans;
        match own.get(plan as usize) {
            Some(p) => p,
            None => &crate::model::kqml::plans()[plan as usize - own.len()],
        }
    }

    /// The names of the agents of its system, by index (this one alone, outside one).
    pub fn agent_names(&self) -> &[String] {
        &self.agents
    }

    /// Whether plan `plan` is one of Jason's plans for messages, not the agent's own.
    pub fn is_kqml_plan(&self, plan: u32) -> bool {
        plan as usize >= self.project.plans.plans.len()
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

    /// Every successor of `state`.
    pub fn successors(&self, state: &State) -> Vec<Transition> {
        let mut out = Vec::new();
        if self.may_request(state.requested, state.is_idle()) {
            for r in 0..self.requests.len() {
                if state.requested >> r & 1 == 1 {
                    continue;
                }
                let mut next = state.clone();
                self.post_request(&mut next, r);
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

    /// Makes request `r`: its event is queued.
    pub fn post_request(&self, s: &mut State, r: usize) {
        s.requested |= 1 << r;
        self.post_event(s, self.request_event(r));
    }

    /// One reasoning cycle: the intentions whose `.wait` ended resume (for an agent that
    /// waits, one branch per choice of timers fired before the cycle), then deliberate on
    /// the first event, then act on the first intention.
    pub(super) fn cycle(&self, state: &State) -> Vec<Transition> {
        self.cycle_sensed(state, false)
    }

    /// [`Semantics::cycle`] of an agent that has just perceived something or read a
    /// message (`sensed`, among several agents): that is a step even for an agent whose
    /// atomic intention sleeps in `.wait` ([`Semantics::atomic_sleeps`]) when no timer
    /// fires.
    pub(super) fn cycle_sensed(&self, state: &State, sensed: bool) -> Vec<Transition> {
        if state.waiting.is_empty() {
            return self.cycle_from(state.clone(), Vec::new());
        }
        let mut out = Vec::new();
        for fired in self.timer_choices(state, sensed) {
            let mut s = state.clone();
            let mut notes = Vec::new();
            self.resume_waiting(&mut s, &fired, &mut notes);
            out.extend(self.cycle_from(s, notes));
        }
        out
    }

    /// The deliberation and act phases of a cycle, after the notes `before`.
    fn cycle_from(&self, state: State, before: Vec<Note>) -> Vec<Transition> {
        let mut options: Vec<(State, Vec<Note>)> = Vec::new();
        // `applySelEv`: no event is selected while there is an atomic intention.
        if state.events.is_empty() || self.has_atomic_intention(&state) {
            options.push((state, before));
        } else {
            let mut s = state;
            let ev = s.events.remove(0);
            options = self.deliberate(s, ev);
            if !before.is_empty() {
                for (_, notes) in &mut options {
                    notes.splice(0..0, before.iter().cloned());
                }
            }
        }
        let mut out = Vec::new();
        for (mut s, mut notes) in options {
            self.proc_act(&mut s, &mut notes);
            // One successor per outcome of the step (several for `.random` only).
            let n = self.act_choices(&s);
            let mut last = Some((s, notes));
            for choice in 0..n {
                let (mut s, mut notes) = match &last {
                    Some((s, notes)) if choice + 1 < n => (s.clone(), notes.clone()),
                    _ => last.take().expect("the last outcome"),
                };
                self.act(&mut s, &mut notes, choice);
                out.push(Transition { notes, next: s });
            }
        }
        out
    }
}

/// `t` annotated `source(who)`, unless it names a source already.
pub(super) fn with_source(t: &Term, who: &str) -> Term {
    let has_source = t.annots().iter().any(|a| a.functor() == Some("source"));
    if has_source {
        return t.clone();
    }
    let annot = Term::structure("source", vec![Term::atom(who)]);
    t.add_annots([annot]).unwrap_or_else(|| t.clone())
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
