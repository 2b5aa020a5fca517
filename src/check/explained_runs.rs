//! Run properties about explanations (`explained(user, a)`): decided on that user's
//! explanation search ([`Explained`]), exact and with its edges, whose transitions carry
//! the explanations the paper's algorithms give. One agent or several: the caller says
//! what a state's letter is and which agents are busy in it.

use super::explanation::{Explained, ExplainedState, Runs, Step};
use super::explore::{explore_with, Limits, Options};
use super::model::CycleNotes;
use super::runs::{self, Letter, Letters};
use crate::findings::{Finding, Phase};
use crate::model::project::Project;
use crate::model::property::RunProperty;
use crate::semantics::Note;

/// How the runs of a user's search are read.
pub(super) struct Reading<'r, S> {
    /// A state's letter (its propositions about states), and the agents busy in it (one bit
    /// each; none: a run may end there, the user asking nothing more).
    pub(super) facts: &'r (dyn Fn(&S) -> (Letter, u64) + Sync),
    /// With weak fairness of agents: how many agents (each loop moves every agent that can
    /// move throughout it).
    pub(super) fair_agents: Option<u8>,
    /// Which runs a passing property held on, for its message.
    pub(super) runs: &'r str,
}

/// Decides `props` (about the explanations `user` gets) on `model`, that user's search:
/// one finding each, located in `manifest` (the project whose manifest has the properties)
/// with its run rendered as `robot`'s (the agent `model` watches), and the phase
/// `ltl search:USER`.
pub(super) fn decide<W: Runs>(
    (manifest, robot): (&Project, &Project),
    (user, model): (&str, &Explained<W>),
    (props, atoms): (&[&RunProperty], &runs::RunAtoms),
    reading: Reading<W::State>,
    (limits, opts): (Limits, &Options),
    progress: &mut dyn FnMut(&str, usize, u32, f64),
) -> (Vec<Finding>, Phase) {
    let t = std::time::Instant::now();
    let mut letters = Letters::default();
    let mut busy: Vec<u64> = Vec::new();
    // Per state, per transition: the agent that moved (`None`: a request).
    let mut moves: Vec<Vec<Option<u8>>> = Vec::new();
    let mut steps = runs::StepLetters::default();
    let phase = format!("ltl search:{user}");
    let opts = Options {
        keep_edges: true,
        ..*opts
    };
    let graph = explore_with(
        model,
        limits,
        &opts,
        |s: &ExplainedState<W::State>, _| (reading.facts)(&s.state),
        |i, _, (letter, b)| {
            letters.push(letter);
            if busy.len() <= i as usize {
                busy.resize(i as usize + 1, 0);
            }
            busy[i as usize] = b;
        },
        |src, k, label: &Step<W::Notes>, _| {
            if reading.fair_agents.is_some() {
                let at = src as usize;
                if moves.len() <= at {
                    moves.resize(at + 1, Vec::new());
                }
                let mut notes = label.notes.notes();
                let request = matches!(
                    (notes.next(), notes.next()),
                    (Some(Note::Request { .. }), None)
                );
                moves[at].push((!request).then_some(label.agent));
            }
            if let Some(l) = atoms.explained_step_letter(label) {
                steps.insert((src, k), l);
            }
        },
        |n, d, t| progress(&phase, n, d, t),
    );
    moves.resize(graph.len(), Vec::new());
    busy.resize(graph.len(), 0);
    let succ = |i: u32| graph.successors(i);
    let may_end =
        |i: u32| graph.successors(i).is_some_and(|e| e.is_empty()) || busy[i as usize] == 0;
    let enabled = |i: u32| {
        moves[i as usize]
            .iter()
            .flatten()
            .fold(0u64, |b, &a| b | 1 << a)
    };
    let mover = |i: u32, k: u32| moves[i as usize].get(k as usize).copied().flatten();
    let recorded = runs::RunFacts {
        len: graph.len() as u32,
        initial: graph.initial as u32,
        successors: &succ,
        may_end: &may_end,
        letters: &letters.ids,
        letter_table: &letters.table,
        steps: &steps,
        fairness: reading.fair_agents.map(|agents| runs::Fairness {
            agents,
            enabled: &enabled,
            mover: &mover,
        }),
    };
    let mut products = runs::Products::default();
    let mut out = Vec::new();
    for p in props {
        let (status, message, v) = runs::decide(
            &recorded,
            p,
            (graph.complete(), reading.runs),
            &mut products,
        );
        let at = (p.span, manifest.map.location(p.span));
        // The message as decided (an undecided one already says why).
        let mut f = super::checker::dynamic_finding("property", &p.name, at, status, String::new());
        f.message = message;
        f.counterexample =
            v.map(|v| super::explanation::counterexample_via(robot, model, &graph, &v));
        out.push(f);
    }
    let phase = Phase {
        name: phase,
        seconds: t.elapsed().as_secs_f64(),
        states: Some(graph.len()),
        beside: Vec::new(),
    };
    (out, phase)
}
