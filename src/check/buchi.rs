//! Büchi automata for LTL formulas: the property side of LTL model checking.
//!
//! A model satisfies a formula when no run of it is accepted by the automaton of the
//! formula's negation, so the search explores the product of the model's states with the
//! automaton's. For that product the automaton here has:
//!
//! * guarded edges: a [`Guard`] is a conjunction of literals over the letter's bits
//!   (`model::ltl`: bit `p` of a letter is proposition `p`);
//! * acceptance on states, one set (degeneralized);
//! * an initial state in which no letter has been read yet: a run on `w0 w1 w2 …` is
//!   `q0 = initial --w0--> q1 --w1--> q2 …`, so the model's initial state is read by the
//!   first step like every later one. A run is accepting iff it visits accepting states
//!   infinitely often.
//!
//! The translation ([`Buchi::from_ltl`]) is the tableau of Gerth, Peled, Vardi and Wolper
//! ("Simple on-the-fly automatic verification of linear temporal logic", 1995): the formula
//! in negation normal form is expanded into nodes, each a set of subformulas that must hold
//! now (`old`) and a set that must hold next (`next`); an edge enters a node under the
//! literals of its `old`; each `a U b` gives one acceptance set (the nodes that do not
//! promise `a U b` or that fulfil it with `b`). The generalized automaton is degeneralized
//! with a counter, states that cannot reach an accepting cycle are pruned, and edges and
//! states that say the same are merged. Everything is kept in ordered sets so that the
//! automaton, state numbers included, depends on the formula only.

use crate::model::ltl::Ltl;
use std::collections::{BTreeMap, BTreeSet, VecDeque};

/// A conjunction of literals: the propositions in `pos` true and those in `neg` false.
/// `Guard { pos: 0, neg: 0 }` matches every letter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Guard {
    /// The propositions (bits) that must be true.
    pub pos: u64,
    /// The propositions (bits) that must be false.
    pub neg: u64,
}

impl Guard {
    /// Whether `letter` satisfies every literal.
    pub fn matches(&self, letter: u64) -> bool {
        letter & self.pos == self.pos && letter & self.neg == 0
    }

    /// Whether every letter `self` matches is one `other` matches (`other` has no literal
    /// `self` lacks).
    fn implies(&self, other: &Guard) -> bool {
        self.pos & other.pos == other.pos && self.neg & other.neg == other.neg
    }

    /// `self | other` when it is again one guard because the two differ in one
    /// proposition only, true in one and false in the other: then it is the rest.
    fn resolve(&self, other: &Guard) -> Option<Guard> {
        let d = self.pos ^ other.pos;
        (d.count_ones() == 1 && self.neg ^ other.neg == d).then_some(Guard {
            pos: self.pos & !d,
            neg: self.neg & !d,
        })
    }
}

/// A state of a [`Buchi`] automaton.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BuchiState {
    /// Whether a run that passes here infinitely often is accepted.
    pub accepting: bool,
    /// The steps out of this state: one reads a letter its guard matches and goes to the
    /// state numbered by the second field.
    pub edges: Vec<(Guard, u32)>,
}

/// A Büchi automaton with guarded edges and accepting states; see the module doc for how
/// a run reads a word.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Buchi {
    /// The states; edges name them by index.
    pub states: Vec<BuchiState>,
    /// The state a run starts in, before the first letter.
    pub initial: u32,
}

impl Buchi {
    /// The automaton accepting exactly the words on which `f` holds.
    ///
    /// A translated automaton always has its initial state; when `f` is unsatisfiable that
    /// state has no edge. Propositions numbered 64 or more are false in every letter, as in
    /// [`Ltl::holds_on_lasso`].
    pub fn from_ltl(f: &Ltl) -> Buchi {
        Buchi::from_ltl_within(f, usize::MAX).unwrap_or(Buchi {
            states: Vec::new(),
            initial: 0,
        })
    }

    /// [`Buchi::from_ltl`], or `None` when the tableau would take more than `budget` steps
    /// (node splits and expansions): the translation is exponential in the formula, and a
    /// long one must be refused rather than take unbounded time and memory.
    pub fn from_ltl_within(f: &Ltl, budget: usize) -> Option<Buchi> {
        let mut closure = Closure::default();
        let root = closure.intern(f, true);
        let tableau = Tableau::expand(&closure, root, budget)?;
        Some(simplify(degeneralize(&closure, &tableau), 0))
    }

