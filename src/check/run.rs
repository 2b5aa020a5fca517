//! One run of a scenario, as a user (or a recorded run of real Jason) would make it: from
//! one initial state, the requests made one after another, each when the agent is idle,
//! and otherwise one reasoning cycle after another, until the agent is idle with no
//! request left or a bound on the cycles is reached.

use crate::model::atoms::{AtomId, AtomSet};
use crate::model::project::Project;
use crate::model::Converter;
use crate::semantics::{Note, Semantics, State};
use crate::syntax::ast::{Expr, ExprKind};
use crate::syntax::manifest::Scenario;
use crate::syntax::Diagnostic;

/// A scenario's initial state and its requests (indices into [`Semantics::requests`]),
/// or why they are not of this project.
pub fn resolve_scenario(
    p: &Project,
    sem: &Semantics,
    sc: &Scenario,
) -> Result<(AtomSet, Vec<u8>), Vec<Diagnostic>> {
    let mut errors = Vec::new();
    let mut beliefs = AtomSet::empty(p.atoms.len());
    // The agent's own initial beliefs hold in every run, whatever the scenario says of
    // the environment.
    p.initial
        .agent_beliefs
        .iter()
        .for_each(|a| beliefs.insert(*a));
    for f in &sc.initial {
        match ground(p, &f.expr) {
            Some(a) => beliefs.insert(a),
            None => errors.push(
                Diagnostic::error(
                    "input",
                    format!("`{}` is not a ground atom of this project", f.text),
                )
                .with_label(f.span, "unknown atom"),
            ),
        }
    }
    let mut requests = Vec::new();
    for f in &sc.requests {
        let term = match &f.expr.kind {
            ExprKind::Literal(l) => Converter::new().literal(l).ok(),
            _ => None,
        };
        match term.as_ref().and_then(|t| sem.request_index(t)) {
            Some(i) => requests.push(i),
            None => errors.push(
                Diagnostic::error(
                    "input",
                    format!("`{}` is not a request the manifest allows", f.text),
                )
                .with_label(f.span, "not in `[requests] goals`"),
            ),
        }
    }
    if errors.is_empty() {
        Ok((beliefs, requests))
    } else {
        Err(errors)
    }
}

/// The ground atom a scenario's literal names.
fn ground(p: &Project, e: &Expr) -> Option<AtomId> {
    let ExprKind::Literal(l) = &e.kind else {
        return None;
    };
    let pred = p.atoms.pred_lit(&l.functor, l.negated)?;
    let args = l
        .args
        .iter()
        .map(|a| match &a.kind {
            ExprKind::Literal(o) if o.args.is_empty() => p.universe.object(&o.functor),
            _ => None,
        })
        .collect::<Option<Vec<_>>>()?;
    p.atoms.id(pred, &args)
}

/// How a scenario run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunEnd {
    /// The agent is idle and every request was made.
    Done,
    /// The cycle bound was reached first.
    Bound,
    /// A request could not be made (the manifest does not allow it in this state).
    Refused,
    /// The run left the finite model ([`Note::Beyond`]).
    Beyond,
}

/// A scenario run: the notes of each transition, in order, and the state it ends in.
#[derive(Clone, Debug)]
pub struct ScenarioRun {
    /// The notes of every transition taken.
    pub steps: Vec<Vec<Note>>,
    /// The last state.
    pub last: State,
    /// How it ended.
    pub end: RunEnd,
    /// Reasoning cycles run (request arrivals are not cycles).
    pub cycles: usize,
}

/// Runs `requests` (indices into [`Semantics::requests`]) from the environment state
/// `initial`, taking the first successor the plan selection gives, for at most
/// `max_cycles` reasoning cycles.
pub fn run_scenario(
    sem: &Semantics,
    initial: &AtomSet,
    requests: &[u8],
    max_cycles: usize,
) -> ScenarioRun {
    let mut state = sem.initial_state(initial);
    let mut steps = Vec::new();
    let mut next_request = 0;
    let mut cycles = 0;
    let end = loop {
        let is_request = |n: &[Note]| matches!(n.first(), Some(Note::Request { .. }));
        let pick = if state.is_idle() {
            let Some(&r) = requests.get(next_request) else {
                break RunEnd::Done;
            };
            next_request += 1;
            // The user asks as the scenario says, even for a goal asked before (the
            // search makes each request once per run; a scenario is one user's run).
            let mut next = state.clone();
            sem.post_request(&mut next, r as usize);
            Some(crate::semantics::Transition {
                notes: vec![Note::Request { index: r }],
                next,
            })
        } else {
            if cycles == max_cycles {
                break RunEnd::Bound;
            }
            cycles += 1;
            sem.successors(&state)
                .into_iter()
                .find(|t| !is_request(&t.notes))
        };
        let Some(t) = pick else {
            break RunEnd::Refused;
        };
        let beyond = crate::check::model::is_beyond(t.notes.iter());
        steps.push(t.notes);
        if beyond {
            break RunEnd::Beyond;
        }
        state = t.next;
    };
    ScenarioRun {
        steps,
        last: state,
        end,
        cycles,
    }
}
