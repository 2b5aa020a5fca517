//! The checks a run that goes on forever decides: `livelock`, `request-not-completed` and
//! `eventually` properties. Each violation is a lasso (the shortest run to a loop, then the
//! loop), found on the strongly connected components of the explored graph.

use super::checker::Checker;
use super::safety::Prop;
use super::search::{bit, set_bit};
use crate::findings::{Finding, Status};
use std::collections::{BTreeMap, HashMap, VecDeque};

impl Checker<'_> {
    pub(super) fn liveness(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let span = self.project.manifest.agent.plans.written.span;
        let n = self.graph.len();
        let loops = self.cyclic_components(|_| true);
        let livelock = loops
            .iter()
            .min_by_key(|c| c.iter().map(|&i| self.graph.depth(i)).min());
        match livelock {
            Some(comp) => {
                let (entry, cycle) = self.lasso_within(comp, |_| true);
                let mut f = self.finding(
                    "livelock",
                    "agent",
                    span,
                    Status::Fail,
                    "the agent can run forever without becoming idle".into(),
                );
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(entry), None, &cycle));
                out.push(f);
            }
            _ => out.push(self.finding(
                "livelock",
                "agent",
                span,
                self.held(),
                "every run ends with the agent idle".into(),
            )),
        }
        // A request pending in every state of a loop is never completed on that run.
        let mut starved: Option<(u8, &Vec<u32>)> = None;
        for comp in &loops {
            let pending = comp
                .iter()
                .fold(u64::MAX, |acc, &i| acc & self.facts.pending(i));
            if pending != 0 {
                starved = Some((pending.trailing_zeros() as u8, comp));
                break;
            }
        }
        match starved {
            Some((r, comp)) => {
                let (entry, cycle) = self.lasso_within(comp, |_| true);
                let goal = &self.agent.sem.requests[r as usize];
                let mut f = self.finding(
                    "request-not-completed",
                    &goal.to_string(),
                    span,
                    Status::Fail,
                    format!("the request !{goal} can stay pending forever"),
                );
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(entry), None, &cycle));
                out.push(f);
            }
            None => out.push(self.finding(
                "request-not-completed",
                "all",
                span,
                self.held(),
                format!(
                    "every request ends (completed or reported as a goal failure) on {}",
                    super::runs::ONE_AGENT_RUNS
                ),
            )),
        }
        use crate::syntax::manifest::PropertyKind;
        let eventually = props.iter().filter(|p| p.kind == PropertyKind::Eventually);
        for (p, bad) in eventually.zip(&self.facts.bad) {
            let bad = |i: u32| bit(bad, i);
            // States reachable from an initial state through states where the property
            // never held.
            let mut seen = vec![0u64; n.div_ceil(64)];
            let mut queue: VecDeque<u32> =
                (0..self.graph.initial as u32).filter(|&i| bad(i)).collect();
            queue.iter().for_each(|&i| set_bit(&mut seen, i, true));
            let mut parent: HashMap<u32, u32> = HashMap::new();
            while let Some(i) = queue.pop_front() {
                for &j in self.graph.successors(i).into_iter().flatten() {
                    if bad(j) && !bit(&seen, j) {
                        set_bit(&mut seen, j, true);
                        parent.insert(j, i);
                        queue.push_back(j);
                    }
                }
            }
            let path_in = |target: u32| {
                let mut path = vec![target];
                let mut at = target;
                while let Some(&p) = parent.get(&at) {
                    path.push(p);
                    at = p;
                }
                path.reverse();
                path
            };
            // A run ends where nothing can happen, and where the agent is idle: the user
            // may stop asking at any point (`[requests] max` is a bound, SPEC §1).
            let terminal = (0..n as u32).find(|&i| {
                bit(&seen, i)
                    && (self.graph.successors(i).is_some_and(|e| e.is_empty())
                        || bit(&self.facts.idle, i))
            });
            let loop_comp = self.cyclic_components(|i| bit(&seen, i)).into_iter().next();
            let message = format!("`{}` may never hold", p.name);
            if let Some(t) = terminal {
                let mut f = self.finding(
                    "property",
                    &p.name,
                    p.span,
                    Status::Fail,
                    format!("{message}: a run ends without it"),
                );
                f.counterexample = Some(self.counterexample(&path_in(t), None, &[]));
                out.push(f);
            } else if let Some(comp) = loop_comp {
                let (entry, cycle) = self.lasso_within(&comp, |i| bit(&seen, i));
                let mut f = self.finding(
                    "property",
                    &p.name,
                    p.span,
                    Status::Fail,
                    format!("{message}: a run loops forever without it"),
                );
                f.counterexample = Some(self.counterexample(&path_in(entry), None, &cycle));
                out.push(f);
            } else {
                out.push(self.finding(
                    "property",
                    &p.name,
                    p.span,
                    self.held(),
                    format!(
                        "`{}` eventually holds on {}",
                        p.name,
                        super::runs::ONE_AGENT_RUNS
                    ),
                ));
            }
        }
    }

    /// The strongly connected components, among the states where `keep` holds, that
    /// contain a cycle; each sorted, components in order of their first state.
    fn cyclic_components(&self, keep: impl Fn(u32) -> bool) -> Vec<Vec<u32>> {
        let succ = |i: u32| -> &[u32] { self.graph.successors(i).unwrap_or(&[]) };
        cyclic_components(self.graph.len(), &succ, self.graph.entered_back(), keep)
    }

    /// The shallowest state of a loop, and a cycle through it (state indices, ending back at
    /// the entry), staying inside the component and among the states where `keep` holds.
    fn lasso_within(&self, comp: &[u32], keep: impl Fn(u32) -> bool) -> (u32, Vec<u32>) {
        let entry = *comp
            .iter()
            .min_by_key(|&&i| (self.graph.depth(i), i))
            .expect("a component has a state");
        let member = |j: u32| comp.binary_search(&j).is_ok() && keep(j);
        // Breadth-first from the entry back to itself inside the component.
        let mut parent: BTreeMap<u32, u32> = BTreeMap::new();
        let mut queue = VecDeque::from([entry]);
        let mut closing = None;
        'bfs: while let Some(i) = queue.pop_front() {
            for &j in self.graph.successors(i).into_iter().flatten() {
                if !member(j) {
                    continue;
                }
                if j == entry {
                    closing = Some(i);
                    break 'bfs;
                }
                if let std::collections::btree_map::Entry::Vacant(e) = parent.entry(j) {
                    e.insert(i);
                    queue.push_back(j);
                }
            }
        }
        let mut cycle = vec![entry];
        let mut at = closing.unwrap_or(entry);
        while at != entry {
            cycle.push(at);
            at = parent[&at];
        }
        cycle.push(entry);
        // Built backwards from the closing state: entry, ..., entry in run order.
        cycle.reverse();
        (entry, cycle)
    }
}