    /// Whether the automaton accepts the word `prefix · cycle^ω`: an accepting state on a
    /// cycle of the product of the word's positions (each with one successor) with the
    /// automaton's states, reachable from (position 0, initial state). Exact, in time
    /// linear in the product.
    ///
    /// `cycle` must not be empty: in a debug build that panics, in a release build the
    /// answer is `false`. Edges to states that do not exist are ignored.
    pub fn accepts_lasso(&self, prefix: &[u64], cycle: &[u64]) -> bool {
        debug_assert!(!cycle.is_empty(), "a lasso's cycle is not empty");
        let s = self.states.len();
        if cycle.is_empty() || self.initial as usize >= s {
            return false;
        }
        let word: Vec<u64> = prefix.iter().chain(cycle).copied().collect();
        let succ = |i: usize| {
            if i + 1 < word.len() {
                i + 1
            } else {
                prefix.len()
            }
        };
        // Product node `i * s + q`: in state `q`, about to read position `i`.
        let adj: Vec<Vec<u32>> = (0..word.len() * s)
            .map(|v| {
                let (i, q) = (v / s, v % s);
                self.states[q]
                    .edges
                    .iter()
                    .filter(|(g, t)| (*t as usize) < s && g.matches(word[i]))
                    .map(|&(_, t)| (succ(i) * s + t as usize) as u32)
                    .collect()
            })
            .collect();
        let good = accepting_cycles(&adj, |v| self.states[v % s].accepting);
        reachable(&adj, [self.initial as usize])
            .iter()
            .zip(good)
            .any(|(&r, g)| r && g)
    }

    /// The number of states.
    pub fn len(&self) -> usize {
        self.states.len()
    }

    /// Whether there is no state at all (never so for a translated automaton, which keeps
    /// its initial state even when it accepts nothing).
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }
}

/// A subformula of the negation normal form, its operands by index in the [`Closure`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Sub {
    True,
    False,
    /// Proposition `p` (below 64), true or negated.
    Lit(u32, bool),
    And(usize, usize),
    Or(usize, usize),
    Next(usize),
    Until(usize, usize),
    Release(usize, usize),
}

/// The subformulas of a formula's negation normal form, each once, so that the tableau's
/// sets are sets of indices.
#[derive(Default)]
struct Closure {
    subs: Vec<Sub>,
    index: BTreeMap<Sub, usize>,
}

impl Closure {
    /// The index of the negation normal form of `f` (`positive`) or of `!f`, with its
    /// subformulas interned first.
    fn intern(&mut self, f: &Ltl, positive: bool) -> usize {
        let sub = match (f, positive) {
            (Ltl::True, true) | (Ltl::False, false) => Sub::True,
            (Ltl::True, false) | (Ltl::False, true) => Sub::False,
            // No letter sets a bit beyond 63.
            (Ltl::Prop(p), _) if *p >= 64 => {
                if positive {
                    Sub::False
                } else {
                    Sub::True
                }
            }
            (Ltl::Prop(p), _) => Sub::Lit(*p, positive),
            (Ltl::Not(g), _) => return self.intern(g, !positive),
            (Ltl::Next(g), _) => Sub::Next(self.intern(g, positive)),
            (Ltl::And(a, b), true) | (Ltl::Or(a, b), false) => {
                Sub::And(self.intern(a, positive), self.intern(b, positive))
            }
            (Ltl::Or(a, b), true) | (Ltl::And(a, b), false) => {
                Sub::Or(self.intern(a, positive), self.intern(b, positive))
            }
            (Ltl::Until(a, b), true) | (Ltl::Release(a, b), false) => {
                Sub::Until(self.intern(a, positive), self.intern(b, positive))
            }
            (Ltl::Release(a, b), true) | (Ltl::Until(a, b), false) => {
                Sub::Release(self.intern(a, positive), self.intern(b, positive))
            }
        };
        if let Some(&i) = self.index.get(&sub) {
            return i;
        }
        self.subs.push(sub);
        self.index.insert(sub, self.subs.len() - 1);
        self.subs.len() - 1
    }
}

