//! Several agents sharing one environment: Jason's asynchronous execution, one reasoning
//! cycle of one agent per transition, every interleaving.
//!
//! Each agent has its own beliefs, events, intentions and mailbox ([`State`], and a queue
//! of [`Message`]s); the environment is one set of atoms. A cycle of agent `k` starts as
//! `TransitionSystem.sense` does: the agent perceives what changed in the environment
//! since its last sense (`Agent.buf`: its own actions' effects and every other agent's),
//! then takes the first message of its mailbox (`checkMail`, one message per `sense`).
//! An `achieve` arrives by Jason's shortcut in `applyProcMsg` (no `kqml_received` plan of
//! the user, a literal content): the external event `+!g[source(sender)]`. Then the cycle
//! goes on as one agent's (`Semantics::cycle`); what its action changed becomes the
//! environment, and the messages it sent are delivered at once (`LocalAgArch.sendMsg` puts
//! them in the receiver's mailbox before `.send` returns).
//!
//! The user's requests go to the first agent.

use super::cycle::{Note, Performative, Semantics, Transition};
use super::state::State;
use crate::model::atoms::AtomSet;
use crate::model::project::Project;
use crate::model::term::Term;
use crate::syntax::ast::TriggerKind;
use crate::syntax::Diagnostic;

/// A message in an agent's mailbox.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Message {
    /// The sender's index.
    pub from: u8,
    /// The performative.
    pub performative: Performative,
    /// The goal to achieve, the belief told, or what is asked.
    pub content: Term,
    /// For an ask whose answer an intention of the sender waits for: its id (`samidN`).
    pub ask: Option<u8>,
    /// For an answer to such an ask of the receiver: that ask's id (`in_reply_to`).
    pub reply_to: Option<u8>,
}

/// The state of every agent, the environment and the messages in transit.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SystemState {
    /// The environment's atoms.
    pub world: AtomSet,
    /// Each agent's state; its environment atoms are what it perceived at its last sense.
    pub agents: Vec<State>,
    /// Each agent's mailbox, oldest first.
    pub mail: Vec<Vec<Message>>,
}

/// One transition: which agent moved, and what its cycle did.
#[derive(Clone, Debug)]
pub struct Step {
    /// The agent.
    pub agent: u8,
    /// What happened, in order (perception and the message read first).
    pub notes: Vec<Note>,
}

/// The transition system of several agents.
pub struct System<'p> {
    /// Each agent's own transition system.
    pub agents: Vec<Semantics<'p>>,
}

