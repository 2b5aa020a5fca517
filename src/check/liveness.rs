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
    /// contain a cycle; each sorted, components in order of their first state. Tarjan's
    /// algorithm with an explicit stack.
    fn cyclic_components(&self, keep: impl Fn(u32) -> bool) -> Vec<Vec<u32>> {
        const UNSEEN: u32 = u32::MAX;
        let n = self.graph.len();
        let succ = |i: u32| -> &[u32] { self.graph.successors(i).unwrap_or(&[]) };
        let mut index = vec![UNSEEN; n];
        let mut low = vec![0u32; n];
        let mut on_stack = vec![0u64; n.div_ceil(64)];
        let mut stack: Vec<u32> = Vec::new();
        let mut next = 0u32;
        let mut comps = Vec::new();
        // (state, position of the next successor to look at)
        let mut calls: Vec<(u32, usize)> = Vec::new();
        for root in 0..n as u32 {
            if index[root as usize] != UNSEEN || !keep(root) {
                continue;
            }
            calls.push((root, 0));
            while let Some(&mut (v, ref mut pos)) = calls.last_mut() {
                if *pos == 0 && index[v as usize] == UNSEEN {
                    index[v as usize] = next;
                    low[v as usize] = next;
                    next += 1;
                    stack.push(v);
                    set_bit(&mut on_stack, v, true);
                }
                let edges = succ(v);
                if let Some(&w) = edges.get(*pos) {
                    *pos += 1;
                    if !keep(w) {
                        continue;
                    }
                    if index[w as usize] == UNSEEN {
                        calls.push((w, 0));
                    } else if bit(&on_stack, w) {
                        low[v as usize] = low[v as usize].min(index[w as usize]);
                    }
                    continue;
                }
                calls.pop();
                if let Some(&(u, _)) = calls.last() {
                    low[u as usize] = low[u as usize].min(low[v as usize]);
                }
                if low[v as usize] == index[v as usize] {
                    let mut comp = Vec::new();
                    while let Some(w) = stack.pop() {
                        on_stack[w as usize / 64] &= !(1 << (w % 64));
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
