//! Counterexample runs rebuilt from the explored graph.
//!
//! The graph keeps fingerprints and parent links only; the steps of a run are recovered by
//! re-executing each transition on the path and keeping the first one that leads to the
//! next state (matched by fingerprint), as stateright rebuilds paths. Under symmetry the
//! fingerprints are those of canonical members, and the rebuilt run is a concrete run of
//! the agent that reaches a renaming of the stored state; a loop is followed until the
//! concrete state comes back, so a lasso is a real lasso.

use super::explore::{fingerprint, Graph, Walk};
use super::model::Agent;
use crate::findings::{
    Counterexample, IntentionView, MeansView, StateView, StepKindTag, TraceStep,
};
use crate::model::atoms::AtomId;
use crate::model::project::Project;
use crate::semantics::{Intention, Note, Origin, Semantics, State};
use std::collections::HashMap;

/// The last transition of a run: from state `src`, the `k`-th transition as exploration
/// numbered it, to a state with fingerprint `fp`, whose notes satisfy `want`.
pub struct Extra<'w> {
    /// The source state.
    pub src: u32,
    /// Its position among the source's transitions during exploration.
    pub k: u32,
    /// The target's fingerprint.
    pub fp: u64,
    /// What the transition must show.
    pub want: &'w dyn Fn(&Vec<Note>) -> bool,
}

/// Most rounds a loop is followed before it closes: a renaming applied over and over
/// comes back to the identity after at most this many rounds for the group sizes symmetry
/// reduction handles (the order of a permutation of `n` objects is small).
const MAX_LOOP_ROUNDS: usize = 720;

/// A run's builder, a walk in its initial state `path[0]` and the atoms true there; `None`
/// when no initial state has the stored fingerprint.
fn start<'a>(
    project: &'a Project,
    agent: &'a Agent,
    graph: &'a Graph,
    path: &[u32],
) -> Option<(Builder<'a>, Walk<'a, Agent<'a>>, Vec<String>)> {
    let walk = Walk::start(agent, graph, path.first().copied().unwrap_or(0))?;
    let initial = walk
        .state
        .beliefs
        .iter()
        .map(|a| project.atoms.display(a, &project.universe))
        .collect();
    Some((Builder::new(project, agent.sem), walk, initial))
}

/// The run along `path` (state indices from an initial state), then the transition
/// `extra` if given, then the loop `cycle` (state indices from the loop's entry back to it)
/// if given.
pub fn counterexample(
    project: &Project,
    agent: &Agent,
    graph: &Graph,
    path: &[u32],
    extra: Option<Extra>,
    cycle: &[u32],
) -> Counterexample {
    let Some((mut b, mut walk, initial)) = start(project, agent, graph, path) else {
        return Counterexample::default();
    };
    for &j in &path[1..] {
        b.push(walk.step_to(j).unwrap_or_default());
    }
    if let Some(x) = extra {
        b.push(walk.step_by(x.k, x.fp, x.want).unwrap_or_default());
    }
    let mut loop_start = None;
    if cycle.len() >= 2 {
        loop_start = Some(b.steps.len());
        let entry = fingerprint(&walk.state);
        for _ in 0..MAX_LOOP_ROUNDS {
            for &j in &cycle[1..] {
                b.push(walk.step_to(j).unwrap_or_default());
            }
            if fingerprint(&walk.state) == entry {
                break;
            }
        }
    }
    Counterexample {
        initial,
        requests: b.requests,
        steps: b.steps,
        loop_start,
    }
}