/// A node of the tableau still being expanded.
#[derive(Clone)]
struct Pending {
    /// The nodes with an edge into this one (0 is the initial node).
    incoming: BTreeSet<usize>,
    /// Subformulas still to process.
    new: BTreeSet<usize>,
    /// Subformulas processed: they hold in this node.
    old: BTreeSet<usize>,
    /// Subformulas that must hold in every successor.
    next: BTreeSet<usize>,
}

/// A fully expanded node.
struct Node {
    incoming: BTreeSet<usize>,
    old: BTreeSet<usize>,
}

/// The tableau's nodes: node 0 is the initial node (nothing read, no formula), every other
/// node has been expanded.
struct Tableau {
    nodes: Vec<Node>,
}

impl Tableau {
    /// GPVW's `expand`, with an explicit stack instead of recursion (a long formula would
    /// otherwise nest one call per node).
    fn expand(closure: &Closure, root: usize, budget: usize) -> Option<Tableau> {
        let init = Node {
            incoming: BTreeSet::new(),
            old: BTreeSet::new(),
        };
        let mut nodes = vec![init];
        // The expanded nodes by (old, next): a node equal to one of them only adds edges.
        let mut found: BTreeMap<(BTreeSet<usize>, BTreeSet<usize>), usize> = BTreeMap::new();
        let mut stack = vec![Pending {
            incoming: BTreeSet::from([0]),
            new: BTreeSet::from([root]),
            old: BTreeSet::new(),
            next: BTreeSet::new(),
        }];
        let mut steps = 0usize;
        while let Some(mut n) = stack.pop() {
            steps += 1;
            if steps > budget {
                return None;
            }
            if !expand_node(closure, &mut n, &mut stack) {
                continue;
            }
            let key = (n.old, n.next);
            if let Some(&id) = found.get(&key) {
                nodes[id].incoming.extend(n.incoming);
                continue;
            }
            let id = nodes.len();
            stack.push(Pending {
                incoming: BTreeSet::from([id]),
                new: key.1.clone(),
                old: BTreeSet::new(),
                next: BTreeSet::new(),
            });
            nodes.push(Node {
                incoming: n.incoming,
                old: key.0.clone(),
            });
            found.insert(key, id);
        }
        Some(Tableau { nodes })
    }
}

/// Processes `n.new` until it is empty, pushing the second half of every split onto
/// `stack`. Returns false when the node is contradictory (and dropped).
fn expand_node(closure: &Closure, n: &mut Pending, stack: &mut Vec<Pending>) -> bool {
    while let Some(f) = n.new.pop_first() {
        if !n.old.insert(f) {
            // Already processed in this node: its consequences are already here.
            continue;
        }
        match closure.subs[f] {
            Sub::True => {}
            Sub::False => return false,
            Sub::Lit(p, positive) => {
                let opposite = closure.index.get(&Sub::Lit(p, !positive));
                if opposite.is_some_and(|o| n.old.contains(o)) {
                    return false;
                }
            }
            Sub::And(a, b) => {
                n.new.extend([a, b]);
            }
            Sub::Next(a) => {
                n.next.insert(a);
            }
            // Each splits in two: the first case goes on here, the second on the stack.
            Sub::Or(a, b) => {
                let mut other = n.clone();
                other.new.insert(b);
                stack.push(other);
                n.new.insert(a);
            }
            // a U b: b now, or a now and a U b next.
            Sub::Until(a, b) => {
                let mut other = n.clone();
                other.new.insert(b);
                stack.push(other);
                n.new.insert(a);
                n.next.insert(f);
            }
            // a R b: a and b now, or b now and a R b next.
            Sub::Release(a, b) => {
                let mut other = n.clone();
                other.new.extend([a, b]);
                stack.push(other);
                n.new.insert(b);
                n.next.insert(f);
            }
        }
    }
    true
}

/// The literals of a node's `old`: the guard of every edge into it.
fn label(closure: &Closure, old: &BTreeSet<usize>) -> Guard {
    let mut g = Guard { pos: 0, neg: 0 };
    for &f in old {
        if let Sub::Lit(p, positive) = closure.subs[f] {
            if positive {
                g.pos |= 1 << p;
            } else {
                g.neg |= 1 << p;
            }
        }
    }
    g
}

