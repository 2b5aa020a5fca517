//! Partial-order reduction for several agents: from a state, follow only one agent's
//! reasoning cycle when it commutes with everything the others can do before it.
//!
//! A cycle of agent `k` is *local* when none of its outcomes changes the environment or
//! sends a message: it reads the environment (perception, action preconditions) and its
//! own mailbox, and writes only its own state and mailbox. Such a cycle is independent of
//! another agent's cycle unless that cycle changes the environment (`k` would perceive it)
//! or sends to `k` while `k`'s mailbox is empty (`k` would read it; behind other mail the
//! two commute). So the outcomes of `k`'s cycle are an ample set (Clarke, Grumberg and
//! Peled, *Model Checking*, ch. 10) when
//!
//! - C0: `k` has something to do;
//! - C1: no agent that can move before `k` does can change the environment, nor send to
//!   `k` while its mailbox is empty. Who can move: the agents with something to do, the
//!   first agent when requests remain (they go to it), and, to a fixed point, whoever they
//!   can wake (anyone, when they can change the environment; their receivers). What an
//!   agent can do is read from its plan library, every plan it may ever add included: an
//!   environment action or a belief update of a percept changes the environment; `.send`
//!   reaches the agent it names (anyone, when the receiver is not a name); `.broadcast`
//!   reaches everyone. For the first agent, no request may arrive before its cycle (a
//!   request changes its state);
//! - C2: no outcome changes a belief of `k` that a checked condition reads;
//! - C3, the cycle proviso, is the search's ([`super::model::Model::ample`]).
//!
//! Transitions left out at a state are independent of the ample ones, so they stay
//! enabled, with the same outcomes, and are taken later: every deadlock, every violation of
//! a condition and every step of every agent (its failures, the plans it adopts) is still
//! found, on a run that may be longer than the shortest one.

use crate::model::atoms::AtomSet;
use crate::model::cond::Cond;
use crate::model::formula::agent_stride;
use crate::model::plans::{BodyStep, Step as BodyItem};
use crate::model::term::Term;
use crate::semantics::{Note, Step, System, SystemState};
use std::ops::Range;

/// What each agent can do, read from its plan library, and what the conditions read.
pub struct PartialOrder {
    /// Per agent: whether some step can change the environment.
    writes_world: Vec<bool>,
    /// Per agent: the agents it can send to, one bit each.
    sends_to: Vec<u64>,
    /// Per agent: its beliefs some checked condition reads.
    visible: Vec<AtomSet>,
    /// Whether some agent perceives the environment at all.
    perceives: Vec<bool>,
}

