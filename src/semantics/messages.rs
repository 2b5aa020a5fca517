//! Messages between agents: what `.send` and `.broadcast` send (stdlib `send`), what the
//! receiver's cycle does with a message it reads (`TransitionSystem.applyProcMsg` and
//! `resumeSyncAskIntention`), and the internal actions of Jason's plans for messages
//! ([`crate::model::kqml`]).
//!
//! An `achieve` or a `tell` of a literal takes Jason's shortcut: the event
//! `+!g[source(sender)]`, or the belief `b[source(sender)]` (`Agent.addBel`). Every other
//! performative becomes the external event `+!kqml_received(Sender, Performative,
//! Content, MsgId)`, which Jason's plans for messages handle step by step. An ask with an
//! answer variable (`.send(bob, askOne, price(X), A)`) suspends its intention until the
//! answer arrives: the answer is unified with `A` (`false` when it is `untell`), and the
//! intention goes back to the queue at once, in the cycle that reads the answer, or fails
//! (`ask_failed`) when they do not unify. With a timeout (`.send(.., A, 500)`) the wait
//! may end at the start of any later cycle, `A` unified with `timeout`, and an answer
//! that comes after it is ignored.
//!
//! An ask's id is `samidN` with the least `N` no answer still on its way has (Jason
//! numbers all messages of the run, `samid12`); the id of a message nobody waits for an
//! answer to is `mid`. Only answers compare ids.

use super::cycle::{Note, Performative, Semantics};
use super::state::{Event, EventTrigger, Origin, State, Told, Waiting};
use super::system::Message;
use crate::model::atoms::AtomId;
use crate::model::internal::nested_source;
use crate::model::term::{Term, MESSAGE_GENERATION};
use crate::model::unify;
use crate::syntax::ast::{TriggerKind, TriggerOp};

/// What a `.send` or `.broadcast` sends.
pub(super) struct Send {
    /// The receiver's name (`self` resolved); `None` for every other agent.
    pub receiver: Option<String>,
    /// The performative.
    pub performative: Performative,
    /// The content, its variables renamed apart.
    pub content: Term,
    /// For an ask with an answer variable: the fourth argument.
    pub answer: Option<Term>,
    /// For an answer (`tell` or `untell` with a fourth argument): the id of the ask it
    /// answers, when that ask waits for it (`samidN`).
    pub reply_to: Option<u8>,
    /// Whether the ask has a timeout.
    pub timed: bool,
}

/// The id an ask waits under, as the receiver sees it: `samidN`, or `mid` for a message
/// whose answer nobody waits for.
fn message_id(ask: Option<u8>) -> Term {
    match ask {
        Some(k) => Term::atom(&format!("samid{k}")),
        None => Term::atom("mid"),
    }
}

/// The ask an id names, if it is one an intention may wait under.
fn ask_of(id: &Term) -> Option<u8> {
    id.functor()?.strip_prefix("samid")?.parse().ok()
}