/// The tableau as a generalized Büchi automaton (one acceptance set per `a U b`: the nodes
/// without it in `old` or with `b` in `old`), degeneralized with a counter.
///
/// State `(node, i)` has seen sets `0..i` since the counter last wrapped. Its successors'
/// counter is `i` moved past each set, in order from `i`, that `node` is in; when that moves
/// it past the last set, the state is accepting and the counter starts again at 0. A run is
/// then accepting iff the counter wraps infinitely often, that is iff it visits every set
/// infinitely often.
/// State 0 is `(initial node, 0)`.
fn degeneralize(closure: &Closure, tableau: &Tableau) -> Vec<BuchiState> {
    let untils: Vec<(usize, usize)> = (0..closure.subs.len())
        .filter_map(|u| match closure.subs[u] {
            Sub::Until(_, b) => Some((u, b)),
            _ => None,
        })
        .collect();
    let k = untils.len();
    let nodes = &tableau.nodes;
    // The initial node promises nothing, but it is left out of every set so that the
    // counter starts at 0 on the first real node.
    let in_set = |q: usize, j: usize| {
        let (u, b) = untils[j];
        q != 0 && (nodes[q].old.contains(&b) || !nodes[q].old.contains(&u))
    };
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    for (q, node) in nodes.iter().enumerate() {
        for &s in &node.incoming {
            out[s].push(q);
        }
    }
    let labels: Vec<Guard> = nodes.iter().map(|n| label(closure, &n.old)).collect();
    let mut ids: BTreeMap<(usize, usize), u32> = BTreeMap::from([((0, 0), 0)]);
    let mut queue = VecDeque::from([(0usize, 0usize)]);
    let mut states = Vec::new();
    while let Some((q, i)) = queue.pop_front() {
        let mut j = i;
        while j < k && in_set(q, j) {
            j += 1;
        }
        let accepting = j == k;
        let counter = if accepting { 0 } else { j };
        let mut edges = Vec::with_capacity(out[q].len());
        for &t in &out[q] {
            let next = ids.len() as u32;
            let id = *ids.entry((t, counter)).or_insert_with(|| {
                queue.push_back((t, counter));
                next
            });
            edges.push((labels[t], id));
        }
        states.push(BuchiState { accepting, edges });
    }
    states
}

/// Drops what no accepting run uses, merges edges and equivalent states, and numbers the
/// states breadth-first from the initial one (which becomes 0).
fn simplify(mut states: Vec<BuchiState>, initial: u32) -> Buchi {
    let adj = |states: &[BuchiState]| -> Vec<Vec<u32>> {
        states
            .iter()
            .map(|s| s.edges.iter().map(|&(_, t)| t).collect())
            .collect()
    };
    // States that can reach an accepting cycle; the initial state stays regardless.
    let good = accepting_cycles(&adj(&states), |q| states[q].accepting);
    let mut rev: Vec<Vec<u32>> = vec![Vec::new(); states.len()];
    for (q, s) in states.iter().enumerate() {
        for &(_, t) in &s.edges {
            rev[t as usize].push(q as u32);
        }
    }
    let live = reachable(&rev, (0..states.len()).filter(|&q| good[q]));
    for s in &mut states {
        s.edges
            .retain(|&(g, t)| live[t as usize] && g.pos & g.neg == 0);
        merge_edges(&mut s.edges);
    }
    let (mut states, mut initial) = renumber(&states, initial);
    // States with the same acceptance and the same edges accept the same words from there
    // on: keep one of each, until no two are alike.
    loop {
        // No run comes back to an initial state without incoming edges, so its acceptance
        // does not matter: make it that of a state with the same edges, to merge the two.
        let entered = states
            .iter()
            .any(|s| s.edges.iter().any(|e| e.1 == initial));
        let init = &states[initial as usize];
        let twin = (0..states.len())
            .find(|&q| q != initial as usize && states[q].edges == init.edges)
            .filter(|_| !entered);
        if let Some(twin) = twin {
            states[initial as usize].accepting = states[twin].accepting;
        }
        let mut seen: BTreeMap<&BuchiState, u32> = BTreeMap::new();
        let rep: Vec<u32> = (0..states.len())
            .map(|q| *seen.entry(&states[q]).or_insert(q as u32))
            .collect();
        if rep.iter().enumerate().all(|(q, &r)| q as u32 == r) {
            break;
        }
        for s in &mut states {
            for e in &mut s.edges {
                e.1 = rep[e.1 as usize];
            }
            merge_edges(&mut s.edges);
        }
        initial = rep[initial as usize];
        (states, initial) = renumber(&states, initial);
    }
    Buchi { states, initial }
}

