//! `bdi-check graph PROJECT (--plans | --states)`: DOT drawings built with petgraph.
//!
//! `--plans` draws the goal-plan tree: each goal (or belief event) points to the plans
//! relevant for it, labelled with their contexts, and each plan to the subgoals its body
//! posts. `--states` draws the explored state graph; when it has more states than can be
//! drawn legibly, it draws the part that the counterexamples of the failing checks go
//! through (or the first states in breadth-first order when nothing fails) and says so.

use crate::check::explore::{explore, fingerprint, Limits};
use crate::check::verify;
use crate::model::plans::{BodyStep, Formula, Step};
use crate::model::project::Project;
use crate::report::Status;
use crate::semantics::{Note, Semantics};
use crate::syntax::Diagnostic;
use petgraph::dot::{Config, Dot};
use petgraph::graph::{DiGraph, NodeIndex};
use std::collections::{BTreeSet, HashMap};

/// Most states `--states` draws in full.
pub const MAX_DRAWN_STATES: usize = 200;

fn formula_text(f: &Formula) -> String {
    match f {
        Formula::True => "true".into(),
        Formula::Literal(t) | Formula::Call(t) => t.to_string(),
        Formula::Not(g) => format!("not {}", formula_text(g)),
        Formula::And(a, b) => format!("{} & {}", formula_text(a), formula_text(b)),
        Formula::Or(a, b) => format!("({} | {})", formula_text(a), formula_text(b)),
        Formula::Rel(op, a, b) => format!("{a} {} {b}", op.symbol()),
    }
}

/// The goals a body posts: `(name/arity, new intention?)`.
fn subgoals(steps: &[Step], out: &mut Vec<(String, bool)>) {
    for s in steps {
        match &s.kind {
            BodyStep::Achieve { goal, new_focus } => out.push((
                format!("{}/{}", goal.functor().unwrap_or(""), goal.arity()),
                *new_focus,
            )),
            BodyStep::If {
                branches,
                else_body,
            } => {
                for (_, b) in branches {
                    subgoals(b, out);
                }
                subgoals(else_body, out);
            }
            BodyStep::While(_, b) | BodyStep::For(_, b) => subgoals(b, out),
            _ => {}
        }
    }
}

/// The goal-plan tree as DOT.
pub fn plans_dot(p: &Project) -> String {
    let mut g: DiGraph<String, String> = DiGraph::new();
    let mut goals: HashMap<String, NodeIndex> = HashMap::new();
    let mut goal = |g: &mut DiGraph<String, String>, key: String| {
        *goals.entry(key.clone()).or_insert_with(|| g.add_node(key))
    };
    for plan in &p.plans.plans {
        let t = &plan.trigger;
        let (op, kind) = (t.op.symbol(), t.kind.symbol());
        let event = format!(
            "{op}{kind}{}/{}",
            t.literal.functor().unwrap_or(""),
            t.literal.arity()
        );
        let from = goal(&mut g, event);
        let loc = p.map.location(plan.span);
        let node = g.add_node(format!(
            "{}\n: {}\n{}:{}",
            plan.name(),
            formula_text(&plan.context),
            loc.file,
            loc.line
        ));
        g.add_edge(from, node, String::new());
        let mut subs = Vec::new();
        subgoals(&plan.body, &mut subs);
        for (name, new_focus) in subs {
            let to = goal(&mut g, format!("+!{name}"));
            g.add_edge(
                node,
                to,
                if new_focus {
                    "new intention".into()
                } else {
                    String::new()
                },
            );
        }
    }
    format!("{}", Dot::with_config(&g, &[Config::EdgeNoLabel])).replace(
        "digraph {",
        "digraph plans {\n    rankdir=LR;\n    node [shape=box, fontname=\"monospace\"];",
    )
}

/// The state graph (or its counterexample part) as DOT, and a note when it was cut.
pub fn states_dot(
    p: &Project,
    limits: Limits,
) -> Result<(String, Option<String>), Vec<Diagnostic>> {
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
    let mut g: DiGraph<String, String> = DiGraph::new();
    let mut node: HashMap<u32, NodeIndex> = HashMap::new();
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
        node.insert(i, g.add_node(label));
    }
    for &i in &drawn {
        let (Some(targets), Some(from)) = (graph.successors(i), state(i)) else {
            continue;
        };
        let succ = sem.successors(&from);
        for &j in targets {
            let Some(&to) = node.get(&j) else { continue };
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
            g.add_edge(node[&i], to, label);
        }
    }
    let mut dot = format!("{}", Dot::new(&g)).replace(
        "digraph {",
        "digraph states {\n    node [shape=box, fontname=\"monospace\"];",
    );
    if let Some(why) = &note {
        dot = format!("// {why}\n{dot}");
    }
    Ok((dot, note))
}
