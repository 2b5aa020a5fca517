//! The `deadlock` of each agent among several: a reachable state where the agent is not
//! done and no run from there lets it take a step again, found by a backward search over
//! the explored graph that follows each agent through the renamings its states are
//! stored under (symmetry over instances).

use super::{Cx, Interleavings, Move, Run};
use crate::check::explore::{explore_with, Graph, Limits, Options};
use crate::check::por::PartialOrder;
use crate::check::symmetry::{AgentPerm, Instances};
use crate::findings::{Finding, Status};
use crate::model::project::Project;
use crate::semantics::{System, SystemState};
use crate::syntax::Diagnostic;

/// Who moves in the search: per stored state, the agents not done there; per transition
/// followed, in order from each state, its agent and the renaming to the canonical member
/// of its target (see [`Move`]); per fingerprint, the renaming of the member the search
/// stored (the first one found).
#[derive(Default)]
pub(super) struct Steps {
    moves: Vec<Vec<(u8, Option<AgentPerm>)>>,
    stored_canon: std::collections::HashMap<u64, AgentPerm>,
}

/// Records the busy agents of stored state `i`.
pub(super) fn record_busy(busy: &mut Vec<u64>, i: u32, bits: u64) {
    let i = i as usize;
    if busy.len() <= i {
        busy.resize(i + 1, 0);
    }
    busy[i] = bits;
}

impl Steps {
    pub(super) fn transition(&mut self, src: u32, label: &Move, fp: u64) {
        let at = src as usize;
        if self.moves.len() <= at {
            self.moves.resize(at + 1, Vec::new());
        }
        self.moves[at].push((label.agent, label.canon.clone()));
        if let Some(c) = &label.canon {
            self.stored_canon.entry(fp).or_insert_with(|| c.clone());
        }
    }

    /// [`stuck_forever`] on the explored graph, whose states have `busy` agents.
    pub(super) fn stuck_forever(
        mut self,
        graph: &Graph<SystemState>,
        mut busy: Vec<u64>,
        system: &System,
        instances: Option<&Instances>,
    ) -> Vec<u64> {
        let n = graph.len();
        busy.resize(n, 0);
        self.moves.resize(n, Vec::new());
        // The renaming each stored state's member was stored under (an initial state's:
        // the first initial state of its class).
        let canon_of: Vec<Option<AgentPerm>> = match instances {
            None => vec![None; n],
            Some(inst) => {
                let mut init: std::collections::HashMap<u64, AgentPerm> = Default::default();
                for s in system.initial_states() {
                    let (fp, perm) = inst.canonical_renaming(&s);
                    init.entry(fp).or_insert(perm);
                }
                (0..n as u32)
                    .map(|i| {
                        let fp = graph.fingerprint(i);
                        init.get(&fp)
                            .or_else(|| self.stored_canon.get(&fp))
                            .cloned()
                    })
                    .collect()
            }
        };
        stuck_forever(graph, &busy, &self.moves, &canon_of, system.names().len())
    }
}

/// Busy agents of a state, one bit each: not idle, or mail waiting.
pub(super) fn busy_agents(s: &SystemState) -> u64 {
    (0..s.agents.len())
        .filter(|&k| !s.agents[k].is_idle() || !s.mail[k].is_empty())
        .fold(0, |b, k| b | 1 << k)
}

/// Every state of the search of `projects` (its member stored), with the agents stuck
/// for ever there, one bit each: what the `deadlock` findings are made of, for the tests
/// to compare with each state's continuations ([`stuck_from`]).
#[doc(hidden)]
pub fn stuck_states(
    projects: &[Project],
    symmetry: bool,
    partial_order: bool,
) -> Result<Vec<(SystemState, u64)>, Vec<Diagnostic>> {
    let system = System::new(projects)?;
    let instances = symmetry.then(|| Instances::new(&system, &[]));
    let active = instances.as_ref().filter(|i| !i.is_empty());
    let model = Interleavings {
        system: &system,
        partial_order: partial_order.then(|| PartialOrder::new(&system, std::iter::empty())),
        instances: active,
    };
    let mut steps = Steps::default();
    let mut busy = Vec::new();
    let opts = Options {
        threads: 1,
        keep_edges: true,
        ..Options::default()
    };
    let graph: Graph<SystemState> = explore_with(
        &model,
        Limits {
            max_states: 1_000_000,
            max_depth: 100_000,
            timeout: None,
        },
        &opts,
        |s, _| busy_agents(s),
        |i, _, bits| record_busy(&mut busy, i, bits),
        |src, _, label, fp| steps.transition(src, label, fp),
        |_, _, _| {},
    );
    let stuck = steps.stuck_forever(&graph, busy, &system, active);
    Ok((0..graph.len() as u32)
        .filter_map(|i| Some((graph.state(&model, i)?, stuck[i as usize])))
        .collect())
}