/// The run from the initial state `path[0]` that takes, to each next state of `path`, the
/// transition at position `path_via[s]` among those exploration numbered (several may lead
/// to one state and do different things), then likewise the loop `cycle` (from its entry
/// back to it) if not empty. Each transition taken satisfies `want` (given the stored
/// source, the position and the notes): under symmetry the concrete state's transitions
/// may come in another order, and `want` tells the one the search took. Under symmetry the
/// loop is followed until the concrete state comes back, so the lasso is a real lasso.
pub fn counterexample_via(
    project: &Project,
    agent: &Agent,
    graph: &Graph,
    (path, path_via): (&[u32], &[u32]),
    (cycle, cycle_via): (&[u32], &[u32]),
    want: &dyn Fn(u32, u32, &Vec<Note>) -> bool,
) -> (Counterexample, usize) {
    let Some((mut b, mut walk, initial)) = start(project, agent, graph, path) else {
        return (Counterexample::default(), 1);
    };
    for (s, (&j, &k)) in path[1..].iter().zip(path_via).enumerate() {
        let fp = graph.fingerprint(j);
        b.push(
            walk.step_by(k, fp, |n| want(path[s], k, n))
                .unwrap_or_default(),
        );
    }
    let mut loop_start = None;
    let mut rounds = 1;
    if cycle.len() >= 2 {
        loop_start = Some(b.steps.len());
        let entry = fingerprint(&walk.state);
        for round in 1..=MAX_LOOP_ROUNDS {
            rounds = round;
            for (s, (&j, &k)) in cycle[1..].iter().zip(cycle_via).enumerate() {
                let fp = graph.fingerprint(j);
                b.push(
                    walk.step_by(k, fp, |n| want(cycle[s], k, n))
                        .unwrap_or_default(),
                );
            }
            if fingerprint(&walk.state) == entry {
                break;
            }
        }
    }
    let cx = Counterexample {
        initial,
        requests: b.requests,
        steps: b.steps,
        loop_start,
    };
    (cx, rounds)
}

/// Renders the notes of consecutive transitions as trace steps, numbering intentions in
/// order of appearance.
pub struct Builder<'a> {
    project: &'a Project,
    sem: &'a Semantics<'a>,
    intentions: HashMap<Origin, usize>,
    steps: Vec<TraceStep>,
    requests: Vec<String>,
}