/// The states reachable from `initial`, numbered breadth-first in edge order (`initial`
/// becomes 0), edges renumbered.
fn renumber(states: &[BuchiState], initial: u32) -> (Vec<BuchiState>, u32) {
    let mut ids: BTreeMap<u32, u32> = BTreeMap::from([(initial, 0)]);
    let mut order = vec![initial];
    let mut i = 0;
    while let Some(&q) = order.get(i) {
        i += 1;
        for &(_, t) in &states[q as usize].edges {
            if let std::collections::btree_map::Entry::Vacant(e) = ids.entry(t) {
                e.insert(order.len() as u32);
                order.push(t);
            }
        }
    }
    let out = order
        .iter()
        .map(|&q| {
            let s = &states[q as usize];
            let mut edges: Vec<(Guard, u32)> = s.edges.iter().map(|&(g, t)| (g, ids[&t])).collect();
            edges.sort_unstable_by_key(|&(g, t)| (t, g));
            BuchiState {
                accepting: s.accepting,
                edges,
            }
        })
        .collect();
    (out, 0)
}

/// Merges a state's edges to the same target: drops an edge whose guard implies another's,
/// and replaces two that differ only in the sign of one proposition by their common part.
fn merge_edges(edges: &mut Vec<(Guard, u32)>) {
    edges.sort_unstable_by_key(|&(g, t)| (t, g));
    edges.dedup();
    'again: loop {
        for i in 0..edges.len() {
            for j in 0..edges.len() {
                let ((gi, ti), (gj, tj)) = (edges[i], edges[j]);
                if i == j || ti != tj {
                    continue;
                }
                if gi.implies(&gj) {
                    edges.remove(i);
                    continue 'again;
                }
                if let Some(g) = gi.resolve(&gj) {
                    edges[i].0 = g;
                    edges.remove(j);
                    continue 'again;
                }
            }
        }
        break;
    }
    edges.sort_unstable_by_key(|&(g, t)| (t, g));
}

/// Which nodes of `adj` are reachable from `from`.
fn reachable(adj: &[Vec<u32>], from: impl IntoIterator<Item = usize>) -> Vec<bool> {
    let mut seen = vec![false; adj.len()];
    let mut stack: Vec<usize> = from.into_iter().collect();
    for &v in &stack {
        seen[v] = true;
    }
    while let Some(v) = stack.pop() {
        for &w in &adj[v] {
            if !seen[w as usize] {
                seen[w as usize] = true;
                stack.push(w as usize);
            }
        }
    }
    seen
}

/// Which nodes of `adj` are accepting and on a cycle (a strongly connected component with
/// an edge inside it): a run can come back to them forever.
fn accepting_cycles(adj: &[Vec<u32>], accepting: impl Fn(usize) -> bool) -> Vec<bool> {
    let comp = components(adj);
    let mut cyclic = vec![false; adj.len()];
    for (v, ws) in adj.iter().enumerate() {
        for &w in ws {
            if comp[w as usize] == comp[v] {
                cyclic[comp[v] as usize] = true;
            }
        }
    }
    (0..adj.len())
        .map(|v| accepting(v) && cyclic[comp[v] as usize])
        .collect()
}

/// The strongly connected components of `adj` (Kosaraju, iteratively so that long paths
/// do not overflow the stack): a component number per node.
fn components(adj: &[Vec<u32>]) -> Vec<u32> {
    let n = adj.len();
    let mut finished = Vec::with_capacity(n);
    let mut seen = vec![false; n];
    for root in 0..n {
        if seen[root] {
            continue;
        }
        seen[root] = true;
        let mut stack = vec![(root, 0usize)];
        while let Some(&(v, i)) = stack.last() {
            match adj[v].get(i) {
                Some(&w) => {
                    if let Some(top) = stack.last_mut() {
                        top.1 += 1;
                    }
                    if !seen[w as usize] {
                        seen[w as usize] = true;
                        stack.push((w as usize, 0));
                    }
                }
                None => {
                    finished.push(v);
                    stack.pop();
                }
            }
        }
    }
    let mut rev: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (v, ws) in adj.iter().enumerate() {
        for &w in ws {
            rev[w as usize].push(v as u32);
        }
    }
    const NONE: u32 = u32::MAX;
    let mut comp = vec![NONE; n];
    let mut next = 0;
    for &root in finished.iter().rev() {
        if comp[root] != NONE {
            continue;
        }
        comp[root] = next;
        let mut stack = vec![root];
        while let Some(v) = stack.pop() {
            for &w in &rev[v] {
                if comp[w as usize] == NONE {
                    comp[w as usize] = next;
                    stack.push(w as usize);
                }
            }
        }
        next += 1;
    }
    comp
}

