//! The checks among several agents that a run going on for ever decides: `livelock` of
//! each agent (it runs for ever without becoming idle), `request-not-completed` (a request
//! of the user stays pending for ever) and `eventually` properties (a run where the
//! property never holds). Each violation is a lasso: the shortest run to a loop, then a
//! loop of the explored graph.
//!
//! Jason runs each agent in a thread of its own, so no agent that can always take a step
//! is left out for ever: the loops counted are those *fair* to every agent (weak
//! fairness): an agent that can take a step in every state of the loop takes one in it.
//! On the strongly connected components of the graph restricted to the states a check
//! keeps, a fair loop exists exactly when every agent that can move in every state of the
//! component moves inside it (a loop through every transition of the component then is
//! one). A request arriving is the user's step, not an agent's: the user may stop asking.
//!
//! These checks follow runs, so they are made on a graph of every interleaving, states
//! unrenamed: when partial-order reduction or symmetry reduced the search and its graph
//! has a loop, `verify` searches again without them for these checks (see
//! `verify_system`). A reduced graph with no loop at all stands for a system that has no
//! run going on for ever.

use super::{Cx, Run};
use crate::check::explore::Graph;
use crate::findings::{Finding, Status};
use crate::semantics::SystemState;
use crate::syntax::Span;
use petgraph::graph::{DiGraph, NodeIndex};
use std::collections::{HashMap, VecDeque};

/// What the liveness checks read of each stored state and transition.
#[derive(Default)]
pub(super) struct Facts {
    /// Per state: the agents not done, one bit each.
    pub busy: Vec<u64>,
    /// Per state: the requests pending (of the agent they go to), one bit each.
    pub pending: Vec<u64>,
    /// Per state: the `eventually` properties that hold, one bit each.
    pub holds: Vec<u64>,
    /// Per state: for each transition followed from it, in order, its agent (`None`: a
    /// request of the user).
    pub moves: Vec<Vec<Option<u8>>>,
}

impl Facts {
    /// Records what state `i` decides.
    pub fn state(&mut self, i: u32, busy: u64, pending: u64, holds: u64) {
        let i = i as usize;
        if self.busy.len() <= i {
            self.busy.resize(i + 1, 0);
            self.pending.resize(i + 1, 0);
            self.holds.resize(i + 1, 0);
        }
        self.busy[i] = busy;
        self.pending[i] = pending;
        self.holds[i] = holds;
    }

    /// Records a transition followed from state `src`.
    pub fn transition(&mut self, src: u32, agent: Option<u8>) {
        let at = src as usize;
        if self.moves.len() <= at {
            self.moves.resize(at + 1, Vec::new());
        }
        self.moves[at].push(agent);
    }

    fn resize(&mut self, n: usize) {
        self.busy.resize(n, 0);
        self.pending.resize(n, 0);
        self.holds.resize(n, 0);
        self.moves.resize(n, Vec::new());
    }
}

/// Transitions a loop must go through, as `(from, to)`.
type Waypoints = Vec<(u32, u32)>;

/// A violation: the state the loop is entered at and a fair loop from it back to it
/// (states, the entry first and last).
type Lasso = (u32, Vec<u32>);