impl<'a> Builder<'a> {
    /// A builder for runs of `sem`.
    pub fn new(project: &'a Project, sem: &'a Semantics<'a>) -> Builder<'a> {
        Builder {
            project,
            sem,
            intentions: HashMap::new(),
            steps: Vec::new(),
            requests: Vec::new(),
        }
    }

    /// The steps rendered so far.
    pub fn steps(&self) -> &[TraceStep] {
        &self.steps
    }

    /// The requests made so far, in order.
    pub fn requests(&self) -> &[String] {
        &self.requests
    }

    fn intention(&mut self, o: Origin) -> usize {
        let next = self.intentions.len() + 1;
        *self.intentions.entry(o).or_insert(next)
    }

    fn plan_place(&self, plan: u32) -> String {
        let p = self.sem.plan(plan);
        let loc = self.project.map.location(p.span);
        if self.sem.is_kqml_plan(plan) {
            // Not a file of the project: Jason's own plans for messages.
            return format!("Jason's {}", loc.file);
        }
        format!("{}:{}", loc.file, loc.line)
    }

    fn atoms(&self, atoms: &[AtomId]) -> Vec<String> {
        atoms
            .iter()
            .map(|a| self.project.atoms.display(*a, &self.project.universe))
            .collect()
    }

    fn step(
        &mut self,
        kind: StepKindTag,
        text: String,
        intention: Option<usize>,
        plan: Option<String>,
    ) -> TraceStep {
        TraceStep {
            kind,
            text,
            intention,
            plan,
            added: Vec::new(),
            removed: Vec::new(),
            explanation: None,
            agent: None,
        }
    }

    /// A step of a plan that changed beliefs.
    fn change(
        &mut self,
        kind: StepKindTag,
        text: String,
        plan: u32,
        origin: Origin,
        added: &[AtomId],
        removed: &[AtomId],
    ) -> TraceStep {
        let i = self.intention(origin);
        let place = self.plan_place(plan);
        let mut s = self.step(kind, text, Some(i), Some(place));
        s.added = self.atoms(added);
        s.removed = self.atoms(removed);
        s
    }

    /// The whole state `s`, its intentions (held by an event, running, awaiting feedback,
    /// waiting) numbered as the steps so far number them (an
    /// intention not seen in a step yet takes the next number).
    pub fn state_view(&mut self, s: &State) -> StateView {
        let events = s
            .events
            .iter()
            .map(|e| match &e.intention {
                Some(i) => format!("{} (intention {})", e.trigger, self.intention(i.origin)),
                None => e.trigger.to_string(),
            })
            .collect();
        let mut intentions: Vec<IntentionView> = Vec::new();
        // An intention that posted a subgoal is held by the event until a plan is chosen.
        for e in &s.events {
            if let Some(i) = &e.intention {
                intentions.push(self.intention_view(i, "held by its event", None));
            }
        }
        for i in &s.intentions {
            intentions.push(self.intention_view(i, "running", None));
        }
        if let Some(p) = &s.pending {
            intentions.push(self.intention_view(&p.intention, "awaiting feedback", None));
        }
        for w in &s.waiting {
            let how = if w.ask.is_some() {
                "waiting for an answer"
            } else {
                "waiting"
            };
            intentions.push(self.intention_view(&w.intention, how, Some(w.step.3)));
        }
        StateView {
            beliefs: s
                .beliefs
                .iter()
                .map(|a| self.project.atoms.display(a, &self.project.universe))
                .collect(),
            events,
            intentions,
            expected: Vec::new(),
        }
    }

    /// One intention, top frame first; `at` is the step it is suspended at, if any.
    fn intention_view(
        &mut self,
        i: &Intention,
        status: &'static str,
        at: Option<crate::syntax::Span>,
    ) -> IntentionView {
        let text = |span| self.project.map.slice(span).trim().to_string();
        let top = i.frames.len().saturating_sub(1);
        let frames = i
            .frames
            .iter()
            .enumerate()
            .rev()
            .map(|(k, f)| {
                let next = match (&f.calling, at) {
                    (_, Some(span)) if k == top => Some(text(span)),
                    (Some(g), _) => Some(format!("!{g}")),
                    _ => self.sem.next_step(f).map(text),
                };
                MeansView {
                    trigger: f.trigger.to_string(),
                    plan: self.plan_place(f.plan),
                    bindings: f
                        .subst
                        .iter()
                        .map(|(v, _)| format!("{v} = {}", f.subst.resolve(v)))
                        .collect(),
                    next,
                }
            })
            .collect();
        IntentionView {
            intention: self.intention(i.origin),
            status,
            frames,
        }
    }

    /// Appends the steps of one transition.
    pub fn push(&mut self, notes: Vec<Note>) {
        for n in notes {
            let step = match n {
                Note::Request { index } => {
                    let goal = format!("{}", self.sem.requests[index as usize]);
                    self.requests.push(goal.clone());
                    let i = self.intention(Origin::Request(index));
                    self.step(StepKindTag::Request, format!("!{goal}"), Some(i), None)
                }
                Note::Event(t) => self.step(StepKindTag::Event, t.to_string(), None, None),
                Note::Plan { plan, origin, .. } => {
                    let i = self.intention(origin);
                    let p = self.sem.plan(plan);
                    let place = self.plan_place(plan);
                    self.step(StepKindTag::Plan, p.name(), Some(i), Some(place))
                }
                Note::Action {
                    text,
                    plan,
                    added,
                    removed,
                    origin,
                    ..
                } => self.change(StepKindTag::Action, text, plan, origin, &added, &removed),
                Note::Belief {
                    text,
                    plan,
                    added,
                    removed,
                    origin,
                } => self.change(StepKindTag::Belief, text, plan, origin, &added, &removed),
                Note::Internal { text, plan, origin } => {
                    let i = self.intention(origin);
                    let place = self.plan_place(plan);
                    self.step(StepKindTag::Internal, text, Some(i), Some(place))
                }
                Note::ActionFailed {
                    text, plan, reason, ..
                } => {
                    let place = self.plan_place(plan);
                    self.step(
                        StepKindTag::Action,
                        format!("{text} fails: {reason}"),
                        None,
                        Some(place),
                    )
                }
                Note::GoalFailed {
                    goal,
                    cause,
                    reason,
                    origin,
                    plan,
                    ..
                } => {
                    let i = self.intention(origin);
                    let place = plan.map(|p| self.plan_place(p));
                    let text = if goal == cause {
                        format!("goal {goal} fails: {reason}; the intention is dropped")
                    } else {
                        format!("{cause} fails: {reason}; goal {goal} fails and the intention is dropped")
                    };
                    self.step(StepKindTag::Event, text, Some(i), place)
                }
                Note::Beyond {
                    text, plan, reason, ..
                } => {
                    let place = self.plan_place(plan);
                    self.step(
                        StepKindTag::Belief,
                        format!("{text} leaves the model: {reason}"),
                        None,
                        Some(place),
                    )
                }
                // Among several agents: the message the agent reads in its sense.
                Note::Received {
                    from,
                    performative,
                    content,
                } => {
                    let sender = &self.sem.agent_names()[from as usize];
                    self.step(
                        StepKindTag::Event,
                        format!("message from {sender}: {} {content}", performative.name()),
                        None,
                        None,
                    )
                }
                Note::Finished(_)
                | Note::NoApplicablePlan(_)
                | Note::Printed(_)
                | Note::Sent { .. }
                | Note::Perceived { .. } => continue,
            };
            self.steps.push(step);
        }
    }
}