#[cfg(test)]
mod tests {
    use super::{Buchi, BuchiState, Guard};
    use crate::model::ltl::Ltl;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    const P: u64 = 1;
    const Q: u64 = 2;

    fn p() -> Ltl {
        Ltl::Prop(0)
    }
    fn q() -> Ltl {
        Ltl::Prop(1)
    }

    #[test]
    fn guards_match_their_literals() {
        let g = Guard { pos: P, neg: Q };
        assert!(g.matches(P) && g.matches(P | 4));
        assert!(!g.matches(P | Q) && !g.matches(0));
        assert!(Guard { pos: 0, neg: 0 }.matches(u64::MAX));
        let (a, b) = (Guard { pos: P | Q, neg: 0 }, Guard { pos: P, neg: Q });
        assert_eq!(a.resolve(&b), Some(Guard { pos: P, neg: 0 }));
        assert_eq!(a.resolve(&Guard { pos: 0, neg: P | Q }), None);
        assert!(a.implies(&Guard { pos: P, neg: 0 }));
    }

    #[test]
    fn accepts_lasso_on_a_hand_made_automaton() {
        // [] <> p: a p-step goes to the accepting state, any other step to the other one.
        let step = |acc| BuchiState {
            accepting: acc,
            edges: vec![(Guard { pos: P, neg: 0 }, 1), (Guard { pos: 0, neg: P }, 0)],
        };
        let a = Buchi {
            states: vec![step(false), step(true)],
            initial: 0,
        };
        assert!(a.accepts_lasso(&[], &[0, P]));
        assert!(!a.accepts_lasso(&[P, P], &[0]));
        // Prefix letters are read before the cycle, not in it.
        assert!(!a.accepts_lasso(&[P], &[Q]));
        let none = Buchi {
            states: vec![],
            initial: 0,
        };
        assert!(!none.accepts_lasso(&[], &[P]));
    }

    /// The sizes of some common properties, to notice a translation that grows.
    #[test]
    fn small_automata_for_common_properties() {
        let size = |f: Ltl| Buchi::from_ltl(&f).len();
        assert_eq!(size(Ltl::until(p(), q())), 2);
        assert_eq!(size(Ltl::always(Ltl::eventually(p()))), 2);
        assert_eq!(size(Ltl::leads_to(p(), q())), 2);
        assert_eq!(size(Ltl::always(p())), 1);
        assert_eq!(size(Ltl::True), 1);
        let never = Buchi::from_ltl(&Ltl::and(p(), Ltl::not(p())));
        assert_eq!(never.len(), 1);
        assert!(never.states[0].edges.is_empty());
    }

    /// Two recurring obligations never met at once: the counter must carry what the first
    /// set saw over to the second.
    #[test]
    fn generalized_acceptance_needs_every_set() {
        let both = Ltl::and(
            Ltl::always(Ltl::eventually(p())),
            Ltl::always(Ltl::eventually(q())),
        );
        let a = Buchi::from_ltl(&both);
        assert!(a.accepts_lasso(&[], &[P, 0, Q]));
        assert!(a.accepts_lasso(&[Q], &[P | Q]));
        assert!(!a.accepts_lasso(&[Q, Q], &[P]));
        assert!(!Buchi::from_ltl(&Ltl::not(both)).accepts_lasso(&[], &[P, Q]));
    }

    #[test]
    fn translation_is_deterministic() {
        let f = Ltl::iff(
            Ltl::leads_to(p(), Ltl::weak_until(q(), Ltl::Prop(2))),
            Ltl::eventually(Ltl::always(Ltl::next(p()))),
        );
        assert_eq!(Buchi::from_ltl(&f), Buchi::from_ltl(&f.clone()));
    }

