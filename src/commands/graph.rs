//! `bdi-check graph PROJECT (--plans | --states)`: the goal-plan tree, or the explored state
//! graph (drawn by [`crate::report::graph`]). When the state graph has more states than can
//! be drawn legibly, the part that the counterexamples of the failing checks go through is
//! drawn (or the first states in breadth-first order when nothing fails).

use super::Output;
use crate::check::explore::{explore, fingerprint, Limits};
use crate::check::verify;
use crate::commands::verify::limits;
use crate::findings::Status;
use crate::model::project::{load_project, Project};
use crate::report::graph::{plans_dot, states_dot, StateGraph, MAX_DRAWN_STATES};
use crate::semantics::{Note, Semantics};
use crate::syntax::Diagnostic;
use std::collections::BTreeSet;
use std::path::Path;

/// `graph PROJECT --plans` (`plans`) or `--states` (with `--max-states`).
pub fn command(project: &Path, plans: bool, max_states: Option<u64>, stderr_color: bool) -> Output {
    let p = match load_project(project) {
        Ok(p) => p,
        Err(e) => {
            return Output::refused(crate::report::diagnostics(
                &e.diagnostics,
                &e.map,
                stderr_color,
            ))
        }
    };
    if plans {
        return Output::report(plans_dot(&p), 0);
    }
    let bounds = super::verify::Bounds {
        max_states,
        ..Default::default()
    };
    match state_graph(&p, limits(&p, &bounds)) {
        Ok(sg) => {
            // An empty drawing says why (`--max-states 0`), as a cut one does.
            let note = sg.note.clone().or_else(|| {
                sg.nodes.is_empty().then(|| {
                    "the state graph is empty: the state bound (`--max-states`, `[bounds] max_states`) stopped the search before its first state".to_string()
                })
            });
            Output {
                stderr: note.map(|n| format!("note: {n}\n")).unwrap_or_default(),
                report: Some(states_dot(&sg)),
                code: 0,
            }
        }
        Err(errs) => Output::refused(crate::report::diagnostics(&errs, &p.map, false)),
    }
}

/// The state graph (or, when it is too large, its counterexample part), and a note when
/// it was cut.
pub fn state_graph(p: &Project, limits: Limits) -> Result<StateGraph, Vec<Diagnostic>> {
    let sem = Semantics::new(p)?;
    let graph = explore(&sem, limits, |_, _, _| {}, |_, _, _| {});
    let n = graph.len();
    // Only fingerprints are kept: a drawn state is rebuilt by replaying the run to it.
    let state = |i: u32| graph.state(&sem, i);
    let (drawn, note): (BTreeSet<u32>, Option<String>) = if n <= MAX_DRAWN_STATES {
        ((0..n as u32).collect(), None)
    } else {
        let v = verify(p, limits, |_, _, _| {}, &[])?;
        let mut keep = BTreeSet::new();
        for f in v.findings.iter().filter(|f| f.status == Status::Fail) {
            if let Some(c) = &f.counterexample {
                // The counterexample's initial state, then follow its steps through the graph.
                let start = (0..graph.initial as u32).find(|&i| {
                    state(i).is_some_and(|s| {
                        s.beliefs
                            .iter()
                            .map(|a| p.atoms.display(a, &p.universe))
                            .collect::<Vec<_>>()
                            == c.initial
                    })
                });
                if let Some(i) = start {
                    keep.insert(i);
                    let mut at = i;
                    for _ in 0..c.steps.len() {
                        let Some(next) = graph.successors(at) else {
                            break;
                        };
                        let Some(&j) = next.first() else { break };
                        keep.insert(j);
                        at = j;
                    }
                }
            }
        }
        let why = if keep.is_empty() {
            keep = (0..MAX_DRAWN_STATES as u32).collect();
            format!("the state graph has {n} states, too many to draw: drawing the first {MAX_DRAWN_STATES} in breadth-first order")
        } else {
            format!("the state graph has {n} states, too many to draw: drawing the {} states the counterexamples go through", keep.len())
        };
        (keep, Some(why))
    };
    let mut nodes: Vec<(u32, String)> = Vec::new();
    let mut drawn_states: BTreeSet<u32> = BTreeSet::new();
    let mut edges: Vec<(u32, u32, String)> = Vec::new();
    for &i in &drawn {
        let Some(s) = state(i) else { continue };
        let beliefs: Vec<String> = s
            .beliefs
            .iter()
            .map(|a| p.atoms.display(a, &p.universe))
            .collect();
        let mut label = format!("s{i}\n{}", beliefs.join("\n"));
        if !s.is_idle() {
            label.push_str(&format!(
                "\n({} events, {} intentions)",
                s.events.len(),
                s.intentions.len()
            ));
        }
        nodes.push((i, label));
        drawn_states.insert(i);
    }
    for &i in &drawn {
        let (Some(targets), Some(from)) = (graph.successors(i), state(i)) else {
            continue;
        };
        let succ = sem.successors(&from);
        for &j in targets {
            if !drawn_states.contains(&j) {
                continue;
            }
            let want = graph.fingerprint(j);
            let label = succ
                .iter()
                .find(|t| fingerprint(&t.next) == want)
                .map(|t| {
                    t.notes
                        .iter()
                        .filter_map(|n| match n {
                            Note::Request { index } => {
                                Some(format!("!{}", sem.requests[*index as usize]))
                            }
                            Note::Action { text, .. } => Some(text.clone()),
                            Note::ActionFailed { text, .. } => Some(format!("{text} fails")),
                            Note::GoalFailed { cause, .. } => Some(format!("{cause} fails")),
                            _ => None,
                        })
                        .collect::<Vec<_>>()
                        .join("; ")
                })
                .unwrap_or_default();
            edges.push((i, j, label));
        }
    }
    Ok(StateGraph { nodes, edges, note })
}