/// The liveness checks on `graph` (a search of every interleaving), whose states and
/// transitions `facts` describes: their findings (`eventually` ones in the order of
/// `eventually`: name and span), each violation with its lasso.
pub(super) fn liveness(
    cx: &Cx,
    mut facts: Facts,
    eventually: &[(String, Span)],
    place: Span,
    out: &mut Vec<Finding>,
) {
    let graph = cx.graph;
    let n = graph.len();
    facts.resize(n);
    let names = cx.system.names();
    let agents = names.len();
    let held = if graph.complete() {
        Status::Pass
    } else {
        Status::Unknown
    };
    let fair = cx.projects[0].manifest.bounds.fair_agents;
    let lg = Loops {
        graph,
        facts: &facts,
        agents,
        fair,
    };
    // What the runs that go on for ever are assumed to be.
    let runs = super::super::runs::agents_runs(fair);
    for (k, name) in names.iter().enumerate() {
        let bit = 1u64 << k;
        // Where the agent is named.
        let at = cx.projects[k].declared;
        // Busy throughout, and taking steps.
        let found = lg.fair_loop(|i| facts.busy[i as usize] & bit != 0, Some(k as u8));
        out.push(match found {
            Some(lasso) => cx.lasso_finding(
                "livelock",
                name,
                at,
                format!("`{name}` can run for ever without becoming idle"),
                &lasso,
                None,
            ),
            None => cx.finding(
                "livelock",
                name,
                at,
                held,
                format!("on {runs}, `{name}` ends idle"),
            ),
        });
    }
    let requests = &cx.system.agents[0].requests;
    let mut starved = None;
    for (r, goal) in requests.iter().enumerate() {
        let bit = 1u64 << r;
        if let Some(lasso) = lg.fair_loop(|i| facts.pending[i as usize] & bit != 0, None) {
            starved = Some((goal, lasso));
            break;
        }
    }
    out.push(match starved {
        Some((goal, lasso)) => cx.lasso_finding(
            "request-not-completed",
            &goal.to_string(),
            place,
            format!(
                "the request !{goal} to `{}` can stay pending for ever",
                names[0]
            ),
            &lasso,
            None,
        ),
        None => cx.finding(
            "request-not-completed",
            "all",
            place,
            held,
            format!("every request ends (completed or reported as a goal failure) on {runs}"),
        ),
    });
    for (j, (name, span)) in eventually.iter().enumerate() {
        let bit = 1u64 << j;
        let never = |i: u32| facts.holds[i as usize] & bit == 0;
        // States a run reaches while the property has not held yet, each with the one
        // before it on a shortest such run.
        let region = lg.reachable_within(never);
        let inside = |i: u32| region[i as usize].is_some();
        // A run that ends there (the nearest), or a fair loop there. A run ends where
        // nothing can happen, and where every agent is done: the user may stop asking at
        // any point (`[requests] max` is a bound, SPEC §1).
        let dead_end = (0..n as u32)
            .filter(|&i| {
                inside(i)
                    && (graph.successors(i).is_some_and(|s| s.is_empty())
                        || facts.busy[i as usize] == 0)
            })
            .min_by_key(|&i| path_within(&region, i).len());
        let f = match (dead_end, lg.fair_loop(inside, None)) {
            (Some(i), _) => {
                let mut f = cx.finding(
                    "property",
                    name,
                    *span,
                    Status::Fail,
                    format!("`{name}` never holds on a run that ends"),
                );
                let run = cx.run(&path_within(&region, i), None);
                f.counterexample = Some(cx.counterexample_of(&run));
                f
            }
            (None, Some(lasso)) => {
                // The run to the loop does not meet the property either.
                let prefix = path_within(&region, lasso.0);
                cx.lasso_finding(
                    "property",
                    name,
                    *span,
                    format!("`{name}` never holds on a run that goes on for ever"),
                    &lasso,
                    Some(prefix),
                )
            }
            (None, None) => cx.finding(
                "property",
                name,
                *span,
                held,
                format!("`{name}` holds at some point of {runs}"),
            ),
        };
        out.push(f);
    }
}

/// The explored graph's loops.
struct Loops<'a> {
    graph: &'a Graph<SystemState>,
    facts: &'a Facts,
    agents: usize,
    /// Weak fairness of agents (`[bounds] fairness`): a loop in which an agent could move
    /// in every state must move it.
    fair: bool,
}