    #[test]
    fn propositions_at_the_end_of_a_letter() {
        let top = 1u64 << 63;
        let a = Buchi::from_ltl(&Ltl::eventually(Ltl::Prop(63)));
        assert!(a.accepts_lasso(&[0], &[top]));
        assert!(!a.accepts_lasso(&[0], &[!top]));
        // Beyond 64 bits a proposition is never true, as in the semantics.
        let beyond = Ltl::eventually(Ltl::Prop(64));
        assert!(!Buchi::from_ltl(&beyond).accepts_lasso(&[], &[u64::MAX]));
        assert!(Buchi::from_ltl(&Ltl::not(beyond)).accepts_lasso(&[], &[u64::MAX]));
    }

    /// Formulas over 3 propositions, depth at most 4, with every operator: the derived ones
    /// through their constructors, the core ones also raw (no constant folding).
    fn formula() -> impl Strategy<Value = Ltl> {
        // Constants mostly fold away: propositions are drawn more often.
        let leaf = prop_oneof![
            1 => Just(Ltl::True),
            1 => Just(Ltl::False),
            6 => (0u32..3).prop_map(Ltl::Prop),
        ];
        leaf.prop_recursive(4, 32, 2, |inner| {
            prop_oneof![
                (0..6u8, inner.clone()).prop_map(|(op, f)| match op {
                    0 => Ltl::not(f),
                    1 => Ltl::next(f),
                    2 => Ltl::always(f),
                    3 => Ltl::eventually(f),
                    4 => Ltl::Not(Box::new(f)),
                    _ => Ltl::Next(Box::new(f)),
                }),
                (0..12u8, inner.clone(), inner).prop_map(|(op, a, b)| {
                    let raw = |a, b| (Box::new(a), Box::new(b));
                    match op {
                        0 => Ltl::and(a, b),
                        1 => Ltl::or(a, b),
                        2 => Ltl::implies(a, b),
                        3 => Ltl::iff(a, b),
                        4 => Ltl::until(a, b),
                        5 => Ltl::release(a, b),
                        6 => Ltl::weak_until(a, b),
                        7 => Ltl::leads_to(a, b),
                        8 => {
                            let (a, b) = raw(a, b);
                            Ltl::And(a, b)
                        }
                        9 => {
                            let (a, b) = raw(a, b);
                            Ltl::Or(a, b)
                        }
                        10 => {
                            let (a, b) = raw(a, b);
                            Ltl::Until(a, b)
                        }
                        _ => {
                            let (a, b) = raw(a, b);
                            Ltl::Release(a, b)
                        }
                    }
                }),
            ]
        })
    }

    /// A few lassos: prefix of 0 to 3 letters, cycle of 1 to 3, letters over 3 bits.
    fn lassos() -> impl Strategy<Value = Vec<(Vec<u64>, Vec<u64>)>> {
        let letters = |n: std::ops::Range<usize>| prop::collection::vec(0u64..8, n);
        prop::collection::vec((letters(0..4), letters(1..4)), 1..8)
    }

    /// A fixed seed keeps runs reproducible; `PROPTEST_RNG_SEED` and `PROPTEST_CASES`
    /// still override it.
    fn config(cases: u32) -> Config {
        let mut c = Config::default();
        if matches!(c.rng_seed, RngSeed::Random) {
            c.rng_seed = RngSeed::Fixed(0xb0c1);
        }
        if std::env::var_os("PROPTEST_CASES").is_none() {
            c.cases = cases;
        }
        c.failure_persistence = None;
        c
    }

    proptest! {
        #![proptest_config(config(5000))]

        /// The automaton of `f` accepts a lasso iff `f` holds on it, and the automaton of
        /// `!f` iff it does not; the negation normal form means the same as `f`.
        #[test]
        fn buchi_agrees_with_the_semantics(f in formula(), words in lassos()) {
            let a = Buchi::from_ltl(&f);
            let not_a = Buchi::from_ltl(&Ltl::not(f.clone()));
            let nnf = f.nnf();
            for (prefix, cycle) in &words {
                let holds = f.holds_on_lasso(prefix, cycle);
                let word = format!("{prefix:?} ({cycle:?})^w");
                prop_assert_eq!(a.accepts_lasso(prefix, cycle), holds, "{}: {:?}", word, a);
                let not_holds = not_a.accepts_lasso(prefix, cycle);
                prop_assert_eq!(not_holds, !holds, "negation, {}: {:?}", word, not_a);
                prop_assert_eq!(nnf.holds_on_lasso(prefix, cycle), holds, "{}: {:?}", word, nnf);
            }
        }
    }
}