impl PartialOrder {
    /// The reduction for `system`, whose checked conditions are `conds` (over
    /// [`System::everything`]).
    pub fn new<'c>(system: &System, conds: impl IntoIterator<Item = &'c Cond>) -> PartialOrder {
        let n = system.agents.len();
        let all = if n >= 64 { u64::MAX } else { (1u64 << n) - 1 };
        let mut writes_world = vec![false; n];
        let mut sends_to = vec![0u64; n];
        let mut asks = vec![0u64; n];
        for (k, sem) in system.agents.iter().enumerate() {
            let p = sem.project;
            let mut out = Capabilities {
                writes_world: false,
                sends_to: 0,
                asks: 0,
            };
            for plan in &p.plans.plans {
                out.scan(&plan.body, system, k, all);
            }
            writes_world[k] = out.writes_world;
            sends_to[k] = out.sends_to;
            asks[k] = out.asks;
        }
        // Whom an agent asks answers it (Jason's plans for messages send the answer).
        for (k, asked) in asks.iter().enumerate() {
            for (j, to) in sends_to.iter_mut().enumerate() {
                if asked >> j & 1 == 1 {
                    *to |= 1 << k;
                }
            }
        }
        let atoms = &system.agents[0].project.atoms;
        let stride = agent_stride(atoms);
        let mut visible: Vec<AtomSet> = (0..n).map(|_| AtomSet::empty(atoms.len())).collect();
        for c in conds {
            for a in c.atoms() {
                let i = a.0 as usize;
                if i >= stride && i / stride <= n {
                    visible[i / stride - 1]
                        .insert(crate::model::atoms::AtomId((i % stride) as u32));
                }
            }
        }
        let perceives = system
            .agents
            .iter()
            .map(|sem| !sem.env_atoms().is_empty())
            .collect();
        PartialOrder {
            writes_world,
            sends_to,
            visible,
            perceives,
        }
    }

    /// The ample set at `s` among its successors (as [`System::successors`] lists them:
    /// the requests, then each agent's outcomes in agent order): the outcomes of the first
    /// agent whose cycle is local, invisible and independent of what the others can do
    /// first. `None` when there is none, or when it would be every successor anyway.
    pub fn ample<'a>(
        &self,
        system: &System,
        s: &SystemState,
        successors: impl Iterator<Item = (&'a Step, &'a SystemState)>,
    ) -> Option<Range<usize>> {
        let successors: Vec<(&Step, &SystemState)> = successors.collect();
        let is_request = |st: &Step| {
            matches!(st.notes.first(), Some(Note::Request { .. })) && st.notes.len() == 1
        };
        let requests = successors
            .iter()
            .take_while(|(st, _)| is_request(st))
            .count();
        let mut at = requests;
        while at < successors.len() {
            let k = successors[at].0.agent as usize;
            let end = at
                + successors[at..]
                    .iter()
                    .take_while(|(st, _)| st.agent as usize == k)
                    .count();
            let range = at..end;
            at = end;
            if range.len() == successors.len() {
                return None;
            }
            if self.is_ample(system, s, k, requests > 0, &successors[range.clone()]) {
                return Some(range);
            }
        }
        None
    }

    fn is_ample(
        &self,
        system: &System,
        s: &SystemState,
        k: usize,
        requests_now: bool,
        outcomes: &[(&Step, &SystemState)],
    ) -> bool {
        // Local and invisible.
        let local = outcomes.iter().all(|(_, t)| {
            t.world == s.world
                && (0..s.mail.len()).all(|j| j == k || t.mail[j] == s.mail[j])
                && self.visible[k]
                    .iter()
                    .all(|a| t.agents[k].beliefs.contains(a) == s.agents[k].beliefs.contains(a))
        });
        if !local {
            return false;
        }
        // No request may arrive to the first agent before its cycle.
        if k == 0 && requests_now {
            return false;
        }
        let requests_remain = system.agents[0].requests_remain(s.agents[0].requested);
        // Who can move before `k`, to a fixed point.
        let n = s.agents.len();
        let mut moving: u64 = 0;
        for j in 0..n {
            if j != k && system.enabled(s, j) {
                moving |= 1 << j;
            }
        }
        if k != 0 && requests_remain {
            moving |= 1;
        }
        loop {
            let mut next = moving;
            for j in 0..n {
                if moving >> j & 1 == 1 {
                    if self.writes_world[j] {
                        next |= (0..n)
                            .filter(|&m| self.perceives[m])
                            .fold(0, |b, m| b | 1 << m);
                    }
                    next |= self.sends_to[j];
                }
            }
            next &= !(1u64 << k);
            if next == moving {
                break;
            }
            moving = next;
        }
        // A moving agent that could change what `k` perceives, or put the first message in
        // its mailbox, does not commute with it.
        let dependent = |j: usize| {
            self.writes_world[j] && self.perceives[k]
                || self.sends_to[j] >> k & 1 == 1 && s.mail[k].is_empty()
        };
        !(0..n).any(|j| moving >> j & 1 == 1 && dependent(j))
    }
}

/// What one agent's plans can do.
struct Capabilities {
    writes_world: bool,
    sends_to: u64,
    /// The agents it can ask something (who then answer it).
    asks: u64,
}

impl Capabilities {
    fn scan(&mut self, body: &[BodyItem], system: &System, k: usize, all: u64) {
        let sem = &system.agents[k];
        let atoms = &sem.project.atoms;
        for step in body {
            match &step.kind {
                BodyStep::Action(_) => self.writes_world = true,
                BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                    let percept = atoms
                        .pred_of_literal(t)
                        .is_some_and(|p| atoms.atoms_of(p).any(|a| sem.is_environment_atom(a)));
                    self.writes_world |= percept;
                }
                BodyStep::Internal(t) => {
                    let (to, performative) = match (t.functor(), t.args()) {
                        (Some(".broadcast"), [p, ..]) => (all, p),
                        (Some(".send"), [r, p, ..]) => {
                            let to = match r {
                                Term::Atom(name) => system
                                    .names()
                                    .iter()
                                    .position(|m| m.as_str() == &**name)
                                    .map_or(0, |i| 1u64 << i),
                                _ => all,
                            };
                            (to, p)
                        }
                        _ => continue,
                    };
                    self.sends_to |= to;
                    if matches!(performative.functor(), Some("askOne" | "askAll")) {
                        self.asks |= to;
                    }
                }
                BodyStep::If {
                    branches,
                    else_body,
                } => {
                    for (_, b) in branches {
                        self.scan(b, system, k, all);
                    }
                    self.scan(else_body, system, k, all);
                }
                BodyStep::While(_, b) | BodyStep::For(_, b) => self.scan(b, system, k, all),
                _ => {}
            }
        }
    }
}
