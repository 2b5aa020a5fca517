//! `bdi-check graph PROJECT (--plans | --states)`: the goal-plan tree, or the explored state
//! graph (drawn by [`crate::report::graph`]). When the state graph has more states than can
//! be drawn legibly, the runs to its first failing states are drawn with their one-step
//! neighbourhood (or, when nothing fails, the states nearest the first initial state).

use super::Output;
use crate::check::explore::{explore_with, Graph, Limits, Options};
use crate::check::model::Model;
use crate::check::runs;
use crate::check::trace::Builder;
use crate::commands::verify::limits;
use crate::model::project::{load_project, Project};
use crate::report::graph::{plans_dot, states_dot, StateGraph, StateStyle, MAX_DRAWN_STATES};
use crate::semantics::{Note, Semantics, State};
use crate::syntax::manifest::PropertyKind;
use crate::syntax::Diagnostic;
use std::collections::BTreeSet;
use std::path::Path;

/// `graph PROJECT --plans` (`plans`) or `--states` (with `--max-states`).
pub fn command(project: &Path, plans: bool, max_states: Option<u64>, stderr_color: bool) -> Output {
    // Several agents: the graph of their interleavings.
    if let Ok(agents) = crate::model::project::load_system(project) {
        if agents.len() > 1 {
            if plans {
                let d = Diagnostic::error(
                    "input",
                    "`graph --plans` draws one agent's plans: give a project of one agent",
                )
                .in_file(agents[0].manifest.path.display().to_string());
                return Output::refused(crate::report::diagnostics(
                    &[d],
                    &agents[0].map,
                    stderr_color,
                ));
            }
            let bounds = super::verify::Bounds {
                max_states,
                ..Default::default()
            };
            return match system_state_graph(&agents, limits(&agents[0], &bounds)) {
                Ok(sg) => drawn_graph(sg),
                Err(errs) => {
                    Output::refused(crate::report::diagnostics(&errs, &agents[0].map, false))
                }
            };
        }
    }
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
        Ok(sg) => drawn_graph(sg),
        Err(errs) => Output::refused(crate::report::diagnostics(&errs, &p.map, false)),
    }
}

/// The DOT of a state graph, and a note on stderr when it is cut or empty.
fn drawn_graph(sg: StateGraph) -> Output {
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

/// How many failing states a cut graph draws the runs to.
const MAX_FAILING_RUNS: usize = 5;

/// The state graph, or, when it is too large, the runs to its first failing states with
/// their one-step neighbourhood (or, when nothing fails, the states nearest the first
/// initial state), and a note when it was cut. Initial, failing and looping states are
/// styled; every transition is labelled with the steps it shows.
pub fn state_graph(p: &Project, limits: Limits) -> Result<StateGraph, Vec<Diagnostic>> {
    let sem = Semantics::new(p)?;
    let invariants: Vec<&crate::model::cond::Cond> = p.invariants.iter().map(|(_, c)| c).collect();
    let always: Vec<crate::model::cond::Cond> = p
        .manifest
        .properties
        .iter()
        .filter(|x| x.kind == PropertyKind::Always)
        .filter(|x| !crate::model::property::is_run_property(x))
        .filter_map(|x| crate::model::formula::compile(&x.formula.expr, &p.atoms, &p.universe).ok())
        .collect();
    // `always` with a modality (`.intend`, `believes`, ...): on the state's propositions.
    let (run_props, atomics) = crate::model::property::compile(p)?;
    let (modal, skipped) = runs::always_on_states(&run_props, &atomics);
    let atoms = runs::RunAtoms::new(&atomics, &sem);
    let mut sg = draw(
        &sem,
        limits,
        |s: &State| {
            let letter = (!modal.is_empty()).then(|| atoms.state_letter(s));
            let bad = invariants.iter().any(|c| !c.eval(&s.beliefs))
                || always.iter().any(|c| !c.eval(&s.beliefs))
                || letter.is_some_and(|l| modal.iter().any(|f| !f.holds(&l)));
            (bad, s.is_idle())
        },
        |notes: &Vec<Note>| notes.iter().any(is_failure),
        |notes: &Vec<Note>| {
            let mut b = Builder::new(p, &sem);
            b.push(notes.clone());
            shown(b.steps())
        },
        |i, s: &State| {
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
                    s.intentions.len() + usize::from(s.pending.is_some()) + s.waiting.len()
                ));
            }
            label
        },
    );
    note_unmarked(&mut sg, &skipped);
    Ok(sg)
}

