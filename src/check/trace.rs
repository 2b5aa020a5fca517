//! Counterexample runs rebuilt from the explored graph.
//!
//! The graph keeps states and parent links only; the steps of a run are recovered by
//! re-executing each transition on the path and keeping the one that leads to the next
//! state (matched by fingerprint), as stateright rebuilds paths.

use super::explore::{fingerprint, Graph};
use crate::model::atoms::AtomId;
use crate::model::project::Project;
use crate::report::{Counterexample, StepKindTag, TraceStep};
use crate::semantics::{Note, Origin, Semantics};
use std::collections::HashMap;

/// The run along `path` (state indices from an initial state), then the transition
/// `extra` (source state, transition index) if given, then the loop `cycle` (state
/// indices from the loop's entry back to it) if given.
pub fn counterexample(
    project: &Project,
    sem: &Semantics,
    graph: &Graph,
    path: &[u32],
    extra: Option<(u32, u32)>,
    cycle: &[u32],
) -> Counterexample {
    let show = |a: &AtomId| project.atoms.display(*a, &project.universe);
    let mut b = Builder::new(project, sem);
    let notes_between = |a: u32, target: u32| -> Vec<Note> {
        let want = fingerprint(&graph.states[target as usize]);
        sem.successors(&graph.states[a as usize])
            .into_iter()
            .find(|t| fingerprint(&t.next) == want)
            .map(|t| t.notes)
            .unwrap_or_default()
    };
    for w in path.windows(2) {
        b.push(notes_between(w[0], w[1]));
    }
    if let Some((src, k)) = extra {
        if let Some(t) = sem
            .successors(&graph.states[src as usize])
            .into_iter()
            .nth(k as usize)
        {
            b.push(t.notes);
        }
    }
    let mut loop_start = None;
    if cycle.len() >= 2 {
        loop_start = Some(b.steps.len());
        for w in cycle.windows(2) {
            b.push(notes_between(w[0], w[1]));
        }
    }
    let first = path.first().copied().unwrap_or(0) as usize;
    Counterexample {
        initial: graph.states[first]
            .beliefs
            .iter()
            .map(|a| show(&a))
            .collect(),
        requests: b.requests,
        steps: b.steps,
        loop_start,
    }
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

    fn intention(&mut self, o: Origin) -> usize {
        let next = self.intentions.len() + 1;
        *self.intentions.entry(o).or_insert(next)
    }

    fn plan_place(&self, plan: u32) -> String {
        let p = &self.project.plans.plans[plan as usize];
        let loc = self.project.map.location(p.span);
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
                Note::Plan { plan, origin } => {
                    let i = self.intention(origin);
                    let p = &self.project.plans.plans[plan as usize];
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
                Note::Finished(_) | Note::NoApplicablePlan(_) => continue,
            };
            self.steps.push(step);
        }
    }
}
