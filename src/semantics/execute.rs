//! The act phase: the feedback of the action sent in the previous cycle, then the first
//! intention runs one body step (environment actions, which wait for their feedback as
//! Jason's pending actions; internal actions; subgoals; test goals; belief changes;
//! constraints; `if`, `while` and `for`). Mirrors `TransitionSystem.applyProcAct`,
//! `applySelInt` and `applyExecInt` (with the stdlib `.while`/`.foreach` loops).

use super::cycle::{with_source, FrameView, Note, Semantics};
use super::library::no_code;
use super::query::{eval, note_trouble, relation, take_trouble, trouble_reason};
use super::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Origin, Pending,
    State,
};
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::plans::{BodyStep, Formula};
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::model::{unify, Substitution};
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::Span;

impl Semantics<'_> {
    /// Moves a frame's cursors to the next step to execute, leaving blocks that have
    /// ended; a loop's body that has ended stays, its cursor past the end, until the loop
    /// is tested again ([`Semantics::loop_again`]). `cursors` is empty when the body is done.
    pub(super) fn normalize(&self, f: &mut Frame) {
        let blocks = &self.blocks[f.plan as usize];
        while let Some(c) = f.cursors.last() {
            if (c.pos as usize) < blocks.blocks[c.block as usize].len()
                || !matches!(c.kind, CursorKind::Seq)
            {
                return;
            }
            f.cursors.pop();
        }
    }

    /// Where the step a frame executes next is written, for traces: the innermost block's
    /// next step (a loop whose body has ended: the step after it in an enclosing block).
    /// `None` when the body is done.
    pub fn next_step(&self, f: &Frame) -> Option<Span> {
        let blocks = &self.blocks[f.plan as usize];
        f.cursors
            .iter()
            .rev()
            .find_map(|c| blocks.blocks[c.block as usize].get(c.pos as usize))
            .map(|s| s.span)
    }

    /// Tests a loop again once its body has ended: `while` restores the bindings it had
    /// when it first ran and asks its condition again (stdlib `loop`: `un.clear();
    /// un.compose(ubak)`), so variables bound in the body are free on the next pass and
    /// after the loop; `for` takes its next answer, and restores the bindings from before
    /// the loop when there is none (stdlib `foreach`). The answers of `for` are computed
    /// when it first runs.
    fn loop_again(&self, f: &mut Frame, s: &State, running: &[Term]) {
        let blocks = &self.blocks[f.plan as usize];
        let Some(c) = f.cursors.last_mut() else {
            return;
        };
        match &mut c.kind {
            CursorKind::Seq => {}
            CursorKind::While { outer, at, base } => {
                let cond = match &blocks.blocks[*outer as usize][*at as usize].kind {
                    BodyStep::While(cond, _) => cond,
                    _ => unreachable!("a while cursor points at a while step"),
                };
                let base = base.clone();
                match self
                    .beliefs_running(s, running)
                    .answers(cond, &base)
                    .into_iter()
                    .next()
                {
                    Some(a) => {
                        f.subst = a;
                        c.pos = 0;
                    }
                    None => {
                        f.subst = base;
                        f.cursors.pop();
                    }
                }
            }
            CursorKind::For { rest, base } => {
                if rest.is_empty() {
                    f.subst = base.clone();
                    f.cursors.pop();
                } else {
                    f.subst = rest.remove(0);
                    c.pos = 0;
                }
            }
        }
        self.normalize(f);
    }

    /// Jason's `applyProcAct`, the act phase's first stage: the feedback of the action
    /// sent in the previous cycle. A done action's intention goes to the back of the
    /// queue (after any the deliberation of this cycle started) and its finished plans are
    /// cleared; a failed one's plan fails (`generateGoalDeletion`).
    pub(super) fn proc_act(&self, s: &mut State, notes: &mut Vec<Note>) {
        let Some(p) = s.pending.take() else {
            return;
        };
        let mut int = p.intention;
        match p.failure {
            Some(f) => {
                let failed = int
                    .frames
                    .last()
                    .map(|f| f.trigger.clone())
                    .expect("a frame");
                let reason = format!("{}: {}", f.action, f.why);
                let at = Some((f.plan, f.span));
                self.fail_intention(s, int, &failed, at, &reason, ("action_failed", &[]), notes);
            }
            None => {
                // `removeActionReQueue` (`AI` again for an atomic intention), then
                // `applyClrInt`.
                let atomic = self.is_atomic(&int);
                if self.clear_finished(&mut int, notes) {
                    self.requeue(s, int, atomic);
                }
            }
        }
    }

    /// The act phase: the first intention runs one step, with the outcome `choice` of a
    /// step that has several ([`Semantics::act_choices`]).
    pub(super) fn act(&self, s: &mut State, notes: &mut Vec<Note>, choice: usize) {
        let env = self.env_count(&s.beliefs);
        self.act_with(s, notes, env, choice)
    }

    /// How many outcomes the act phase has: the values `.random` may give when it is the
    /// first intention's next step (stdlib `random`: an element of its list, or a number
    /// of `[bounds] random`), else one.
    pub(super) fn act_choices(&self, s: &State) -> usize {
        if !s.atomic && self.atomic_suspended(s) {
            return 1;
        }
        let Some(f) = s.intentions.first().and_then(|i| i.frames.last()) else {
            return 1;
        };
        let Some(c) = f.cursors.last() else {
            return 1;
        };
        match self.blocks[f.plan as usize].blocks[c.block as usize]
            .get(c.pos as usize)
            .map(|s| &s.kind)
        {
            Some(BodyStep::Internal(t)) if t.functor() == Some(".random") => {
                match t.args().first().map(|a| f.subst.apply(a)) {
                    Some(l) if l.is_list() => l.list_elements().map_or(1, |(e, _)| e.len().max(1)),
                    _ => self.random_values().len().max(1),
                }
            }
            _ => 1,
        }
    }

    /// `[bounds] random`: the values `.random(X)` may give.
    fn random_values(&self) -> &[f64] {
        self.project
            .manifest
            .bounds
            .random
            .as_ref()
            .map_or(&[], |r| r.value.as_slice())
    }

    /// [`Semantics::act`] on a state that may hold only some of the beliefs, `env` of the
    /// environment's atoms holding in the whole state (their number decides the order in
    /// which Jason perceives an action's effects).
    pub(super) fn act_with(&self, s: &mut State, notes: &mut Vec<Note>, env: usize, choice: usize) {
        // `applySelInt`: the atomic intention first (`removeAtomicIntention` clears `AI`),
        // none while it is suspended.
        if s.intentions.is_empty() || !s.atomic && self.atomic_suspended(s) {
            return;
        }
        s.atomic = false;
        let mut int = s.intentions.remove(0);
        let finished_top = int.frames.last().is_none_or(|f| f.cursors.is_empty());
        if !finished_top {
            let at = int
                .frames
                .last()
                .and_then(|f| Some((f.plan, self.next_step(f)?)));
            take_trouble();
            let flow = self.step(s, &mut int, notes, env, choice);
            if let (Some(e), Some((plan, span))) = (take_trouble(), at) {
                // Arithmetic Jason would throw on or go on past with a non-number: the
                // run leaves the model here (not followed, so what the step did is moot).
                notes.push(Note::Beyond {
                    text: step_text(self, span),
                    plan,
                    span,
                    reason: trouble_reason(e),
                });
                return;
            }
            match flow {
                Flow::Continue => {}
                Flow::Suspended | Flow::Gone => return,
            }
        }
        // `removeActionReQueue` puts it back (in `AI` when atomic), then `applyClrInt`
        // pops its finished plans.
        let atomic = self.is_atomic(&int);
        if self.clear_finished(&mut int, notes) {
            self.requeue(s, int, atomic);
        }
    }

    /// Executes the next step of the top frame.
    fn step(
        &self,
        s: &mut State,
        int: &mut Intention,
        notes: &mut Vec<Note>,
        env_before: usize,
        choice: usize,
    ) -> Flow {
        let depth = int.frames.len() - 1;
        // What `.intend`/`.desire` see of this intention while it is out of the state (a
        // library that asks about intentions is never local: the compiled search never
        // pays for this).
        let running: Vec<Term> = if self.is_local() {
            Vec::new()
        } else {
            int.goals().cloned().collect()
        };
        // `.drop_intention(g)` may drop the very intention that runs it.
        let drops_itself = |g: &Term| {
            int.frames.iter().any(|f| {
                f.trigger.kind == TriggerKind::Achieve
                    && crate::model::unifier(g, &f.trigger.literal).is_some()
            })
        };
        let own_drop = int.frames.last().and_then(|f| {
            let c = f.cursors.last()?;
            match &self.blocks[f.plan as usize].blocks[c.block as usize]
                .get(c.pos as usize)?
                .kind
            {
                BodyStep::Internal(t)
                    if matches!(t.functor(), Some(".drop_desire" | ".drop_intention")) =>
                {
                    Some(drops_itself(&f.subst.apply(t.args().first()?)))
                }
                _ => None,
            }
        });
        // The stack an environment action runs in (for explanations); other steps need none.
        let acts = int.frames.last().is_some_and(|f| {
            f.cursors.last().is_some_and(|c| {
                matches!(
                    self.blocks[f.plan as usize].blocks[c.block as usize]
                        .get(c.pos as usize)
                        .map(|s| &s.kind),
                    Some(BodyStep::Action(_))
                )
            })
        });
        let views: Vec<FrameView> = if acts {
            int.frames
                .iter()
                .map(|f| FrameView {
                    plan: f.plan,
                    subst: f.subst.clone(),
                    at: f.cursors.last().map_or((0, 0), |c| (c.block, c.pos)),
                })
                .collect()
        } else {
            Vec::new()
        };
        // For Jason's `kqmlError` plan: the query of the `askOne` plan that failed below it.
        let failed_query = int
            .frames
            .last()
            .filter(|f| self.is_kqml_plan(f.plan))
            .and_then(|_| int.frames.iter().rev().nth(1))
            .map(|f| f.subst.apply(&Term::var("Query")))
            .filter(|q| !q.is_var());
        let frame = int.frames.last_mut().expect("an intention has a frame");
        let plan = frame.plan;
        let blocks = &self.blocks[plan as usize];
        let Some(cursor) = frame.cursors.last_mut() else {
            return Flow::Continue;
        };
        let (block, pos) = (cursor.block, cursor.pos);
        let Some(step) = blocks.blocks[block as usize].get(pos as usize) else {
            // The end of a loop's body: testing the loop again is a step of its own, as
            // Jason's `.while`/`.foreach` internal actions run again after the body.
            self.loop_again(frame, s, &running);
            return Flow::Continue;
        };
        cursor.pos += 1;
        let origin = int.origin;
        let fail = |sem: &Self,
                    s: &mut State,
                    int: Intention,
                    text: &str,
                    reason: String,
                    notes: &mut Vec<Note>| {
            let failed = int.frames.last().map(|f| f.trigger.clone()).expect("frame");
            // The `error(Id)` Jason's `createBasicErrorAnnots` gives the failure event.
            let error = match &step.kind {
                BodyStep::Test(_) => "test_goal_failed",
                BodyStep::Constraint(..) => "constraint_failed",
                // A JasonException's default error (`JasonException.defaultError`).
                BodyStep::Library { .. } => "internal_action",
                BodyStep::Internal(t) if t.functor() == Some(".kqml_tell_how") => "internal_action",
                BodyStep::AddBel(_) | BodyStep::DelBel(_) | BodyStep::DelAddBel(_) => {
                    "belief_revision_failed"
                }
                _ => "ia_failed",
            };
            sem.fail_intention(
                s,
                int,
                &failed,
                Some((plan, step.span)),
                &format!("{text}: {reason}"),
                (error, &[]),
                notes,
            );
            Flow::Gone
        };
        // A step whose arithmetic has no value fails, as Jason's exception fails the plan.
        macro_rules! value {
            ($t:expr) => {
                match eval($t, &frame.subst) {
                    Ok(v) => v,
                    Err(e) => {
                        // `act_with` turns this into a refusal of the run.
                        note_trouble(e);
                        let text = frame.subst.apply($t).to_string();
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(self, s, int, &text, e.to_string(), notes);
                    }
                }
            };
        }
        // An internal action with no answer: noted, then the plan fails.
        macro_rules! no_answer {
            ($text:expr) => {{
                notes.push(Note::Internal {
                    text: $text.clone(),
                    plan,
                    origin,
                });
                let int = std::mem::replace(int, empty_intention(origin));
                return fail(self, s, int, &$text, "it has no answer".into(), notes);
            }};
        }
        // A step bdi-check does not follow at run time: noted, and the run stops there.
        macro_rules! or_beyond {
            ($r:expr, $text:expr) => {
                match $r {
                    Ok(v) => v,
                    Err(reason) => {
                        notes.push(Note::Beyond {
                            text: $text,
                            plan,
                            span: step.span,
                            reason,
                        });
                        return Flow::Gone;
                    }
                }
            };
        }
        match &step.kind {
            BodyStep::Action(t) if self.is_emission(t) => {
                // The agent's own explanation: said, not done; the world does not change.
                let term = value!(t);
                notes.push(Note::Action {
                    text: term.to_string(),
                    term,
                    stack: views,
                    plan,
                    span: step.span,
                    added: Vec::new(),
                    removed: Vec::new(),
                    origin,
                });
                return self.wait_for_feedback(s, int, None);
            }
            BodyStep::Action(t) => {
                let term = value!(t);
                let text = term.to_string();
                // The environment runs the action now; the intention waits for the
                // feedback, which the next cycle's `ProcAct` takes (Jason's pending action).
                let ga = match self.ground_action(&term) {
                    Ok(ga) if !ga.applicable(&s.beliefs) => {
                        Err("its precondition does not hold".to_string())
                    }
                    other => other,
                };
                let ga = match ga {
                    Ok(ga) => ga,
                    Err(reason) => {
                        notes.push(Note::ActionFailed {
                            text,
                            plan,
                            span: step.span,
                            reason: reason.clone(),
                        });
                        let failure = ActionFailure {
                            plan,
                            span: step.span,
                            action: term,
                            why: reason,
                        };
                        return self.wait_for_feedback(s, int, Some(failure));
                    }
                };
                let before = s.beliefs.clone();
                s.beliefs = ga.apply(&before);
                let (mut added, mut removed) = diff(&before, &s.beliefs);
                let after = env_before + added.len() - removed.len();
                self.java_order(&mut removed, env_before);
                self.java_order(&mut added, after);
                // Among several agents the change is perceived at the agent's next sense,
                // with every other agent's (see `System`).
                if !self.shared_world {
                    self.perceive(s, &added, &removed);
                }
                notes.push(Note::Action {
                    text,
                    term,
                    stack: views,
                    plan,
                    span: step.span,
                    added,
                    removed,
                    origin,
                });
                return self.wait_for_feedback(s, int, None);
            }
            BodyStep::Internal(t) => {
                let term = value!(t);
                let text = term.to_string();
                match term.functor().unwrap_or("") {
                    ".print" | ".println" => {
                        let out: String = term
                            .args()
                            .iter()
                            .map(|a| match a {
                                Term::Str(s) => s.to_string(),
                                Term::Var(_) => format!("{a}<no-value>"),
                                _ => a.to_string(),
                            })
                            .collect();
                        notes.push(Note::Printed(out));
                    }
                    f @ (".succeed_goal" | ".fail_goal") => {
                        let g = term.args().first().cloned().unwrap_or_else(Term::nil);
                        let fail = f == ".fail_goal";
                        self.normalize(frame);
                        let current = std::mem::replace(int, empty_intention(origin));
                        if fail && self.fails_a_bottom_goal(s, &current, &g) {
                            notes.push(Note::Beyond {
                                text,
                                plan,
                                span: step.span,
                                reason: format!(
                                    "{g} is the bottom goal of an intention: Jason 3 throws a NullPointerException inside .fail_goal here (Intention.dropGoal empties the intention, then TransitionSystem.findEventForFailure peeks at it), and bdi-check does not model that"
                                ),
                            });
                            return Flow::Gone;
                        }
                        notes.push(Note::Internal { text, plan, origin });
                        self.goal_directive(s, current, &g, fail, (plan, step.span), notes);
                        return Flow::Gone;
                    }
                    ".abolish" => {
                        // `Agent.abolish`: every belief that unifies goes, in belief-base
                        // order, each with its `-b` event.
                        let q = term.args().first().cloned().unwrap_or_else(Term::nil);
                        let gone: Vec<AtomId> = self
                            .beliefs(s)
                            .literal_answers(&q, &Substitution::new())
                            .into_iter()
                            .map(|(a, _)| a)
                            .collect();
                        gone.iter().for_each(|a| s.beliefs.remove(*a));
                        // Every source goes (`Agent.abolish` removes the whole belief).
                        s.told.retain(|t| !gone.contains(&t.atom));
                        self.perceive(s, &[], &gone);
                        notes.push(Note::Belief {
                            text: text.clone(),
                            plan,
                            added: Vec::new(),
                            removed: gone,
                            origin,
                        });
                    }
                    ".random" => {
                        // Jason's answer is random; here it is the `choice`-th possible one.
                        let args = term.args();
                        let (out, value) = match args.first() {
                            Some(l) if l.is_list() => (
                                args.get(1),
                                l.list_elements().and_then(|(e, _)| e.get(choice).cloned()),
                            ),
                            first => (
                                first,
                                self.random_values().get(choice).map(|v| Term::num(*v)),
                            ),
                        };
                        let mut u = frame.subst.clone();
                        let bound = match (out, value) {
                            (Some(out), Some(v)) => unify(out, &v, &mut u),
                            _ => false,
                        };
                        if !bound {
                            no_answer!(text);
                        }
                        frame.subst = u;
                        let text = frame.subst.apply(t).to_string();
                        notes.push(Note::Internal { text, plan, origin });
                        self.normalize(frame);
                        return Flow::Continue;
                    }
                    ".drop_desire" | ".drop_intention" => {
                        let g = term.args().first().cloned().unwrap_or_else(Term::nil);
                        let matches = |i: &Intention| {
                            i.frames.iter().any(|f| {
                                f.trigger.kind == TriggerKind::Achieve
                                    && crate::model::unifier(&g, &f.trigger.literal).is_some()
                            })
                        };
                        s.intentions.retain(|i| !matches(i));
                        // `drop_intention.dropInt` drops pending intentions too: the wait
                        // ends with them.
                        s.waiting.retain(|w| !matches(&w.intention));
                        s.events.retain(|e| {
                            let goal_matches = e.trigger.kind == TriggerKind::Achieve
                                && crate::model::unifier(&g, &e.trigger.literal).is_some();
                            !(goal_matches || e.intention.as_ref().is_some_and(matches))
                        });
                        if own_drop == Some(true) {
                            notes.push(Note::Internal { text, plan, origin });
                            return Flow::Gone;
                        }
                    }
                    f @ (".send" | ".broadcast") => {
                        let beyond = |reason: String, notes: &mut Vec<Note>| {
                            notes.push(Note::Beyond {
                                text: text.clone(),
                                plan,
                                span: step.span,
                                reason,
                            });
                            Flow::Gone
                        };
                        let send = match self.message(f, &term) {
                            Ok(m) => m,
                            Err(reason) => return beyond(reason, notes),
                        };
                        let to: Vec<u8> = match send.receiver {
                            // `LocalAgArch.broadcast`: every agent but the sender.
                            None => (0..self.agents.len() as u8)
                                .filter(|&k| k != self.me)
                                .collect(),
                            Some(name) => match self.agents.iter().position(|a| *a == name) {
                                Some(k) => vec![k as u8],
                                None => {
                                    // `LocalAgArch.sendMsg`: ReceiverNotFoundException,
                                    // annotated `agent_not_found(Name)`.
                                    let int = std::mem::replace(int, empty_intention(origin));
                                    let failed = int
                                        .frames
                                        .last()
                                        .map(|f| f.trigger.clone())
                                        .expect("frame");
                                    let missing =
                                        Term::structure("agent_not_found", vec![Term::atom(&name)]);
                                    self.fail_intention(
                                        s,
                                        int,
                                        &failed,
                                        Some((plan, step.span)),
                                        &format!("{text}: no agent is named `{name}` (receiver_not_found)"),
                                        ("receiver_not_found", &[missing]),
                                        notes,
                                    );
                                    return Flow::Gone;
                                }
                            },
                        };
                        if !self.shared_world && !to.is_empty() {
                            return beyond(
                                "a message to the agent itself: bdi-check delivers messages in projects of several agents".into(),
                                notes,
                            );
                        }
                        // An ask whose answer the intention waits for: an id no answer
                        // still on its way has (stdlib `send`: `setSyncAskMsgId`).
                        let ask = match &send.answer {
                            None => None,
                            Some(_) => match (0..64u8).find(|k| s.asked >> k & 1 == 0) {
                                Some(k) => Some(k),
                                None => {
                                    return beyond(
                                        "64 asks already wait for their answers, the most bdi-check keeps".into(),
                                        notes,
                                    )
                                }
                            },
                        };
                        notes.push(Note::Internal {
                            text: text.clone(),
                            plan,
                            origin,
                        });
                        notes.push(Note::Sent {
                            to,
                            performative: send.performative,
                            content: send.content,
                            ask,
                            reply_to: send.reply_to,
                        });
                        self.normalize(frame);
                        if let (Some(k), Some(answer)) = (ask, send.answer) {
                            // The intention waits in `C.PI` until the answer comes.
                            s.asked |= 1 << k;
                            let waiting = std::mem::replace(int, empty_intention(origin));
                            s.waiting.push(crate::semantics::state::Waiting {
                                intention: waiting,
                                step: (plan, block, pos, step.span),
                                ask: Some((k, answer)),
                                timed: send.timed,
                                woken: false,
                            });
                            return Flow::Gone;
                        }
                        return Flow::Continue;
                    }
                    ".kqml_untell" => {
                        // `--Content[source(Sender)]`: that source goes; the belief with
                        // it when it has no other (a new focus: the event is external).
                        let (c, sender) = (&term.args()[0], &term.args()[1]);
                        let removed = self.untell(s, c, sender);
                        notes.push(Note::Belief {
                            text: format!("--{}", crate::model::internal::nested_source(c, sender)),
                            plan,
                            added: Vec::new(),
                            removed: removed
                                .iter()
                                .filter(|(_, gone)| *gone)
                                .map(|(a, _)| *a)
                                .collect(),
                            origin,
                        });
                        if let Some((a, _)) = removed.first() {
                            let literal = self.beliefs(s).atom_term(*a).without_annots();
                            let literal = crate::model::internal::nested_source(&literal, sender);
                            self.post_event(
                                s,
                                Event {
                                    trigger: EventTrigger {
                                        op: TriggerOp::Del,
                                        kind: TriggerKind::Belief,
                                        literal,
                                    },
                                    intention: None,
                                    origin: Origin::Spawned,
                                    posted_at: None,
                                },
                            );
                        }
                    }
                    f @ (".kqml_tell_how" | ".kqml_untell_how") => {
                        // `.add_plan(Content, Sender)` and `.remove_plan(Content, Sender)`
                        // of Jason's plans for messages: the plans are compiled (see
                        // `model::know_how`), the content names them.
                        let change = or_beyond!(self.know_how_change(f, &term), text);
                        notes.push(Note::Internal {
                            text: text.clone(),
                            plan,
                            origin,
                        });
                        if let Err(why) = self.change_library(s, &change) {
                            let int = std::mem::replace(int, empty_intention(origin));
                            return fail(self, s, int, &text, why, notes);
                        }
                        self.normalize(frame);
                        return Flow::Continue;
                    }
                    ".kqml_relevant_plans" => {
                        // `.relevant_plans(Trigger, Plans)`, each plan as its key.
                        let plans = or_beyond!(self.relevant_keys(s, &term.args()[0]), text);
                        let mut u = frame.subst.clone();
                        if !unify(&term.args()[1], &plans, &mut u) {
                            no_answer!(text);
                        }
                        frame.subst = u;
                        let text = frame.subst.apply(t).to_string();
                        notes.push(Note::Internal { text, plan, origin });
                        self.normalize(frame);
                        return Flow::Continue;
                    }
                    ".kqml_error" => {
                        notes.push(Note::Printed(
                            self.communication_error(&term, failed_query.as_ref()),
                        ));
                    }
                    _ => {
                        let f = Formula::Call(t.clone());
                        match self
                            .beliefs_running(s, &running)
                            .answers(&f, &frame.subst)
                            .into_iter()
                            .next()
                        {
                            Some(a) => frame.subst = a,
                            None => no_answer!(text),
                        }
                    }
                }
                notes.push(Note::Internal { text, plan, origin });
            }
            BodyStep::Library { change, text, call } => {
                notes.push(Note::Internal {
                    text: text.clone(),
                    plan,
                    origin,
                });
                if let Err(why) = self.change_library(s, change) {
                    let int = std::mem::replace(int, empty_intention(origin));
                    let queued = s.events.len();
                    let flow = fail(self, s, int, text, why, notes);
                    if !call {
                        s.events.iter_mut().skip(queued).for_each(no_code);
                    }
                    return flow;
                }
            }
            BodyStep::Achieve { goal, new_focus } => {
                let written = renamed_apart(&value!(goal), depth);
                let trigger = EventTrigger {
                    op: TriggerOp::Add,
                    kind: TriggerKind::Achieve,
                    literal: with_source(&written, "self"),
                };
                if *new_focus {
                    self.post_event(
                        s,
                        Event {
                            trigger,
                            intention: None,
                            origin: Origin::Spawned,
                            posted_at: Some((plan, step.span)),
                        },
                    );
                } else {
                    return self.post_subgoal(s, int, trigger, written, (plan, step.span));
                }
            }
            BodyStep::Test(f) => {
                match self
                    .beliefs_running(s, &running)
                    .answers(f, &frame.subst)
                    .into_iter()
                    .next()
                {
                    Some(a) => frame.subst = a,
                    None => {
                        // Jason's `applyExecInt` (test): with no answer, a literal whose
                        // `+?g` some plan is relevant for becomes that event, as a subgoal.
                        if let Formula::Literal(t) = f {
                            let written = renamed_apart(&frame.subst.apply(t), depth);
                            let trigger = EventTrigger {
                                op: TriggerOp::Add,
                                kind: TriggerKind::Test,
                                literal: with_source(&written, "self"),
                            };
                            if !self.relevant_in(s.library.as_deref(), &trigger).is_empty() {
                                let at = (plan, step.span);
                                return self.post_subgoal(s, int, trigger, written, at);
                            }
                        }
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(self, s, int, "test goal", "it has no answer".into(), notes);
                    }
                }
            }
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                let lit = value!(t);
                let mut removed = Vec::new();
                let mut added = Vec::new();
                if matches!(step.kind, BodyStep::DelBel(_) | BodyStep::DelAddBel(_)) {
                    // `-b` removes the first belief that unifies; `-+b` the first belief of
                    // the same predicate, whatever its arguments.
                    let pattern = match step.kind {
                        BodyStep::DelAddBel(_) => {
                            let vars = (0..lit.arity())
                                .map(|i| Term::var(&format!("_DelAdd{i}")))
                                .collect();
                            Term::structure(lit.functor().unwrap_or(""), vars)
                        }
                        _ => lit.clone(),
                    };
                    let hits = self
                        .beliefs_running(s, &running)
                        .literal_answers(&pattern, &frame.subst);
                    if let Some((a, answer)) = hits.into_iter().next() {
                        if s.told(a).is_some() {
                            return told_beyond(self, step, plan, notes);
                        }
                        s.beliefs.remove(a);
                        removed.push(a);
                        if matches!(step.kind, BodyStep::DelBel(_)) {
                            frame.subst = answer;
                        }
                    }
                }
                // What the events tell: `-+b` of a belief that holds removes it, then adds it.
                let ev_removed = removed.clone();
                if matches!(step.kind, BodyStep::AddBel(_) | BodyStep::DelAddBel(_)) {
                    match self.ground_atom(&lit) {
                        Some(a) if s.told(a).is_some() => {
                            return told_beyond(self, step, plan, notes);
                        }
                        Some(a) => {
                            if !s.beliefs.contains(a) {
                                s.beliefs.insert(a);
                                added.push(a);
                            }
                            removed.retain(|r| *r != a);
                            added.retain(|x| !removed.contains(x));
                        }
                        None => {
                            // Jason would add it: the run goes where the model cannot follow.
                            let reason = match &self.project.manifest.bounds.numbers {
                                Some(n) => format!(
                                    "the belief is not an atom of the model (a free variable, or a number outside {} to {}, `[bounds] numbers`)",
                                    n.value.0, n.value.1
                                ),
                                None => "the belief is not an atom of the model (a free variable, or a number: declare `[bounds] numbers`)".into(),
                            };
                            // The transition is not followed: leave the beliefs as
                            // they were, so both representations agree on it.
                            removed.iter().for_each(|a| s.beliefs.insert(*a));
                            notes.push(Note::Beyond {
                                text: format!("+{lit}"),
                                plan,
                                span: step.span,
                                reason,
                            });
                            *int = empty_intention(origin);
                            return Flow::Gone;
                        }
                    }
                }
                // Jason's default `sameFocus`: the first event of the change the step asks
                // for carries the intention, which waits in it (`-+b`'s removal is a
                // change of its own, with an event of its own).
                let focus = match step.kind {
                    BodyStep::DelBel(_) => ev_removed.first().map(|a| (TriggerOp::Del, *a)),
                    _ => added.first().map(|a| (TriggerOp::Add, *a)),
                };
                let focused = self.perceive_with_focus(s, &added, &ev_removed, focus);
                let sign = match step.kind {
                    BodyStep::AddBel(_) => "+",
                    BodyStep::DelBel(_) => "-",
                    _ => "-+",
                };
                notes.push(Note::Belief {
                    text: format!("{sign}{lit}"),
                    plan,
                    added,
                    removed,
                    origin,
                });
                if let Some(trigger) = focused {
                    return self.suspend_in(s, int, trigger, (plan, step.span));
                }
            }
            BodyStep::Constraint(op, a, b) => {
                let (x, y) = (value!(a), value!(b));
                let text = format!("{x} {} {y}", op.symbol());
                match relation(*op, &x, &y, &frame.subst) {
                    Some(u) => frame.subst = u,
                    None => {
                        let int = std::mem::replace(int, empty_intention(origin));
                        return fail(
                            self,
                            s,
                            int,
                            &text,
                            "the constraint does not hold".into(),
                            notes,
                        );
                    }
                }
            }
            BodyStep::Wait { timeout, .. } => {
                // `(long) time.solve()`: a timer runs for a timeout of at least 0.
                let limit = match timeout {
                    Some(t) => Some(value!(t)),
                    None => None,
                };
                let timed = match limit {
                    None => false,
                    Some(t) => match t.as_f64() {
                        Some(ms) => ms.trunc() >= 0.0,
                        None => {
                            let int = std::mem::replace(int, empty_intention(origin));
                            let text = step_text(self, step.span);
                            return fail(
                                self,
                                s,
                                int,
                                &text,
                                format!("its timeout `{t}` is not a number"),
                                notes,
                            );
                        }
                    },
                };
                notes.push(Note::Internal {
                    text: step_text(self, step.span),
                    plan,
                    origin,
                });
                self.normalize(frame);
                let waiting = std::mem::replace(int, empty_intention(origin));
                return match self.suspend(s, waiting, (plan, block, pos, step.span), timed) {
                    Some(back) => {
                        *int = back;
                        Flow::Continue
                    }
                    None => Flow::Gone,
                };
            }
            BodyStep::If { branches, .. } => {
                let kids = &blocks.children[&(block, pos)];
                let b = self.beliefs_running(s, &running);
                let mut chosen = kids.last().copied();
                for (k, (cond, _)) in branches.iter().enumerate() {
                    if let Some(a) = b.answers(cond, &frame.subst).into_iter().next() {
                        frame.subst = a;
                        chosen = Some(kids[k]);
                        break;
                    }
                }
                if let Some(child) = chosen {
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::Seq,
                    });
                }
            }
            BodyStep::While(cond, _) => {
                let child = blocks.children[&(block, pos)][0];
                let base = frame.subst.clone();
                if let Some(a) = self
                    .beliefs_running(s, &running)
                    .answers(cond, &base)
                    .into_iter()
                    .next()
                {
                    frame.subst = a;
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::While {
                            outer: block,
                            at: pos,
                            base,
                        },
                    });
                }
            }
            BodyStep::For(cond, _) => {
                let child = blocks.children[&(block, pos)][0];
                let mut answers = self
                    .beliefs_running(s, &running)
                    .answers(cond, &frame.subst);
                if !answers.is_empty() {
                    let base = std::mem::replace(&mut frame.subst, answers.remove(0));
                    frame.cursors.push(Cursor {
                        block: child,
                        pos: 0,
                        kind: CursorKind::For {
                            rest: answers,
                            base,
                        },
                    });
                }
            }
        }
        self.normalize(frame);
        Flow::Continue
    }

    /// `int` sent an environment action: it waits, its step done (or failed, with why),
    /// for the feedback that the next cycle's `ProcAct` takes.
    fn wait_for_feedback(
        &self,
        s: &mut State,
        int: &mut Intention,
        failure: Option<ActionFailure>,
    ) -> Flow {
        if let Some(top) = int.frames.last_mut() {
            self.normalize(top);
        }
        let origin = int.origin;
        let intention = std::mem::replace(int, empty_intention(origin));
        s.pending = Some(Pending { intention, failure });
        Flow::Gone
    }

    /// Suspends `int` on the subgoal event `trigger` (`!g`, or `?g` handled by a `+?g`
    /// plan): its top plan waits for `g` (its current step, `written`: the literal as the
    /// body has it, without the `source(self)` the event gets), in the event.
    /// Jason's applyExecInt on a belief update that changed something, with the default
    /// `sameFocus`: the intention is suspended in the update's event, queued whether or
    /// not a plan is relevant for it (`updateEvents(result, curInt)`). Its step is done:
    /// when the event's plan ends, or the event has none, the intention goes on after it.
    fn suspend_in(
        &self,
        s: &mut State,
        int: &mut Intention,
        trigger: EventTrigger,
        at: (u32, Span),
    ) -> Flow {
        let origin = int.origin;
        if let Some(top) = int.frames.last_mut() {
            self.normalize(top);
        }
        let suspended = std::mem::replace(int, empty_intention(origin));
        self.queue_event(
            s,
            Event {
                trigger,
                intention: Some(suspended),
                origin,
                posted_at: Some(at),
            },
        );
        Flow::Suspended
    }

    fn post_subgoal(
        &self,
        s: &mut State,
        int: &mut Intention,
        trigger: EventTrigger,
        written: Term,
        at: (u32, Span),
    ) -> Flow {
        let origin = int.origin;
        if let Some(top) = int.frames.last_mut() {
            // Jason's applyClrInt compares a finished failure plan's goal with the body
            // term of the step below (`getCurrentStep().getBodyTerm()`), which has no
            // `source(self)`: `!g` then matches a `-!g` that `.fail_goal(g)` posted.
            top.calling = Some(written);
            self.normalize(top);
        }
        let suspended = std::mem::replace(int, empty_intention(origin));
        self.post_event(
            s,
            Event {
                trigger,
                intention: Some(suspended),
                origin,
                posted_at: Some(at),
            },
        );
        Flow::Suspended
    }

    /// Whether the agent explains itself (the manifest names an `emitted_by` action).
    pub fn explains_itself(&self) -> bool {
        self.emitted_by.is_some()
    }

    /// Whether an action is the agent's own explanation (`[explanation] emitted_by`).
    pub fn is_emission(&self, t: &Term) -> bool {
        self.emitted_by.is_some() && t.functor() == self.emitted_by.as_deref()
    }

    /// The ground action a term names, or why there is none.
    pub(super) fn ground_action(
        &self,
        t: &Term,
    ) -> Result<&crate::model::ground::GroundAction, String> {
        let name = t.functor().ok_or("it is not an action")?;
        // An action with an `?agent` parameter is done by this agent.
        let full;
        let t = match self.project.vocabulary.action(name) {
            Some((_, a)) if a.actor.is_some() => {
                full = a.done_by(t, &self.agent_name);
                &full
            }
            _ => t,
        };
        let args = self.objects(t).ok_or("its arguments are not all objects")?;
        self.project.actions.get(name, &args).ok_or_else(|| {
            format!("`{name}` with these arguments is not an action of the PDDL domain")
        })
    }

    fn objects(&self, t: &Term) -> Option<Vec<ObjectId>> {
        t.args()
            .iter()
            .map(|a| self.project.universe.object_of(a))
            .collect()
    }

    /// The atom a ground literal names (annotations ignored).
    pub(super) fn ground_atom(&self, t: &Term) -> Option<AtomId> {
        let p = self.project.atoms.pred_of_literal(t)?;
        self.project.atoms.id(p, &self.objects(t)?)
    }
}