/// Adds to the drawing's note the `always` properties whose failing states it cannot mark
/// (they read the step into a state, `did` or `explained`, not the state).
fn note_unmarked(sg: &mut StateGraph, skipped: &[String]) {
    if skipped.is_empty() {
        return;
    }
    let names: Vec<String> = skipped.iter().map(|n| format!("`{n}`")).collect();
    let (verb, who) = if names.len() == 1 {
        ("fails", "it reads")
    } else {
        ("fail", "they read")
    };
    let what = format!(
        "the states where {} {verb} are not marked: {who} the step into a state, not the state (`verify` checks them)",
        names.join(", ")
    );
    sg.note = Some(match sg.note.take() {
        Some(n) => format!("{n}; {what}"),
        None => what,
    });
}

/// The drawing of the state graph of `model` within `limits`: `summary` says of a state
/// whether a state property fails there and whether it is done, `failure` whether a
/// transition shows a failure, `edge` what a transition shows, `node` what a state shows.
fn draw<M: Model + Sync>(
    model: &M,
    limits: Limits,
    summary: impl Fn(&M::State) -> (bool, bool) + Sync,
    failure: impl Fn(&M::Label) -> bool,
    edge: impl Fn(&M::Label) -> String,
    node: impl Fn(u32, &M::State) -> String,
) -> StateGraph
where
    M::State: Send + Sync,
    M::Label: Send,
{
    // Per state: whether a state property fails there, and whether the run is done.
    let mut facts: Vec<(bool, bool)> = Vec::new();
    let mut failing_step: BTreeSet<u32> = BTreeSet::new();
    let graph = explore_with(
        model,
        limits,
        &Options::default(),
        |s, _| summary(s),
        |i, _, x| {
            let i = i as usize;
            if facts.len() <= i {
                facts.resize(i + 1, (false, true));
            }
            facts[i] = x;
        },
        |src, _, label: &M::Label, _| {
            if failure(label) {
                failing_step.insert(src);
            }
        },
        |_, _, _| {},
    );
    let stuck = |i: u32| {
        graph.successors(i).is_some_and(|e| e.is_empty())
            && !facts.get(i as usize).is_some_and(|x| x.1)
    };
    let failing = |i: u32| {
        facts.get(i as usize).is_some_and(|x| x.0) || failing_step.contains(&i) || stuck(i)
    };
    let (drawn, note) = drawn_states(&graph, &failing);
    // Rebuild each drawn state (by replaying its run) and label it and its transitions.
    let mut states: std::collections::BTreeMap<u32, M::State> = Default::default();
    for &i in &drawn {
        if let Some(s) = graph.state(model, i) {
            states.insert(i, s);
        }
    }
    let mut edges: Vec<(u32, u32, String, bool)> = Vec::new();
    for (&i, from) in &states {
        let Some(targets) = graph.successors(i) else {
            continue;
        };
        let succ = model.next_states(from);
        for &j in targets {
            if !states.contains_key(&j) {
                continue;
            }
            let want = graph.fingerprint(j);
            let Some((label, _)) = succ.iter().find(|(_, t)| model.fingerprint(t) == want) else {
                continue;
            };
            edges.push((i, j, edge(label), failure(label)));
        }
    }
    let looping = looping(states.keys().copied(), &edges);
    let nodes = states
        .iter()
        .map(|(&i, s)| {
            let style = StateStyle {
                initial: (i as usize) < graph.initial,
                failing: failing(i),
                looping: looping.contains(&i),
            };
            (i, node(i, s), style)
        })
        .collect();
    StateGraph { nodes, edges, note }
}

/// A transition's label: the steps it shows, one a line.
fn shown(steps: &[crate::findings::TraceStep]) -> String {
    if steps.is_empty() {
        "(a cycle that shows no step)".to_string()
    } else {
        steps
            .iter()
            .map(|s| s.text.clone())
            .collect::<Vec<_>>()
            .join("\n")
    }
}

/// The states to draw: all, or, when there are too many, the runs to the first failing
/// states with their one-step neighbourhood (or, when nothing fails, the states nearest the
/// first initial state), and why not all.
fn drawn_states<S>(
    graph: &Graph<S>,
    failing: &impl Fn(u32) -> bool,
) -> (BTreeSet<u32>, Option<String>) {
    let n = graph.len();
    if n <= MAX_DRAWN_STATES {
        ((0..n as u32).collect(), None)
    } else {
        let mut keep = BTreeSet::new();
        let targets: Vec<u32> = (0..n as u32)
            .filter(|&i| failing(i))
            .take(MAX_FAILING_RUNS)
            .collect();
        for &t in &targets {
            for i in graph.path_to(t) {
                keep.insert(i);
                // The one-step neighbourhood: what else the run could have done.
                for &j in graph.successors(i).unwrap_or(&[]) {
                    if keep.len() < MAX_DRAWN_STATES {
                        keep.insert(j);
                    }
                }
            }
        }
        let why = if targets.is_empty() {
            // Nothing fails: the states nearest the first initial state, breadth first.
            let mut queue = std::collections::VecDeque::from([0u32]);
            while let Some(i) = queue.pop_front() {
                if keep.len() >= MAX_DRAWN_STATES {
                    break;
                }
                if keep.insert(i) {
                    queue.extend(graph.successors(i).unwrap_or(&[]).iter().copied());
                }
            }
            format!("the state graph has {n} states, too many to draw: drawing the {} states nearest the first initial state", keep.len())
        } else {
            format!(
                "the state graph has {n} states, too many to draw: drawing the runs to the first {} failing states and what else each step could have done ({} states)",
                targets.len(),
                keep.len()
            )
        };
        (keep, Some(why))
    }
}