/// The strongly connected components of a graph of `n` states, among those where `keep`
/// holds, that contain a cycle; each sorted, components in order of their first state.
///
/// Tarjan's search gives every state it visits two numbers; on graphs of millions of
/// states, most often without a cycle, that was most of the checks after the search. So it
/// runs only on the states [`cycle_candidates`] keeps, narrowed until they stop shrinking,
/// and numbers them among themselves. `entered`, when known, holds every state that an
/// edge from a state numbered no lower enters ([`Graph::entered_back`]): the first pass
/// then begins from them ([`seeded_candidates`]).
///
/// [`Graph::entered_back`]: super::explore::Graph::entered_back
fn cyclic_components<'g>(
    n: usize,
    succ: &impl Fn(u32) -> &'g [u32],
    entered: Option<&[u64]>,
    keep: impl Fn(u32) -> bool,
) -> Vec<Vec<u32>> {
    let first = match entered {
        Some(entered) => seeded_candidates(n, succ, entered),
        None => cycle_candidates(succ, &all_of(n), true),
    };
    match first.and_then(|c| narrowed(succ, c, n, true)) {
        Some(within) => tarjan(succ, &within, keep),
        None => Vec::new(),
    }
}

/// A bit set of the states of a graph of `n` states that holds every state on a cycle
/// ([`cycle_candidates`], narrowed until a pass removes little); `None` when there is no
/// cycle. Without `self_loops`, a cycle of one state and its loop is not counted: the
/// states outside the set are then alone in their component, with or without a loop.
pub(super) fn on_cycles<'g>(
    n: usize,
    succ: &impl Fn(u32) -> &'g [u32],
    self_loops: bool,
) -> Option<Vec<u64>> {
    narrowed(succ, all_of(n), n, self_loops)
}

/// `within` (a bit set of every state on a cycle, out of `count` states before its pass)
/// narrowed by [`cycle_candidates`] until a pass removes little; `None` when a pass finds
/// no cycle.
fn narrowed<'g>(
    succ: &impl Fn(u32) -> &'g [u32],
    mut within: Vec<u64>,
    mut count: usize,
    self_loops: bool,
) -> Option<Vec<u64>> {
    loop {
        let c = cycle_candidates(succ, &within, self_loops)?;
        let left: usize = c.iter().map(|w| w.count_ones() as usize).sum();
        within = c;
        // Each pass costs a look at every edge among the candidates: stop when one
        // removes little.
        if left + left / 8 >= count {
            return Some(within);
        }
        count = left;
    }
}