impl<'p> System<'p> {
    /// The system of the agents of a project ([`crate::model::project::load_system`]).
    pub fn new(projects: &'p [Project]) -> Result<System<'p>, Vec<Diagnostic>> {
        let names: Vec<String> = projects.iter().map(|p| p.name.clone()).collect();
        let mut agents = Vec::new();
        for (k, p) in projects.iter().enumerate() {
            if p.plans.plans.iter().any(|pl| {
                pl.trigger.literal.functor() == Some("kqml_received")
                    && pl.trigger.kind == TriggerKind::Achieve
            }) {
                let span = p
                    .plans
                    .plans
                    .iter()
                    .find(|pl| pl.trigger.literal.functor() == Some("kqml_received"))
                    .map(|pl| pl.span)
                    .expect("found");
                return Err(vec![Diagnostic::error(
                    "input",
                    "a plan for `+!kqml_received` changes how this agent takes messages, and bdi-check runs Jason's own (kqmlPlans.asl)",
                )
                .with_label(span, "here")]);
            }
            let mut sem = Semantics::new(p)?;
            sem.agents = names.clone();
            sem.me = k as u8;
            sem.shared_world = true;
            agents.push(sem);
        }
        // What one agent asks with variables, another answers from its beliefs in their
        // order: a predicate whose order can show for one can for all.
        let ordered: Vec<bool> = (0..agents[0].ordered.len())
            .map(|i| agents.iter().any(|a| a.ordered[i]))
            .collect();
        for a in &mut agents {
            a.ordered = ordered.clone();
        }
        Ok(System { agents })
    }

    /// The agents' names.
    pub fn names(&self) -> &[String] {
        &self.agents[0].agents
    }

    /// One initial state per initial state of the environment: each agent starts with its
    /// own initial beliefs and goals and perceives the environment, as one agent does.
    pub fn initial_states(&self) -> Vec<SystemState> {
        let p = self.agents[0].project;
        p.initial
            .states()
            .iter()
            .map(|w| SystemState {
                world: w.clone(),
                agents: self
                    .agents
                    .iter()
                    .map(|sem| {
                        let mut b = w.clone();
                        sem.project
                            .initial
                            .agent_beliefs
                            .iter()
                            .for_each(|a| b.insert(*a));
                        sem.initial_state(&b)
                    })
                    .collect(),
                mail: vec![Vec::new(); self.agents.len()],
            })
            .collect()
    }

    /// Whether agent `k` has something to do: something to perceive, a message, or an
    /// event or intention.
    pub fn enabled(&self, s: &SystemState, k: usize) -> bool {
        !s.agents[k].is_idle() || !s.mail[k].is_empty() || self.unperceived(s, k)
    }

    fn unperceived(&self, s: &SystemState, k: usize) -> bool {
        let env = &self.agents[k].env_atoms;
        let mine = s.agents[k].beliefs.words();
        s.world
            .words()
            .iter()
            .zip(mine)
            .zip(env.words())
            .any(|((w, b), e)| (w ^ b) & e != 0)
    }

    /// Every successor of `s`: the user's requests (to the first agent), then a cycle of
    /// each agent that has something to do, in agent order.
    pub fn successors(&self, s: &SystemState) -> Vec<(Step, SystemState)> {
        let mut out = Vec::new();
        let first = &self.agents[0];
        let a0 = &s.agents[0];
        if first.may_request(a0.requested, a0.is_idle() && s.mail[0].is_empty()) {
            for r in 0..first.requests.len() {
                if a0.requested >> r & 1 == 1 {
                    continue;
                }
                let mut next = s.clone();
                first.post_request(&mut next.agents[0], r);
                out.push((
                    Step {
                        agent: 0,
                        notes: vec![Note::Request { index: r as u8 }],
                    },
                    next,
                ));
            }
        }
        for k in 0..self.agents.len() {
            if self.enabled(s, k) {
                out.extend(self.cycle_of(s, k));
            }
        }
        out
    }

    /// The sense that begins a cycle of agent `k` (`TransitionSystem.sense`): perception
    /// first (`Agent.buf`: what changed in the environment since its last sense), then one
    /// message (`checkMail`). The agent after it, its mailbox left, and what it did.
    fn sense(&self, s: &SystemState, k: usize) -> (State, Vec<Message>, Vec<Note>) {
        let sem = &self.agents[k];
        let mut agent = s.agents[k].clone();
        let mut mail = s.mail[k].clone();
        let mut before = Vec::new();
        let env_before = sem.env_count(&agent.beliefs);
        let (mut added, mut removed) = (Vec::new(), Vec::new());
        for a in sem.env_atoms.iter() {
            match (s.world.contains(a), agent.beliefs.contains(a)) {
                (true, false) => added.push(a),
                (false, true) => removed.push(a),
                _ => {}
            }
        }
        if !added.is_empty() || !removed.is_empty() {
            added.iter().for_each(|a| agent.beliefs.insert(*a));
            removed.iter().for_each(|a| agent.beliefs.remove(*a));
            let after = env_before + added.len() - removed.len();
            sem.java_order(&mut removed, env_before);
            sem.java_order(&mut added, after);
            sem.perceive(&mut agent, &added, &removed);
            before.push(Note::Perceived {
                added: added.clone(),
                removed: removed.clone(),
            });
        }
        if !mail.is_empty() {
            let m = mail.remove(0);
            before.extend(sem.receive(&mut agent, &m));
        }
        (agent, mail, before)
    }

    /// Agent `k`'s beliefs after the sense that begins its next cycle in `s`, when that
    /// sense perceives or reads something (the cycle's notes then begin with what it
    /// did); `None` when it has nothing to perceive or read.
    pub fn sensed(&self, s: &SystemState, k: usize) -> Option<AtomSet> {
        if s.mail[k].is_empty() && !self.unperceived(s, k) {
            return None;
        }
        Some(self.sense(s, k).0.beliefs)
    }

    /// One reasoning cycle of agent `k` (enabled or not: an agent with nothing to do
    /// has one outcome, which changes nothing), one successor per outcome.
    pub fn cycle_of(&self, s: &SystemState, k: usize) -> Vec<(Step, SystemState)> {
        let sem = &self.agents[k];
        let (agent, mail, before) = self.sense(s, k);
        let perceived = agent.beliefs.clone();
        let transitions = if agent.is_idle() {
            vec![Transition {
                notes: Vec::new(),
                next: agent,
            }]
        } else {
            sem.cycle_sensed(&agent, !before.is_empty())
        };
        transitions
            .into_iter()
            .map(|t| {
                let mut next = s.clone();
                next.mail[k] = mail.clone();
                // What the cycle's action changed is the environment now; the agent
                // perceives it at its next sense.
                let mut world = s.world.clone();
                let mut mine = t.next;
                for a in sem.env_atoms.iter() {
                    if mine.beliefs.contains(a) != perceived.contains(a) {
                        if mine.beliefs.contains(a) {
                            world.insert(a);
                            mine.beliefs.remove(a);
                        } else {
                            world.remove(a);
                            mine.beliefs.insert(a);
                        }
                    }
                }
                for n in &t.notes {
                    if let Note::Sent {
                        to,
                        performative,
                        content,
                        ask,
                        reply_to,
                    } = n
                    {
                        for &r in to {
                            next.mail[r as usize].push(Message {
                                from: k as u8,
                                performative: *performative,
                                content: content.clone(),
                                ask: *ask,
                                reply_to: *reply_to,
                            });
                        }
                    }
                }
                next.world = world;
                next.agents[k] = mine;
                let mut notes = before.clone();
                notes.extend(t.notes);
                (
                    Step {
                        agent: k as u8,
                        notes,
                    },
                    next,
                )
            })
            .collect()
    }
}

impl System<'_> {
    /// Whether agent `k` has nothing to do but wait for a timer or an answer: no message,
    /// nothing to perceive, no event, no running intention (or its atomic intention
    /// sleeps in `.wait`, and the others wait for it: [`Semantics::atomic_sleeps`]).
    pub fn asleep(&self, s: &SystemState, k: usize) -> bool {
        let a = &s.agents[k];
        s.mail[k].is_empty()
            && !self.unperceived(s, k)
            && (self.agents[k].atomic_sleeps(a)
                || a.events.is_empty()
                    && a.intentions.is_empty()
                    && a.pending.is_none()
                    && a.waiting.iter().all(|w| !w.woken))
    }

    /// Whether agent `k` has perceived the environment as it is now.
    pub fn has_perceived(&self, s: &SystemState, k: usize) -> bool {
        !self.unperceived(s, k)
    }
}

impl System<'_> {
    /// The environment's atoms and every agent's beliefs in one set, as the conditions of
    /// [`crate::model::formula::compile_in`] read them: agent `k`'s belief `a` at
    /// `(k + 1) * stride + a`.
    pub fn everything(&self, s: &SystemState) -> AtomSet {
        let atoms = &self.agents[0].project.atoms;
        let stride = crate::model::formula::agent_stride(atoms);
        let mut all = AtomSet::empty(stride * (s.agents.len() + 1));
        s.world.iter().for_each(|a| all.insert(a));
        for (k, agent) in s.agents.iter().enumerate() {
            let base = ((k + 1) * stride) as u32;
            agent
                .beliefs
                .iter()
                .for_each(|a| all.insert(crate::model::atoms::AtomId(base + a.0)));
        }
        all
    }
}