/// The drawn states on a cycle among the drawn transitions.
fn looping(states: impl Iterator<Item = u32>, edges: &[(u32, u32, String, bool)]) -> BTreeSet<u32> {
    let mut g: petgraph::graph::DiGraph<u32, ()> = petgraph::graph::DiGraph::new();
    let index: std::collections::HashMap<u32, petgraph::graph::NodeIndex> =
        states.map(|i| (i, g.add_node(i))).collect();
    for (i, j, _, _) in edges {
        g.add_edge(index[i], index[j], ());
    }
    let mut looping: BTreeSet<u32> = BTreeSet::new();
    for scc in petgraph::algo::kosaraju_scc(&g) {
        let on_cycle = scc.len() > 1 || g.contains_edge(scc[0], scc[0]);
        if on_cycle {
            looping.extend(scc.iter().map(|&k| g[k]));
        }
    }
    looping
}

/// The graph of the interleavings of several agents (every one, no reduction), drawn as
/// [`state_graph`] draws one agent's: a state shows the environment and what each agent
/// has to do; a transition, its agent and the steps it shows.
pub fn system_state_graph(
    projects: &[Project],
    limits: Limits,
) -> Result<StateGraph, Vec<Diagnostic>> {
    use crate::semantics::{Step, System, SystemState};
    let system = System::new(projects)?;
    let p = &projects[0];
    let names = system.names();
    let conds: Vec<crate::model::cond::Cond> = p
        .invariants
        .iter()
        .map(|(_, c)| c.clone())
        .chain(
            p.manifest
                .properties
                .iter()
                .filter(|x| x.kind == PropertyKind::Always)
                .filter(|x| !crate::model::property::is_run_property(x))
                .filter_map(|x| {
                    crate::model::formula::compile_in(&x.formula.expr, &p.atoms, &p.universe, names)
                        .ok()
                }),
        )
        .collect();
    let (run_props, atomics) = crate::model::property::compile_in(p, names)?;
    let (modal, skipped) = runs::always_on_states(&run_props, &atomics);
    let atoms = runs::RunAtoms::new(&atomics, &system.agents[0]);
    let busy = |s: &SystemState, k: usize| !s.agents[k].is_idle() || !s.mail[k].is_empty();
    let mut sg = draw(
        &system,
        limits,
        |s: &SystemState| {
            let all = system.everything(s);
            let letter = (!modal.is_empty()).then(|| atoms.system_letter(&all, &s.agents));
            let bad = conds.iter().any(|c| !c.eval(&all))
                || letter.is_some_and(|l| modal.iter().any(|f| !f.holds(&l)));
            (bad, (0..s.agents.len()).all(|k| !busy(s, k)))
        },
        |step: &Step| step.notes.iter().any(is_failure),
        |step: &Step| {
            let k = step.agent as usize;
            let mut b = Builder::new(&projects[k], &system.agents[k]);
            b.push(step.notes.clone());
            format!("{}: {}", names[k], shown(b.steps()))
        },
        |i, s: &SystemState| {
            let world: Vec<String> = s
                .world
                .iter()
                .map(|a| p.atoms.display(a, &p.universe))
                .collect();
            let mut label = format!("s{i}\n{}", world.join("\n"));
            for (k, a) in s.agents.iter().enumerate() {
                if busy(s, k) {
                    label.push_str(&format!(
                        "\n{}: {} events, {} intentions, {} messages",
                        names[k],
                        a.events.len(),
                        a.intentions.len() + usize::from(a.pending.is_some()) + a.waiting.len(),
                        s.mail[k].len()
                    ));
                }
            }
            label
        },
    );
    note_unmarked(&mut sg, &skipped);
    Ok(sg)
}

/// Whether a transition's note is a failure a check reports.
fn is_failure(n: &Note) -> bool {
    matches!(n, Note::ActionFailed { .. } | Note::GoalFailed { .. })
}