/// The bit set of the states `0..n`.
pub(super) fn all_of(n: usize) -> Vec<u64> {
    let mut set = vec![u64::MAX; n.div_ceil(64)];
    if !n.is_multiple_of(64) {
        if let Some(last) = set.last_mut() {
            *last = (1 << (n % 64)) - 1;
        }
    }
    set
}

/// The states of `within` (a bit set) that may lie on a cycle among them, as a bit set;
/// `None` when none does. States are numbered, and a cycle has an edge to a state numbered
/// no higher than its source (lower, for a cycle of several states): each state of the
/// cycle reaches the source of such an edge and is reached from its target. Two passes
/// over the edges find both. Without `self_loops`, loops from a state to itself are not
/// counted as cycles.
fn cycle_candidates<'g>(
    succ: &impl Fn(u32) -> &'g [u32],
    within: &[u64],
    self_loops: bool,
) -> Option<Vec<u64>> {
    let set = |v: &mut [u64], i: u32| v[i as usize / 64] |= 1 << (i % 64);
    // Backwards: the states that reach a backward edge's source (a later successor was
    // decided first; an earlier one makes the edge backward). The targets start `from`.
    let mut reaches = vec![0u64; within.len()];
    let mut from = vec![0u64; within.len()];
    let mut any = false;
    for i in members(within).rev() {
        let mut r = false;
        for &w in succ(i).iter().filter(|&&w| bit(within, w)) {
            if w < i || (w == i && self_loops) {
                r = true;
                set(&mut from, w);
            } else {
                r |= bit(&reaches, w);
            }
        }
        if r {
            any = true;
            set(&mut reaches, i);
        }
    }
    if !any {
        return None;
    }
    // Forwards: the states reached from a backward edge's target (a target earlier than
    // its source is in `from` from the start).
    for i in members(within) {
        if bit(&from, i) {
            for &w in succ(i).iter().filter(|&&w| bit(within, w)) {
                set(&mut from, w);
            }
        }
    }
    for (f, r) in from.iter_mut().zip(&reaches) {
        *f &= r;
    }
    Some(from)
}

/// [`cycle_candidates`] of every state of a graph of `n` states, self-loops counted, when
/// `entered` already holds the targets of the backward edges (and perhaps other states):
/// the states reached from them first, then among those the states that reach a backward
/// edge's source. Every state of a cycle is in both, and the first pass of the 5-cup
/// kitchen then looks at 7.6 M lists instead of 13.5 M. `None` when there is no cycle.
fn seeded_candidates<'g>(
    n: usize,
    succ: &impl Fn(u32) -> &'g [u32],
    entered: &[u64],
) -> Option<Vec<u64>> {
    let set = |v: &mut [u64], i: u32| v[i as usize / 64] |= 1 << (i % 64);
    let mut from = all_of(n);
    for (f, e) in from
        .iter_mut()
        .zip(entered.iter().chain(std::iter::repeat(&0)))
    {
        *f &= e;
    }
    for i in 0..n as u32 {
        if bit(&from, i) {
            for &w in succ(i) {
                set(&mut from, w);
            }
        }
    }
    let mut reaches = vec![0u64; from.len()];
    let mut any = false;
    for i in members(&from).rev() {
        let mut r = false;
        for &w in succ(i).iter().filter(|&&w| bit(&from, w)) {
            r |= w <= i || bit(&reaches, w);
        }
        if r {
            any = true;
            set(&mut reaches, i);
        }
    }
    any.then_some(reaches)
}

/// The members of a bit set, in increasing order (reversible).
fn members(set: &[u64]) -> impl DoubleEndedIterator<Item = u32> + '_ {
    set.iter()
        .enumerate()
        .filter(|(_, &w)| w != 0)
        .flat_map(|(k, &w)| Bits(w).map(move |b| k as u32 * 64 + b))
}

/// The set bits of a word, lowest first (reversible).
struct Bits(u64);

impl Iterator for Bits {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        let b = self.0.trailing_zeros();
        (b < 64).then(|| {
            self.0 &= self.0 - 1;
            b
        })
    }
}

impl DoubleEndedIterator for Bits {
    fn next_back(&mut self) -> Option<u32> {
        (self.0 != 0).then(|| {
            let b = 63 - self.0.leading_zeros();
            self.0 &= !(1 << b);
            b
        })
    }
}