impl Semantics<'_> {
    /// What `.send(..)` or `.broadcast(..)` (`f`, its arguments evaluated) sends, or why
    /// bdi-check does not follow the run there.
    pub(super) fn message(&self, f: &str, term: &Term) -> Result<Send, String> {
        let args = term.args();
        let (receiver, ilf, content, rest) = if f == ".send" {
            (Some(&args[0]), &args[1], &args[2], &args[3..])
        } else {
            (None, &args[0], &args[1], &args[..0])
        };
        let receiver = match receiver {
            None => None,
            Some(Term::Atom(n) | Term::Str(n)) if &**n == "self" => Some(self.agent_name.clone()),
            Some(Term::Atom(n) | Term::Str(n)) => Some(n.to_string()),
            Some(r) => return Err(format!("the receiver `{r}` is not an agent's name")),
        };
        let performative = match ilf {
            Term::Atom(p) => Performative::named(p),
            _ => None,
        }
        .ok_or_else(|| format!("the performative `{ilf}` is not one bdi-check delivers"))?;
        let (mut answer, mut reply_to, mut timed) = (None, None, false);
        let replying =
            matches!(performative, Performative::Tell | Performative::Untell) && !rest.is_empty();
        match (performative, rest) {
            (_, []) => {}
            (Performative::AskOne | Performative::AskAll, [a, more @ ..]) => {
                answer = Some(a.clone());
                if let Some(t) = more.first() {
                    if t.as_f64().is_none() {
                        return Err(format!("the timeout `{t}` is not a number: Jason's `.send` throws once the message is sent, which bdi-check does not model"));
                    }
                    timed = true;
                }
            }
            (Performative::Tell | Performative::Untell | Performative::TellHow, [id])
                if matches!(id, Term::Atom(_)) =>
            {
                reply_to = ask_of(id);
            }
            _ => {
                return Err(format!(
                    "`.send` of `{}` with these arguments is not one bdi-check models",
                    performative.name()
                ))
            }
        }
        if matches!(
            performative,
            Performative::TellHow | Performative::UntellHow | Performative::AskHow
        ) {
            // The content is what `model::know_how` made of the text: keys and labels.
            return Ok(Send {
                receiver,
                performative,
                content: content.clone(),
                answer,
                reply_to,
                timed,
            });
        }
        let sync_reply = reply_to.is_some();
        if content.is_list() && !sync_reply {
            return Err("a list of contents (Jason's kqmlPlans take them one by one), which bdi-check does not model yet".into());
        }
        if !content.is_literal() && !sync_reply {
            return Err(format!("the content `{content}` is not a literal"));
        }
        if !sync_reply && !content.annots().is_empty() {
            return Err(if replying || performative != Performative::Tell {
                "the content has annotations (an answer from a belief with other sources would nest them in the receiver's `source`), which bdi-check does not model".into()
            } else {
                "the told belief is not an atom of the model without annotations, and bdi-check keeps only the sources of a belief".into()
            });
        }
        match performative {
            Performative::Achieve if !content.is_ground() => {
                return Err("the message's content is not ground, and bdi-check sends ground goals only".into())
            }
            Performative::Tell if !sync_reply && self.ground_atom(content).is_none() => {
                return Err("the told belief is not an atom of the model without annotations, and bdi-check keeps only the sources of a belief".into())
            }
            _ => {}
        }
        Ok(Send {
            receiver,
            performative,
            content: rename_apart(content),
            answer,
            reply_to,
            timed,
        })
    }

    /// Agent state `s` reads message `m` (`applyProcMsg`): an answer its intention waits
    /// for resumes it, an answer nobody waits for any more is ignored, an `achieve` or a
    /// `tell` takes Jason's shortcut, and any other performative is the event
    /// `+!kqml_received(..)`. The notes say what happened.
    pub(super) fn receive(&self, s: &mut State, m: &Message) -> Vec<Note> {
        let mut notes = vec![Note::Received {
            from: m.from,
            performative: m.performative,
            content: m.content.clone(),
        }];
        let sender = if m.from == self.me {
            "self".to_string()
        } else {
            self.agents[m.from as usize].clone()
        };
        if let Some(k) = m.reply_to {
            s.asked &= !(1 << k);
            let at = s
                .waiting
                .iter()
                .position(|w| matches!(w.ask, Some((id, _)) if id == k));
            if let Some(i) = at {
                let w = s.waiting.remove(i);
                self.answered(s, w, m, &sender, &mut notes);
            }
            // Otherwise its timeout came first, or the intention was dropped: Jason
            // ignores the answer (`Message.isReplyToSyncAsk`).
            return notes;
        }
        let literal = nested_source(&m.content, &Term::atom(&sender));
        let trigger = match m.performative {
            Performative::Achieve => Some(EventTrigger {
                op: TriggerOp::Add,
                kind: TriggerKind::Achieve,
                literal,
            }),
            Performative::Tell => self.told_by(s, m.from, &m.content).then_some(EventTrigger {
                op: TriggerOp::Add,
                kind: TriggerKind::Belief,
                literal,
            }),
            p => Some(EventTrigger {
                op: TriggerOp::Add,
                kind: TriggerKind::Achieve,
                literal: Term::structure(
                    "kqml_received",
                    vec![
                        Term::atom(&sender),
                        Term::atom(p.name()),
                        m.content.clone(),
                        message_id(m.ask),
                    ],
                ),
            }),
        };
        if let Some(trigger) = trigger {
            // The shortcuts' `C.addEvent` and `Agent.addBel`, and `updateEvents` of the
            // `kqml_received` goal: an external event.
            self.post_event(
                s,
                Event {
                    trigger,
                    intention: None,
                    origin: Origin::Spawned,
                    posted_at: None,
                },
            );
        }
        notes
    }

    /// `resumeSyncAskIntention`: the answer `m` to the ask `w` waits for is unified with
    /// the `.send`'s fourth argument, and the intention goes back to the queue, or fails
    /// with `ask_failed` when they do not unify.
    fn answered(
        &self,
        s: &mut State,
        w: Waiting,
        m: &Message,
        sender: &str,
        notes: &mut Vec<Note>,
    ) {
        let (plan, block, pos, span) = w.step;
        let Some((_, answer)) = &w.ask else {
            unreachable!("an ask waits for its answer")
        };
        let asked = &self.block(plan, block)[pos as usize];
        let send = match &asked.kind {
            crate::model::plans::BodyStep::Internal(t) => t.args().get(1).cloned(),
            _ => None,
        };
        let one = send.as_ref().and_then(Term::functor) == Some("askOne");
        let who = Term::atom(sender);
        let value = if m.performative == Performative::Untell && one {
            Term::atom("false")
        } else {
            // `add_nested_source.addAnnotToList`: a literal, or each element of a list.
            nested_source(&m.content, &who)
        };
        let mut int = w.intention;
        let origin = int.origin;
        let text = format!(
            "{} is answered: {value}",
            self.project.map.slice(span).trim()
        );
        notes.push(Note::Internal {
            text: text.clone(),
            plan,
            origin,
        });
        let atomic = self.is_atomic(&int);
        let top = int.frames.last_mut().expect("a frame");
        let mut u = top.subst.clone();
        if unify(answer, &value, &mut u) {
            top.subst = u;
            // `resumeIntention`: `AI` for an atomic intention (see `atomic.rs`).
            if self.clear_finished(&mut int, notes) {
                self.requeue(s, int, atomic);
            }
        } else if atomic {
            notes.push(self.atomic_beyond(plan, span, "an answer that does not unify"));
        } else {
            let failed = int.frames.last().map(|f| f.trigger.clone()).expect("frame");
            self.fail_intention(
                s,
                int,
                &failed,
                Some((plan, span)),
                &format!("{text}, which does not unify with `{answer}`"),
                ("ask_failed", &[]),
                notes,
            );
        }
    }

    /// The timeout of the ask `w` waits for came first: its answer is `timeout` (when it
    /// unifies), and the intention goes back to the queue.
    pub(super) fn ask_timed_out(&self, s: &mut State, w: Waiting, notes: &mut Vec<Note>) {
        let (plan, _, _, span) = w.step;
        let Some((_, answer)) = &w.ask else {
            unreachable!("an ask waits for its answer")
        };
        let mut int = w.intention;
        notes.push(Note::Internal {
            text: format!("{} times out", self.project.map.slice(span).trim()),
            plan,
            origin: int.origin,
        });
        // `send`'s timer: `unifies(send.getTerm(3), timeout)`, whatever it gives.
        let top = int.frames.last_mut().expect("a frame");
        let mut u = top.subst.clone();
        if unify(answer, &Term::atom("timeout"), &mut u) {
            top.subst = u;
        }
        let atomic = self.is_atomic(&int);
        if self.clear_finished(&mut int, notes) {
            self.requeue(s, int, atomic);
        }
    }

    /// Agent state `s` believes `b[source(from)]` (`Agent.addBel`,
    /// `DefaultBeliefBase.add`): whether anything changed (a new belief, or a new source of
    /// one already held). Only mental notes are told (a percept is refused where the `tell`
    /// is written).
    fn told_by(&self, s: &mut State, from: u8, content: &Term) -> bool {
        let Some(a) = self.ground_atom(content) else {
            return false;
        };
        let at = s.told.binary_search_by_key(&a, |t| t.atom);
        // A message from the agent itself is `source(self)`: its own belief.
        if from == self.me {
            return match at {
                Ok(i) if s.told[i].own => false,
                Ok(i) => {
                    s.told[i].own = true;
                    true
                }
                Err(_) if s.beliefs.contains(a) => false,
                Err(_) => {
                    s.beliefs.insert(a);
                    self.note_added(s, a);
                    true
                }
            };
        }
        let bit = 1u64 << from;
        match at {
            Ok(i) if s.told[i].from & bit != 0 => false,
            Ok(i) => {
                s.told[i].from |= bit;
                true
            }
            Err(i) => {
                let own = s.beliefs.contains(a);
                s.told.insert(
                    i,
                    Told {
                        atom: a,
                        from: bit,
                        own,
                    },
                );
                if !own {
                    s.beliefs.insert(a);
                    self.note_added(s, a);
                }
                true
            }
        }
    }

    /// `--Content[source(Sender)]` (`DefaultBeliefBase.remove`): the first belief that
    /// unifies with `c` and has that source loses it, and goes when it has no source
    /// left. Returns that belief, and whether it went.
    pub(super) fn untell(&self, s: &mut State, c: &Term, sender: &Term) -> Vec<(AtomId, bool)> {
        let from = match sender.functor() {
            Some("self") => self.me,
            Some(name) => match self.agents.iter().position(|a| a == name) {
                Some(k) => k as u8,
                None => return Vec::new(),
            },
            None => return Vec::new(),
        };
        let query = nested_source(c, sender);
        let hit = self
            .beliefs(s)
            .literal_answers(&query, &crate::model::Substitution::new())
            .into_iter()
            .next();
        let Some((a, _)) = hit else {
            return Vec::new();
        };
        let gone = match s.told.binary_search_by_key(&a, |t| t.atom) {
            Ok(i) if from == self.me => {
                s.told[i].own = false;
                false
            }
            Ok(i) => {
                s.told[i].from &= !(1u64 << from);
                let t = &s.told[i];
                match (t.from, t.own) {
                    (0, true) => {
                        s.told.remove(i);
                        false
                    }
                    (0, false) => {
                        s.told.remove(i);
                        true
                    }
                    _ => false,
                }
            }
            // Its one source, `self`.
            Err(_) => true,
        };
        if gone {
            s.beliefs.remove(a);
            self.reorder(s, &[], &[a]);
        }
        vec![(a, gone)]
    }

    /// What Jason's `kqmlError` plan prints for the failure `Error` of a `kqml_received`
    /// goal: `Communication error -- Error: Message`, with Jason's message where bdi-check
    /// knows it (a test goal of an `askOne` with no applicable `+?` plan), else the error
    /// alone.
    pub(super) fn communication_error(&self, term: &Term, query: Option<&Term>) -> String {
        let error = term.args().first().cloned().unwrap_or_else(Term::nil);
        match (error.functor(), query) {
            (Some(e @ ("no_applicable" | "no_relevant")), Some(q)) => format!(
                "Communication error -- {error}: Found a goal for which there is no {} plan: +?{q}",
                e.trim_start_matches("no_")
            ),
            _ => format!("Communication error -- {error}"),
        }
    }
}

/// A message's content with its variables renamed apart from every plan's and rule's,
/// numbered in order of first occurrence (the receiver's plans bind them).
fn rename_apart(t: &Term) -> Term {
    let vars = t.vars();
    t.map_vars(&mut |v| {
        let i = vars.iter().position(|x| x == v).unwrap_or(0) as u32;
        Term::from(v.with_generation(MESSAGE_GENERATION + i))
    })
}