/// Per stored state, the agents (in the numbering of the member stored, one bit each)
/// that are not done there and can never take a step again: no run from there reaches a
/// state where they take one. `canon_of` gives, per stored state, the renaming its member
/// was stored under (under symmetry: the agent that is `x` in a transition's target is
/// `canon_of[j]⁻¹(canon[x])` in the member stored for `j`). A state the search did not
/// expand completely may lead anywhere.
fn stuck_forever(
    graph: &Graph<SystemState>,
    busy: &[u64],
    moves: &[Vec<(u8, Option<AgentPerm>)>],
    canon_of: &[Option<AgentPerm>],
    agents: usize,
) -> Vec<u64> {
    let n = graph.len();
    // Which agent of the stored member of a transition's target each agent of the source
    // becomes.
    let into = |j: u32, canon: &Option<AgentPerm>, x: usize| -> usize {
        match (canon, &canon_of[j as usize]) {
            (Some(c), Some(stored)) => {
                let slot = c[x];
                stored.iter().position(|&y| y == slot).unwrap_or(x)
            }
            _ => x,
        }
    };
    // Predecessor pairs `(source, agent there)` of each `(target, agent there)`, as one
    // array sliced by target and agent.
    let pair = |i: u32, x: usize| i as usize * agents + x;
    let mut start = vec![0usize; n * agents + 1];
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for i in 0..n as u32 {
        let Some(succ) = graph.successors(i) else {
            continue;
        };
        for (e, &j) in succ.iter().enumerate() {
            let canon = moves[i as usize]
                .get(e)
                .and_then(|(_, c)| c.as_ref())
                .cloned();
            for x in 0..agents {
                edges.push((pair(j, into(j, &canon, x)), pair(i, x)));
            }
        }
    }
    for &(to, _) in &edges {
        start[to + 1] += 1;
    }
    for p in 0..n * agents {
        start[p + 1] += start[p];
    }
    let mut fill = start.clone();
    let mut preds = vec![0usize; edges.len()];
    for &(to, from) in &edges {
        preds[fill[to]] = from;
        fill[to] += 1;
    }
    // The pairs from which the agent takes a step on some run.
    let mut may_move = vec![false; n * agents];
    let mut queue = Vec::new();
    for i in 0..n as u32 {
        let expanded = graph.successors(i).is_some();
        for x in 0..agents {
            let moves_here = moves[i as usize].iter().any(|(a, _)| *a as usize == x);
            if moves_here || !expanded {
                may_move[pair(i, x)] = true;
                queue.push(pair(i, x));
            }
        }
    }
    while let Some(p) = queue.pop() {
        for &q in &preds[start[p]..start[p + 1]] {
            if !may_move[q] {
                may_move[q] = true;
                queue.push(q);
            }
        }
    }
    (0..n as u32)
        .map(|i| {
            (0..agents)
                .filter(|&x| busy[i as usize] >> x & 1 == 1 && !may_move[pair(i, x)])
                .fold(0, |b, x| b | 1 << x)
        })
        .collect()
}

/// The first stored state (in search order, so at least depth) where each agent is stuck
/// for ever ([`stuck_forever`]).
pub(super) fn first_stuck(stuck: &[u64], agents: usize) -> Vec<Option<u32>> {
    (0..agents)
        .map(|x| (0..stuck.len() as u32).find(|&i| stuck[i as usize] >> x & 1 == 1))
        .collect()
}

/// Most states [`stuck_from`] looks at.
const MAX_STUCK_STATES: usize = 1 << 20;

/// Whether agent `k`, not done in `s`, can never take a step again: no run from `s`
/// reaches a state where it takes one. `None` when more than `MAX_STUCK_STATES` states
/// would have to be looked at to tell.
pub fn stuck_from(system: &System, s: &SystemState, k: usize) -> Option<bool> {
    use std::collections::HashSet;
    let busy = !s.agents[k].is_idle() || !s.mail[k].is_empty();
    if !busy {
        return Some(false);
    }
    let mut seen: HashSet<u64> = HashSet::from([crate::check::explore::fingerprint(s)]);
    let mut frontier = vec![s.clone()];
    while let Some(st) = frontier.pop() {
        for (label, t) in system.successors(&st) {
            if label.agent as usize == k {
                return Some(false);
            }
            if seen.insert(crate::check::explore::fingerprint(&t)) {
                if seen.len() > MAX_STUCK_STATES {
                    return None;
                }
                frontier.push(t);
            }
        }
    }
    Some(true)
}

