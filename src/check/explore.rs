//! Breadth-first exploration of every reachable state, with parent links so that the path
//! to any state is a shortest one.
//!
//! States are identified by a 64-bit fingerprint (std's SipHash with fixed keys, so the same
//! on every run). Two distinct states with one fingerprint would be merged; with `n` states
//! the probability of that is about `n² / 2⁶⁵`, printed with the statistics.

use super::model::Model;
use crate::semantics::State;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::time::Instant;

/// A state's fingerprint.
pub fn fingerprint<S: Hash>(s: &S) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    s.hash(&mut h);
    h.finish()
}

/// Why exploration stopped before covering everything.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// `max_states` reached.
    States,
    /// `max_depth` reached (states deeper were not expanded).
    Depth,
    /// `--timeout` reached.
    Time,
}

/// The explored graph of a model (by default, the agent's).
pub struct Graph<S = State> {
    /// Every reached state, in BFS order.
    pub states: Vec<S>,
    /// For each state: its BFS parent and the index of the transition taken (none for
    /// initial states).
    pub parent: Vec<Option<(u32, u32)>>,
    /// For each state: its depth.
    pub depth: Vec<u32>,
    /// For each expanded state: the targets of its transitions, in order (`None` when the
    /// state was not expanded, or not fully, because a bound was hit).
    pub edges: Vec<Option<Vec<u32>>>,
    /// How many states are initial (the first ones).
    pub initial: usize,
    /// Transitions taken.
    pub transitions: usize,
    /// The bound that stopped the search, if any.
    pub bound: Option<Bound>,
    /// Seconds spent.
    pub seconds: f64,
}

/// Limits of one search.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Most distinct states.
    pub max_states: u64,
    /// Deepest state expanded.
    pub max_depth: u64,
    /// Wall-clock limit in seconds.
    pub timeout: Option<f64>,
}

/// Explores a model from every initial state, breadth first. `on_transition` sees every
/// transition (source index, its position among the source's transitions, its label) as it
/// is generated, so checks need not regenerate them.
pub fn explore<M: Model>(
    model: &M,
    limits: Limits,
    mut on_transition: impl FnMut(u32, u32, &M::Label),
    mut progress: impl FnMut(usize, u32, f64),
) -> Graph<M::State> {
    let start = Instant::now();
    let mut index: HashMap<u64, u32> = HashMap::new();
    let mut g = Graph {
        states: Vec::new(),
        parent: Vec::new(),
        depth: Vec::new(),
        edges: Vec::new(),
        initial: 0,
        transitions: 0,
        bound: None,
        seconds: 0.0,
    };
    for s in model.init_states() {
        let fp = fingerprint(&s);
        if let std::collections::hash_map::Entry::Vacant(e) = index.entry(fp) {
            e.insert(g.states.len() as u32);
            g.states.push(s);
            g.parent.push(None);
            g.depth.push(0);
            g.edges.push(None);
        }
    }
    g.initial = g.states.len();
    let mut next = 0usize;
    while next < g.states.len() {
        if next.is_multiple_of(4096) {
            let elapsed = start.elapsed().as_secs_f64();
            progress(g.states.len(), g.depth[next], elapsed);
            if limits.timeout.is_some_and(|t| elapsed > t) {
                g.bound = Some(Bound::Time);
                break;
            }
        }
        let d = g.depth[next];
        if u64::from(d) >= limits.max_depth {
            g.bound.get_or_insert(Bound::Depth);
            next += 1;
            continue;
        }
        let succ = model.next_states(&g.states[next]);
        let mut targets = Vec::with_capacity(succ.len());
        let mut cut = false;
        for (k, (label, target_state)) in succ.into_iter().enumerate() {
            on_transition(next as u32, k as u32, &label);
            g.transitions += 1;
            let fp = fingerprint(&target_state);
            let target = match index.get(&fp) {
                Some(&i) => i,
                None => {
                    if g.states.len() as u64 >= limits.max_states {
                        g.bound = Some(Bound::States);
                        cut = true;
                        continue;
                    }
                    let i = g.states.len() as u32;
                    index.insert(fp, i);
                    g.states.push(target_state);
                    g.parent.push(Some((next as u32, k as u32)));
                    g.depth.push(d + 1);
                    g.edges.push(None);
                    i
                }
            };
            targets.push(target);
        }
        // A state some of whose successors were cut off counts as not expanded: it must
        // not look like a state with no successors (a deadlock) or a finished run.
        g.edges[next] = (!cut).then_some(targets);
        next += 1;
    }
    g.seconds = start.elapsed().as_secs_f64();
    g
}

impl<S> Graph<S> {
    /// The shortest path from an initial state to `target`: state indices, initial first.
    pub fn path_to(&self, target: u32) -> Vec<u32> {
        let mut path = vec![target];
        let mut at = target;
        while let Some((p, _)) = self.parent[at as usize] {
            path.push(p);
            at = p;
        }
        path.reverse();
        path
    }

    /// The deepest depth reached.
    pub fn max_depth(&self) -> u32 {
        self.depth.iter().copied().max().unwrap_or(0)
    }

    /// Whether every reachable state was expanded.
    pub fn complete(&self) -> bool {
        self.bound.is_none()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counting modulo `n` by +1 or +2: every residue is reachable, and the shortest path
    /// to `k` takes `ceil(k / 2)` steps.
    struct Counter(u32);

    impl Model for Counter {
        type State = u32;
        type Label = u32;
        fn init_states(&self) -> Vec<u32> {
            vec![0]
        }
        fn next_states(&self, s: &u32) -> Vec<(u32, u32)> {
            vec![(1, (s + 1) % self.0), (2, (s + 2) % self.0)]
        }
    }

    fn unbounded() -> Limits {
        Limits {
            max_states: u64::MAX,
            max_depth: u64::MAX,
            timeout: None,
        }
    }

    #[test]
    fn any_model_is_explored_breadth_first_with_shortest_paths() {
        let mut labels = 0;
        let g = explore(
            &Counter(10),
            unbounded(),
            |_, _, _| labels += 1,
            |_, _, _| {},
        );
        assert!(g.complete());
        assert_eq!(g.states.len(), 10);
        assert_eq!((g.transitions, labels), (20, 20));
        for (i, s) in g.states.iter().enumerate() {
            let path = g.path_to(i as u32);
            assert_eq!(path.len() - 1, s.div_ceil(2) as usize, "state {s}");
            assert_eq!(g.depth[i] as usize, path.len() - 1);
        }
    }

    #[test]
    fn bounds_leave_the_graph_incomplete() {
        let limits = Limits {
            max_states: 4,
            ..unbounded()
        };
        let g = explore(&Counter(10), limits, |_, _, _| {}, |_, _, _| {});
        assert_eq!(g.states.len(), 4);
        assert_eq!(g.bound, Some(Bound::States));
        // A state whose successors were cut off is not taken as expanded.
        assert!(g.edges.iter().any(|e| e.is_none()));
        let limits = Limits {
            max_depth: 1,
            ..unbounded()
        };
        let g = explore(&Counter(10), limits, |_, _, _| {}, |_, _, _| {});
        assert_eq!(g.states.len(), 3);
        assert_eq!(g.bound, Some(Bound::Depth));
    }
}