impl Loops<'_> {
    /// The agents that take a step from state `i`, one bit each (not the user).
    fn enabled(&self, i: u32) -> u64 {
        self.facts.moves[i as usize]
            .iter()
            .flatten()
            .fold(0, |b, &a| b | 1 << a)
    }

    /// A fair loop through states `keep` keeps (with a step of `mover` in it, when
    /// given), entered at its least deep state, by the least deep such loop.
    fn fair_loop(&self, keep: impl Fn(u32) -> bool, mover: Option<u8>) -> Option<Lasso> {
        let graph = self.graph;
        // Only states expanded completely: their steps are all known.
        let kept = |i: u32| keep(i) && graph.successors(i).is_some();
        let comps = components(graph, &kept);
        // (depth of the entry, the entry, one transition of each agent that must move).
        let mut best: Option<(u32, u32, Waypoints)> = None;
        for comp in comps {
            let inside: std::collections::HashSet<u32> = comp.iter().copied().collect();
            // The transitions inside, with their agents.
            let mut edges: Vec<(u32, u32, Option<u8>)> = Vec::new();
            for &i in &comp {
                let succ = graph.successors(i).expect("expanded");
                for (e, &j) in succ.iter().enumerate() {
                    if inside.contains(&j) {
                        edges.push((i, j, self.facts.moves[i as usize].get(e).copied().flatten()));
                    }
                }
            }
            if edges.is_empty() {
                continue;
            }
            // Every agent that can move everywhere in it moves in it.
            let everywhere = comp.iter().fold(u64::MAX, |b, &i| b & self.enabled(i));
            let moved = edges
                .iter()
                .filter_map(|(_, _, a)| *a)
                .fold(0u64, |b, a| b | 1 << a);
            let needed = (0..self.agents as u8)
                .filter(|a| self.fair && everywhere >> a & 1 == 1)
                .collect::<Vec<_>>();
            if needed.iter().any(|a| moved >> a & 1 == 0) {
                continue;
            }
            let mut must: Vec<u8> = needed;
            if let Some(m) = mover {
                if moved >> m & 1 == 0 {
                    continue;
                }
                if !must.contains(&m) {
                    must.push(m);
                }
            }
            let entry = *comp
                .iter()
                .min_by_key(|&&i| (graph.depth(i), i))
                .expect("a state");
            let depth = graph.depth(entry);
            if best
                .as_ref()
                .is_some_and(|(d, e, _)| (*d, *e) <= (depth, entry))
            {
                continue;
            }
            // One transition of each agent that must move, in the order met; and, for each
            // agent that can move at the entry but not everywhere in the component, a
            // transition into a state where it cannot (so that the loop itself is fair:
            // a loop that never leaves the states where such an agent can move would have
            // to move it too).
            let mut waypoints: Vec<(u32, u32)> = Vec::new();
            for a in must {
                if let Some(&(i, j, _)) = edges.iter().find(|(_, _, x)| *x == Some(a)) {
                    waypoints.push((i, j));
                }
            }
            for a in (0..self.agents as u8).filter(|&a| {
                self.fair && everywhere >> a & 1 == 0 && self.enabled(entry) >> a & 1 == 1
            }) {
                if let Some(&(i, j, _)) = edges
                    .iter()
                    .find(|(_, j, _)| self.enabled(*j) >> a & 1 == 0)
                {
                    waypoints.push((i, j));
                }
            }
            best = Some((depth, entry, waypoints));
        }
        let (_, entry, waypoints) = best?;
        // The loop: from the entry through each waypoint's transition, and back.
        let comp_keep = |i: u32| kept(i);
        let mut cycle = vec![entry];
        let mut at = entry;
        for (i, j) in waypoints {
            let path = self.shortest(at, i, &comp_keep)?;
            cycle.extend(&path[1..]);
            cycle.push(j);
            at = j;
        }
        let back = self.shortest_nonempty(at, entry, &comp_keep)?;
        cycle.extend(&back[1..]);
        Some((entry, cycle))
    }

    /// A shortest path from `a` to `b` through states `keep` keeps (`[a]` when `a == b`).
    fn shortest(&self, a: u32, b: u32, keep: &impl Fn(u32) -> bool) -> Option<Vec<u32>> {
        if a == b {
            return Some(vec![a]);
        }
        self.bfs(a, b, keep)
    }

    /// A shortest path of at least one transition from `a` to `b`.
    fn shortest_nonempty(&self, a: u32, b: u32, keep: &impl Fn(u32) -> bool) -> Option<Vec<u32>> {
        self.bfs(a, b, keep)
    }

    fn bfs(&self, a: u32, b: u32, keep: &impl Fn(u32) -> bool) -> Option<Vec<u32>> {
        let mut parent: HashMap<u32, u32> = HashMap::new();
        let mut queue = VecDeque::from([a]);
        while let Some(i) = queue.pop_front() {
            for &j in self.graph.successors(i).unwrap_or(&[]) {
                if !keep(j) || parent.contains_key(&j) {
                    continue;
                }
                parent.insert(j, i);
                if j == b {
                    let mut path = vec![b];
                    let mut at = b;
                    while at != a || path.len() == 1 {
                        at = parent[&at];
                        path.push(at);
                        if at == a {
                            break;
                        }
                    }
                    path.reverse();
                    return Some(path);
                }
                queue.push_back(j);
            }
        }
        None
    }

    /// The states reachable from an initial state through states `keep` keeps, each with
    /// the state before it on a shortest such run (itself, for an initial state).
    fn reachable_within(&self, keep: impl Fn(u32) -> bool) -> Vec<Option<u32>> {
        let n = self.graph.len();
        let mut before = vec![None; n];
        let mut queue: VecDeque<u32> = (0..self.graph.initial as u32)
            .filter(|&i| keep(i))
            .collect();
        for &i in &queue {
            before[i as usize] = Some(i);
        }
        while let Some(i) = queue.pop_front() {
            for &j in self.graph.successors(i).unwrap_or(&[]) {
                if keep(j) && before[j as usize].is_none() {
                    before[j as usize] = Some(i);
                    queue.push_back(j);
                }
            }
        }
        before
    }
}