/// A subgoal's literal as the plan at `depth` of its stack posts it, before Jason's
/// `prepareBodyForEvent` gives its event `source(self)`: the plan's variables renamed to
/// the next generation (the subgoal's plan has variables of its own).
fn renamed_apart(t: &Term, depth: usize) -> Term {
    t.map_vars(&mut |v| {
        if v.generation() == 0 {
            Term::from(v.with_generation(depth as u32 + 1))
        } else {
            Term::from(v.clone())
        }
    })
}

/// A step as written, for notes.
fn step_text(sem: &Semantics, span: Span) -> String {
    sem.project.map.slice(span).trim().to_string()
}

/// What became of the intention after a step.
enum Flow {
    /// It goes on (and goes to the back of the queue).
    Continue,
    /// It waits in an event for a subgoal's plan.
    Suspended,
    /// It was dropped or handed to a failure event.
    Gone,
}

/// A belief update of a belief other agents told: Jason's `+b`/`-b` add or remove only
/// the agent's own source (`source(self)`), which bdi-check does not model yet.
fn told_beyond(
    sem: &Semantics,
    step: &crate::model::plans::Step,
    plan: u32,
    notes: &mut Vec<Note>,
) -> Flow {
    notes.push(Note::Beyond {
        text: step_text(sem, step.span),
        plan,
        span: step.span,
        reason: "the belief was told by another agent: Jason would change only its own source of it (`source(self)`), and bdi-check does not model that yet".into(),
    });
    Flow::Gone
}

fn empty_intention(origin: Origin) -> Intention {
    Intention {
        frames: Vec::new(),
        origin,
    }
}

fn diff(before: &AtomSet, after: &AtomSet) -> (Vec<AtomId>, Vec<AtomId>) {
    let added = after.iter().filter(|a| !before.contains(*a)).collect();
    let removed = before.iter().filter(|a| !after.contains(*a)).collect();
    (added, removed)
}