/// The strongly connected components among the states of `within` (a bit set) where
/// `keep` holds that contain a cycle; each sorted, components in order of their first
/// state. Tarjan's algorithm with an explicit stack; its numbers are kept per member of
/// `within`, by rank.
fn tarjan<'g>(
    succ: &impl Fn(u32) -> &'g [u32],
    within: &[u64],
    keep: impl Fn(u32) -> bool,
) -> Vec<Vec<u32>> {
    const UNSEEN: u32 = u32::MAX;
    let mut before = Vec::with_capacity(within.len());
    let mut m = 0u32;
    for w in within {
        before.push(m);
        m += w.count_ones();
    }
    let rank = |i: u32| {
        let (k, b) = (i as usize / 64, i % 64);
        (before[k] + (within[k] & ((1u64 << b) - 1)).count_ones()) as usize
    };
    let keep = |i: u32| bit(within, i) && keep(i);
    let mut index = vec![UNSEEN; m as usize];
    let mut low = vec![0u32; m as usize];
    let mut on_stack = vec![0u64; (m as usize).div_ceil(64)];
    let mut stack: Vec<u32> = Vec::new();
    let mut next = 0u32;
    let mut comps = Vec::new();
    // (state, position of the next successor to look at)
    let mut calls: Vec<(u32, usize)> = Vec::new();
    for root in members(within) {
        if index[rank(root)] != UNSEEN || !keep(root) {
            continue;
        }
        calls.push((root, 0));
        while let Some(&mut (v, ref mut pos)) = calls.last_mut() {
            let rv = rank(v);
            if *pos == 0 && index[rv] == UNSEEN {
                index[rv] = next;
                low[rv] = next;
                next += 1;
                stack.push(v);
                set_bit(&mut on_stack, rv as u32, true);
            }
            let edges = succ(v);
            if let Some(&w) = edges.get(*pos) {
                *pos += 1;
                if !keep(w) {
                    continue;
                }
                let rw = rank(w);
                if index[rw] == UNSEEN {
                    calls.push((w, 0));
                } else if bit(&on_stack, rw as u32) {
                    low[rv] = low[rv].min(index[rw]);
                }
                continue;
            }
            calls.pop();
            if let Some(&(u, _)) = calls.last() {
                let ru = rank(u);
                low[ru] = low[ru].min(low[rv]);
            }
            if low[rv] == index[rv] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    let rw = rank(w);
                    on_stack[rw / 64] &= !(1 << (rw % 64));
                    comp.push(w);
                    if w == v {
                        break;
                    }
                }
                let cyclic = comp.len() > 1 || succ(v).contains(&v);
                if cyclic {
                    comp.sort();
                    comps.push(comp);
                }
            }
        }
    }
    comps.sort();
    comps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_candidates_keep_every_cyclic_component() {
        // Random graphs, some acyclic in their numbering, some not: the search on the
        // candidates finds what the search on every state finds.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |k: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % k
        };
        let mut cyclic = 0;
        for round in 0..1000 {
            // Up to several words of bits.
            let n = 1 + next(200) as usize;
            let back = next(4) == 0;
            let lists: Vec<Vec<u32>> = (0..n as u32)
                .map(|i| {
                    (0..next(4))
                        .map(|_| next(n as u64) as u32)
                        .filter(|&w| back || w > i)
                        .collect()
                })
                .collect();
            let succ = |i: u32| -> &[u32] { &lists[i as usize] };
            let mask = next(1 << 20);
            let keep = |i: u32| round % 2 == 0 || mask >> (i % 20) & 1 == 1;
            let every = all_of(n);
            let all = tarjan(&succ, &every, keep);
            let reduced = cyclic_components(n, &succ, None, keep);
            assert_eq!(reduced, all, "{lists:?}");
            // Beginning from the states edges enter backwards, as the search records them
            // (and a few more, as edges dropped since may leave): the same components.
            let mut entered = vec![0u64; n.div_ceil(64)];
            for (i, list) in lists.iter().enumerate() {
                for &w in list.iter().filter(|&&w| w as usize <= i || next(50) == 0) {
                    entered[w as usize / 64] |= 1 << (w % 64);
                }
            }
            let seeded = cyclic_components(n, &succ, Some(&entered), keep);
            assert_eq!(seeded, all, "{lists:?}");
            if let Some(first) = seeded_candidates(n, &succ, &entered) {
                assert!(all.iter().flatten().all(|&i| bit(&first, i)), "{lists:?}");
            } else {
                assert!(tarjan(&succ, &every, |_| true).is_empty(), "{lists:?}");
            }
            // Without self-loops, the set still holds every component of several states.
            let several = on_cycles(n, &succ, false);
            for comp in tarjan(&succ, &every, |_| true) {
                if comp.len() > 1 {
                    let set = several.as_ref().expect("a cycle of several states");
                    assert!(comp.iter().all(|&i| bit(set, i)), "{lists:?}");
                }
            }
            cyclic += usize::from(!all.is_empty());
            if !back {
                assert!(cycle_candidates(&succ, &every, true).is_none(), "{lists:?}");
            }
        }
        assert!(cyclic > 20, "{cyclic} graphs with a cycle");
    }
}