impl Cx<'_> {
    /// The `deadlock` findings, one per agent, located where the agent is named: for an
    /// agent `stuck` names a first state of
    /// (in the numbering of the member stored), a run to it, gone on to show what becomes
    /// of the agent; under symmetry, each instance of its agent is stuck on a renamed run.
    pub(super) fn deadlocks(&self, out: &mut Vec<Finding>, stuck: &[Option<u32>], held: Status) {
        let names = self.system.names();
        // Per agent: the depth of its first stuck state and the run there.
        let mut found: Vec<Option<(u32, Run, usize)>> = (0..names.len()).map(|_| None).collect();
        for (x, first) in stuck.iter().enumerate() {
            let Some(i) = *first else { continue };
            let (run, prefix) = self.gone_on(i);
            if run.states.len() <= prefix {
                continue;
            }
            let mut runs = vec![(x, run, prefix)];
            if let Some(inst) = self.model.instances {
                let base = &runs[0].1;
                let mut more = Vec::new();
                for perm in inst.images(&[x as u8]).into_iter().skip(1) {
                    if let Some((states, steps)) =
                        inst.rename_run(self.system, &base.states, &base.steps, &perm)
                    {
                        more.push((perm[x] as usize, Run { states, steps }, prefix));
                    }
                }
                runs.extend(more);
            }
            let depth = self.graph.depth(i);
            for (k, run, prefix) in runs {
                if found[k].as_ref().is_none_or(|(d, ..)| depth < *d) {
                    found[k] = Some((depth, run, prefix));
                }
            }
        }
        for (k, f) in found.into_iter().enumerate() {
            let name = &names[k];
            // Where the agent is named.
            let place = self.projects[k].declared;
            let Some((_, run, prefix)) = f else {
                out.push(self.finding(
                    "deadlock",
                    name,
                    place,
                    held,
                    format!("`{name}` can always take a step until it is done"),
                ));
                continue;
            };
            let at_stuck = &run.states[prefix];
            let nobody = self.system.successors(at_stuck).is_empty();
            let mut message = if nobody {
                let waiting: Vec<String> = (0..names.len())
                    .filter(|&j| !at_stuck.agents[j].is_idle() || !at_stuck.mail[j].is_empty())
                    .map(|j| format!("`{}`", names[j]))
                    .collect();
                format!(
                    "no agent can take a step, but {} {} not done",
                    waiting.join(", "),
                    if waiting.len() == 1 { "is" } else { "are" }
                )
            } else {
                format!("`{name}` is not done, and can never take a step again")
            };
            // An intention that waits for an answer no agent will send is the likely
            // cause: the finding points at its `.send`.
            let ask = at_stuck.agents[k]
                .waiting
                .iter()
                .find(|w| w.ask.is_some())
                .map(|w| w.step.3);
            let at = match ask {
                Some(span) => {
                    message.push_str(&format!(
                        ": `{name}` waits for the answer to `{}`, which no agent will send",
                        self.projects[k].map.slice(span).trim()
                    ));
                    span
                }
                None => place,
            };
            let mut f = self.finding("deadlock", name, at, Status::Fail, message);
            // The run ends in a loop when its last state is one it went through.
            let loop_from = run.states[..run.states.len() - 1]
                .iter()
                .position(|s| Some(s) == run.states.last())
                .filter(|_| run.states.len() > prefix + 1);
            f.counterexample = Some(self.counterexample_looping(&run, loop_from));
            out.push(f);
        }
    }

    /// The run to stored state `i`, then on, by the first transition followed from each
    /// state, until a state is stored again or none follows: the run, and where `i` is in
    /// it.
    fn gone_on(&self, i: u32) -> (Run, usize) {
        let mut path = self.graph.path_to(i);
        let prefix = path.len() - 1;
        let mut seen: std::collections::HashSet<u32> = path.iter().copied().collect();
        while let Some(&j) = self
            .graph
            .successors(*path.last().expect("a state"))
            .and_then(|s| s.first())
        {
            path.push(j);
            if !seen.insert(j) {
                break;
            }
        }
        (self.run(&path, None), prefix)
    }
}
