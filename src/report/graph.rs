//! `bdi-check graph PROJECT (--plans | --states)`: DOT drawings built with petgraph.
//!
//! `--plans` draws the goal-plan tree: each goal (or belief event) points to the plans
//! relevant for it, labelled with their contexts, and each plan to the subgoals its body
//! posts. `--states` draws the explored state graph; when it has more states than can be
//! drawn legibly, it draws the part that the counterexamples of the failing checks go
//! through (or the first states in breadth-first order when nothing fails) and says so.

use crate::model::plans::{BodyStep, Formula, Step};
use crate::model::project::Project;
use petgraph::dot::{Config, Dot};
use petgraph::graph::{DiGraph, NodeIndex};
use std::collections::HashMap;

/// Most states `--states` draws in full.
pub const MAX_DRAWN_STATES: usize = 200;

/// A context as text, as the model holds it.
pub(super) fn formula_text(f: &Formula) -> String {
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
pub(super) fn subgoals(steps: &[Step], out: &mut Vec<(String, bool)>) {
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
    for (i, plan) in p.plans.plans.iter().enumerate() {
        let t = &plan.trigger;
        let (op, kind) = (t.op.symbol(), t.kind.symbol());
        let event = format!(
            "{op}{kind}{}/{}",
            t.literal.functor().unwrap_or(""),
            t.literal.arity()
        );
        let from = goal(&mut g, event);
        let loc = p.map.location(plan.span);
        // A plan a step adds is only in the library once it has been added.
        let added = if p.plans.is_added(i) {
            "\n(added at run time)"
        } else {
            ""
        };
        let node = g.add_node(format!(
            "{}\n: {}\n{}:{}{added}",
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

/// How a drawn state is styled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StateStyle {
    /// An initial state (drawn with a double border).
    pub initial: bool,
    /// A state where a check fails: an invariant or `always` property is false, no step is
    /// possible though the agent is not done, or a transition from it fails an action or a
    /// goal (filled red).
    pub failing: bool,
    /// A state on a loop among the drawn states (filled yellow).
    pub looping: bool,
}

/// A drawn part of the state graph: the states (by number, with their labels and styles),
/// the transitions between them (with every step they show, and whether one fails), and
/// why it was cut, if it was.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StateGraph {
    /// Each drawn state, in drawing order.
    pub nodes: Vec<(u32, String, StateStyle)>,
    /// Each drawn transition `(from, to, label, failing)`, between drawn states.
    pub edges: Vec<(u32, u32, String, bool)>,
    /// Why not every state is drawn, if not.
    pub note: Option<String>,
}

/// The state graph as DOT; a cut graph says why in a comment on its first line.
pub fn states_dot(sg: &StateGraph) -> String {
    let mut g: DiGraph<(String, StateStyle), (String, bool)> = DiGraph::new();
    let mut node: HashMap<u32, NodeIndex> = HashMap::new();
    for (i, label, style) in &sg.nodes {
        node.insert(*i, g.add_node((label.clone(), *style)));
    }
    for (i, j, label, failing) in &sg.edges {
        g.add_edge(node[i], node[j], (label.clone(), *failing));
    }
    let quote = |t: &str| {
        t.replace('\\', "\\\\")
            .replace('"', "\\\"")
            .replace('\n', "\\n")
    };
    let edge = |_: &DiGraph<_, _>, e: petgraph::graph::EdgeReference<(String, bool)>| {
        let (label, failing) = e.weight();
        let colour = if *failing {
            ", color=red, fontcolor=red"
        } else {
            ""
        };
        format!("label = \"{}\"{colour}", quote(label))
    };
    let state = |_: &DiGraph<_, _>, (_, (label, st)): (NodeIndex, &(String, StateStyle))| {
        let mut a = format!("label = \"{}\"", quote(label));
        if st.initial {
            a.push_str(", peripheries=2");
        }
        if st.failing {
            a.push_str(", style=filled, fillcolor=\"#f4cccc\", color=red");
        } else if st.looping {
            a.push_str(", style=filled, fillcolor=\"#fff2cc\"");
        }
        a
    };
    let dot = Dot::with_attr_getters(
        &g,
        &[Config::EdgeNoLabel, Config::NodeNoLabel],
        &edge,
        &state,
    );
    let mut dot = format!("{dot:?}").replace(
        "digraph {",
        "digraph states {\n    node [shape=box, fontname=\"monospace\"];\n    edge [fontname=\"monospace\"];",
    );
    if let Some(why) = &sg.note {
        dot = format!("// {why}\n{dot}");
    }
    dot
}