/// The shortest run within a region ([`Loops::reachable_within`]) to state `i` of it,
/// initial state first.
fn path_within(region: &[Option<u32>], i: u32) -> Vec<u32> {
    let mut path = vec![i];
    let mut at = i;
    while let Some(b) = region[at as usize].filter(|&b| b != at) {
        path.push(b);
        at = b;
    }
    path.reverse();
    path
}

/// Whether the explored graph has no loop (Kahn's topological sort takes every state).
pub(super) fn acyclic(graph: &Graph<SystemState>) -> bool {
    let n = graph.len();
    let mut indegree = vec![0u32; n];
    for i in 0..n as u32 {
        for &j in graph.successors(i).unwrap_or(&[]) {
            indegree[j as usize] += 1;
        }
    }
    let mut ready: Vec<u32> = (0..n as u32)
        .filter(|&i| indegree[i as usize] == 0)
        .collect();
    let mut taken = 0;
    while let Some(i) = ready.pop() {
        taken += 1;
        for &j in graph.successors(i).unwrap_or(&[]) {
            indegree[j as usize] -= 1;
            if indegree[j as usize] == 0 {
                ready.push(j);
            }
        }
    }
    taken == n
}

/// The strongly connected components of the graph restricted to states `keep` keeps
/// that hold a loop (more than one state, or a transition to itself).
fn components(graph: &Graph<SystemState>, keep: &impl Fn(u32) -> bool) -> Vec<Vec<u32>> {
    let n = graph.len() as u32;
    let mut g: DiGraph<u32, ()> = DiGraph::new();
    let mut node: HashMap<u32, NodeIndex> = HashMap::new();
    for i in (0..n).filter(|&i| keep(i)) {
        node.insert(i, g.add_node(i));
    }
    let mut self_loop = std::collections::HashSet::new();
    for (&i, &a) in &node {
        for &j in graph.successors(i).unwrap_or(&[]) {
            if let Some(&b) = node.get(&j) {
                g.add_edge(a, b, ());
                if i == j {
                    self_loop.insert(i);
                }
            }
        }
    }
    petgraph::algo::kosaraju_scc(&g)
        .into_iter()
        .map(|c| {
            let mut c: Vec<u32> = c.into_iter().map(|x| g[x]).collect();
            c.sort_unstable();
            c
        })
        .filter(|c| c.len() > 1 || self_loop.contains(&c[0]))
        .collect()
}

impl Cx<'_> {
    /// A failing finding whose run is `lasso`: `prefix` (by default the shortest run) to its
    /// entry, then the loop, which repeats for ever.
    fn lasso_finding(
        &self,
        check: &str,
        name: &str,
        span: Span,
        message: String,
        (entry, cycle): &Lasso,
        prefix: Option<Vec<u32>>,
    ) -> Finding {
        let mut path = prefix.unwrap_or_else(|| self.graph.path_to(*entry));
        let loop_from = path.len() - 1;
        path.extend(&cycle[1..]);
        let run: Run = self.run(&path, None);
        let mut f = self.finding(check, name, span, Status::Fail, message);
        f.counterexample = Some(self.counterexample_looping(&run, Some(loop_from)));
        f
    }
}
