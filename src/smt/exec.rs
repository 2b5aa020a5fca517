//! Symbolic execution of a plan body for the `precondition` check.
//!
//! The execution starts from a state satisfying the invariants in which the plan is
//! applicable (its trigger matches an event of the declared types and its context holds,
//! its variables bound symbolically) and follows the body step by step; at every
//! environment action it asks whether the precondition can be false. What each step does:
//!
//! * an action: its precondition is assumed from then on (had it failed, the plan would have
//!   stopped there), and its effects are applied, for whichever ground action the arguments
//!   select;
//! * `!g`: the atoms of g's [summary](super::summary) change as the summary allows;
//!   `!!g` also after every later step, since the new intention runs interleaved;
//! * `?f`, `X = t`, `.count(...)`: assumed, binding their variables;
//! * `+b`, `-b`, `-+b`: the mental note changes;
//! * `if`: each branch under its condition (and the negation of the earlier ones), the
//!   states joined after; `while`/`for`: the body from a state where what the body may
//!   change has changed as the summary allows, and after the loop likewise;
//! * everything else (`.print`, an undefined action) changes nothing.
//!
//! After every step the invariants are assumed again: they hold in every reachable state
//! (`verify` checks that, `action-breaks-invariant` checks the actions). Other intentions
//! running between two steps are not modelled (SPEC's "given the context and the effects of
//! the earlier steps"), and a context's answer is any answer, not only Jason's first: both
//! make the check an over-approximation, which is why a failure is a warning.

use super::encode::{and, or, val_eq, Enc, Env, Frame, State, Unsupported, Val};
use super::lint::{Base, Group, Linter};
use super::solve::{truth, Outcome};
use super::summary::Effects;
use super::text;
use crate::model::atoms::AtomId;
use crate::model::ground::GroundAction;
use crate::model::plans::{BodyStep, Formula, Plan, Step};
use crate::model::term::Term;
use crate::syntax::Span;
use std::collections::BTreeSet;
use z3::ast::{Bool, Int};

/// The answer for one action step.
#[derive(Debug)]
pub(super) enum PreResult {
    /// The precondition holds whenever the step runs.
    Pass,
    /// It may not hold: the ground action selected (`None`: no action of the domain fits
    /// the arguments), the literals at fault at that step, and the plan's start state.
    Fail {
        instance: Option<String>,
        lits: Vec<String>,
        initial: Vec<String>,
        requests: Vec<String>,
    },
    /// Not decided.
    Unknown(String),
}

/// One checked action step.
#[derive(Debug)]
pub(super) struct StepCheck {
    pub span: Span,
    pub action: String,
    pub result: PreResult,
}

type StepErr = (Span, Unsupported);

/// Checks every action step of `plan` (of group `g`). Also returns where the execution had
/// to stop because of a construct the encoding does not cover.
pub(super) fn run(l: &Linter, g: &Group, plan: &Plan) -> (Vec<StepCheck>, Option<StepErr>) {
    let (ints, event, dom) = l.event(g);
    let mut ex = Exec {
        l,
        base: l.base(),
        g,
        ints,
        frame: l.enc.frame(),
        volatile: Effects::default(),
        checks: Vec::new(),
    };
    let mut env = Env::new();
    let start = (|| -> Enc<Bool> {
        let rel = l.enc.relevant(&plan.trigger.literal, &event, &mut env)?;
        let ctx = l
            .enc
            .assert_formula(&plan.context, &mut env, &mut ex.frame, &l.enc.base)?;
        Ok(and(vec![dom, rel, ctx]))
    })();
    let p0 = match start {
        Ok(b) => ex.path(vec![b]),
        Err(u) => {
            return (
                Vec::new(),
                Some((plan.context_span.unwrap_or(plan.span), u)),
            )
        }
    };
    let result = ex.steps(&plan.body, l.enc.base.clone(), &mut env, p0);
    (ex.checks, result.err())
}

struct Exec<'a, 'p> {
    l: &'a Linter<'p>,
    base: Base,
    g: &'a Group,
    ints: Vec<Int>,
    frame: Frame,
    /// What intentions started with `!!` may change between any two steps.
    volatile: Effects,
    checks: Vec<StepCheck>,
}

impl Exec<'_, '_> {
    /// A new path literal implying every part.
    fn path(&self, parts: Vec<Bool>) -> Bool {
        let p = self.l.enc.fresh_bool("path");
        self.base.sess.solver.assert(p.implies(and(parts)));
        p
    }

    fn invariants(&self, st: &State) -> Bool {
        and(self
            .l
            .p
            .invariants
            .iter()
            .map(|(_, c)| self.l.enc.cond(c, st))
            .collect())
    }

    /// `st` after something that may change what `eff` says, as it says.
    fn havoc(&self, st: &State, eff: &Effects) -> State {
        let mut out = st.clone();
        for a in eff.touched() {
            let i = a.0 as usize;
            let h = self.l.enc.fresh_bool("changed");
            let (add, del) = (eff.add.contains(&a), eff.del.contains(&a));
            if add && !del {
                self.base.sess.solver.assert(st[i].implies(&h));
            } else if del && !add {
                self.base.sess.solver.assert(h.implies(&st[i]));
            }
            out[i] = h;
        }
        out
    }

    /// `st` where each selected atom may become true (`add`) or false, the others as they
    /// were.
    fn havoc_selected(&self, st: &State, targets: Vec<(AtomId, Bool)>, add: bool) -> State {
        let mut out = st.clone();
        for (a, sel) in targets {
            let i = a.0 as usize;
            let h = self.l.enc.fresh_bool("changed");
            let solver = &self.base.sess.solver;
            solver.assert(sel.not().implies(h.iff(&st[i])));
            if add {
                solver.assert(st[i].implies(&h));
            } else {
                solver.assert(h.implies(&st[i]));
            }
            out[i] = h;
        }
        out
    }

    fn havoc_step(&self, st: &State, p: &Bool, eff: &Effects) -> (State, Bool) {
        if eff.is_empty() {
            return (st.clone(), p.clone());
        }
        let next = self.havoc(st, eff);
        let q = self.path(vec![p.clone(), self.invariants(&next)]);
        (next, q)
    }

    /// A state whose atoms in `changes` are defined by the given values.
    fn define(&self, st: &State, changes: Vec<(AtomId, Bool)>) -> State {
        let mut next = st.clone();
        for (a, v) in changes {
            let n = self.l.enc.fresh_bool("after");
            self.base.sess.solver.assert(n.iff(&v));
            next[a.0 as usize] = n;
        }
        next
    }

    fn steps(
        &mut self,
        steps: &[Step],
        st: State,
        env: &mut Env,
        p: Bool,
    ) -> Result<(State, Bool), StepErr> {
        let (mut st, mut p) = (st, p);
        for s in steps {
            (st, p) = self.step(s, st, env, p)?;
            if !self.volatile.is_empty() {
                (st, p) = self.havoc_step(&st, &p, &self.volatile.clone());
            }
        }
        Ok((st, p))
    }

    fn step(
        &mut self,
        s: &Step,
        st: State,
        env: &mut Env,
        p: Bool,
    ) -> Result<(State, Bool), StepErr> {
        let at = |u: Unsupported| (s.span, u);
        match &s.kind {
            BodyStep::Action(t) => self.action(t, s.span, st, env, p).map_err(at),
            BodyStep::Internal(t) => match t.functor() {
                Some(".count" | ".member" | ".desire" | ".intend") => self
                    .assume(&Formula::Call(t.clone()), st, env, p)
                    .map_err(at),
                _ => Ok((st, p)),
            },
            BodyStep::Achieve { goal, new_focus } => {
                let eff = goal
                    .functor()
                    .and_then(|f| self.l.sum.goal(f, goal.arity()))
                    .cloned()
                    .unwrap_or_default();
                if *new_focus {
                    self.volatile.absorb(&eff);
                }
                Ok(self.havoc_step(&st, &p, &eff))
            }
            BodyStep::Test(f) => self.assume(f, st, env, p).map_err(at),
            BodyStep::Constraint(op, a, b) => self
                .assume(&Formula::Rel(*op, a.clone(), b.clone()), st, env, p)
                .map_err(at),
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                self.belief(&s.kind, t, st, env, p).map_err(at)
            }
            BodyStep::If {
                branches,
                else_body,
            } => self.branch(branches, else_body, st, env, p, s.span),
            BodyStep::While(c, body) => self.repeat(c, body, true, st, env, p, s.span),
            // The plan library is no part of the beliefs.
            BodyStep::Library { .. } => Ok((st, p)),
            BodyStep::For(c, body) => self.repeat(c, body, false, st, env, p, s.span),
            // While it waits, other intentions run, as between any two steps; what the
            // event or condition binds is left unconstrained.
            BodyStep::Wait { .. } => Ok((st, p)),
        }
    }

    fn assume(&mut self, f: &Formula, st: State, env: &mut Env, p: Bool) -> Enc<(State, Bool)> {
        let b = self.l.enc.assert_formula(f, env, &mut self.frame, &st)?;
        let q = self.path(vec![p, b]);
        Ok((st, q))
    }

    fn action(
        &mut self,
        t: &Term,
        span: Span,
        st: State,
        env: &mut Env,
        p: Bool,
    ) -> Enc<(State, Bool)> {
        let l = self.l;
        let enc = &l.enc;
        let name = t.functor().unwrap_or("");
        let (params, full) = match l.p.vocabulary.action(name) {
            // An action with an `?agent` parameter is done by this agent.
            Some((_, a)) if a.call_arity() == t.arity() => {
                (a.params.clone(), a.done_by(t, &l.p.name))
            }
            // Undefined (its own finding) or the agent's explanation action: no effect.
            _ => return Ok((st, p)),
        };
        let t = &full;
        // Unbound arguments are some object of the parameter's type.
        let mut extra = Vec::new();
        let mut args = Vec::new();
        for (i, a) in t.args().iter().enumerate() {
            match a {
                Term::Var(v) if !env.contains_key(v) => {
                    let x = if v.is_anonymous() {
                        enc.fresh_int("argument")
                    } else {
                        self.frame.sym(v)
                    };
                    extra.push(enc.dom(&x, params[i]));
                    if !v.is_anonymous() {
                        env.insert(v.clone(), Val::Sym(x.clone()));
                    }
                    args.push(Val::Sym(x));
                }
                _ => match enc.term_val(a, env)? {
                    Some(v) => args.push(v),
                    None => {
                        return Err(Unsupported(format!(
                            "the argument `{a}` of `{t}` is not modelled by lint"
                        )))
                    }
                },
            }
        }
        // The ground actions the arguments can select, and when they select each.
        let mut cands: Vec<(&GroundAction, Bool)> = Vec::new();
        for g in
            l.p.actions
                .all()
                .iter()
                .filter(|g| &*g.name == name && g.args.len() == args.len())
        {
            let mut eqs = Vec::new();
            let mut possible = true;
            for (v, o) in args.iter().zip(&g.args) {
                match v {
                    Val::Obj(x) => possible &= x == o,
                    Val::Sym(_) => eqs.push(val_eq(v, &Val::Obj(*o))),
                    _ => possible = false,
                }
            }
            if possible {
                cands.push((g, and(eqs)));
            }
        }
        let pre_ok = or(cands
            .iter()
            .map(|(g, sel)| and(vec![sel.clone(), enc.cond(&g.pre, &st)]))
            .collect());
        let mut q = extra.clone();
        q.push(pre_ok.not());
        let result = match self.base.witness(&and(q), std::slice::from_ref(&p)).0 {
            Outcome::Sat(m) => {
                let (initial, requests) = l.plan_counterexample(&m, self.g, &self.ints);
                let chosen = cands.iter().find(|(_, sel)| truth(&m, sel));
                match chosen {
                    Some((g, _)) => {
                        let value = |a: AtomId| truth(&m, &st[a.0 as usize]);
                        let lits = text::why(&g.pre, &value)
                            .into_iter()
                            .map(|(a, v)| text::literal(&l.p.atoms, &l.p.universe, a, v))
                            .collect();
                        PreResult::Fail {
                            instance: Some(g.display(&l.p.universe)),
                            lits,
                            initial,
                            requests,
                        }
                    }
                    None => PreResult::Fail {
                        instance: None,
                        lits: Vec::new(),
                        initial,
                        requests,
                    },
                }
            }
            Outcome::Unsat(_) => PreResult::Pass,
            Outcome::Unknown(r) => PreResult::Unknown(r),
        };
        self.checks.push(StepCheck {
            span,
            action: text::term(t),
            result,
        });
        // From here on the action ran: its precondition held and its effects apply.
        let touched: BTreeSet<AtomId> = cands.iter().flat_map(|(g, _)| g.touched()).collect();
        let mut changes = Vec::new();
        for a in touched {
            let i = a.0 as usize;
            let mut value = st[i].clone();
            for (g, sel) in cands.iter().rev() {
                let adds: Vec<Bool> = g
                    .effects
                    .iter()
                    .filter(|e| e.add.contains(&a))
                    .map(|e| enc.cond(&e.when, &st))
                    .collect();
                let dels: Vec<Bool> = g
                    .effects
                    .iter()
                    .filter(|e| e.del.contains(&a))
                    .map(|e| enc.cond(&e.when, &st))
                    .collect();
                if adds.is_empty() && dels.is_empty() {
                    continue;
                }
                let after = or(vec![or(adds), and(vec![st[i].clone(), or(dels).not()])]);
                value = sel.ite(&after, &value);
            }
            changes.push((a, value));
        }
        let next = self.define(&st, changes);
        let mut parts = vec![p];
        parts.extend(extra);
        parts.push(pre_ok);
        parts.push(self.invariants(&next));
        let q = self.path(parts);
        Ok((next, q))
    }

    /// The atoms a belief term can be under `env`, each with when it is selected, and
    /// whether some argument is unbound (then which atom is meant is not known).
    fn belief_atoms(&self, t: &Term, env: &Env) -> Enc<(Vec<(AtomId, Bool)>, bool)> {
        let l = self.l;
        let atoms = &l.p.atoms;
        let Some(pred) = atoms.pred_of_literal(t) else {
            return Ok((Vec::new(), false));
        };
        if atoms.pred_params(pred).len() != t.arity() {
            return Ok((Vec::new(), false));
        }
        let mut vals = Vec::new();
        let mut wild = false;
        for a in t.args() {
            let v = l.enc.term_val(a, env)?;
            wild |= v.is_none();
            vals.push(v);
        }
        let mut out = Vec::new();
        'atoms: for a in atoms.atoms_of(pred) {
            let (_, objs) = atoms.decode(a);
            let mut eqs = Vec::new();
            for (v, o) in vals.iter().zip(objs.iter()) {
                match v {
                    None => {}
                    Some(Val::Obj(x)) if x == o => {}
                    Some(s @ Val::Sym(_)) => eqs.push(val_eq(s, &Val::Obj(*o))),
                    Some(_) => continue 'atoms,
                }
            }
            out.push((a, and(eqs)));
        }
        Ok((out, wild))
    }

    fn belief(
        &mut self,
        kind: &BodyStep,
        t: &Term,
        st: State,
        env: &mut Env,
        p: Bool,
    ) -> Enc<(State, Bool)> {
        let (targets, wild) = self.belief_atoms(t, env)?;
        let mut st1 = st.clone();
        if let BodyStep::DelAddBel(_) = kind {
            // `-+b` removes some belief of b's predicate first.
            let all = super::summary::same_predicate_atoms(self.l.p, t);
            let eff = Effects {
                add: BTreeSet::new(),
                del: all.into_iter().collect(),
            };
            st1 = self.havoc(&st, &eff);
        }
        let next = match (kind, wild) {
            (BodyStep::AddBel(_) | BodyStep::DelAddBel(_), false) => {
                let changes = targets
                    .into_iter()
                    .map(|(a, sel)| (a, or(vec![st1[a.0 as usize].clone(), sel])))
                    .collect();
                self.define(&st1, changes)
            }
            (BodyStep::DelBel(_), false) => {
                let changes = targets
                    .into_iter()
                    .map(|(a, sel)| (a, and(vec![st1[a.0 as usize].clone(), sel.not()])))
                    .collect();
                self.define(&st1, changes)
            }
            // An unbound argument: which selected atom changes is not known.
            (BodyStep::DelBel(_), true) => self.havoc_selected(&st1, targets, false),
            _ => self.havoc_selected(&st1, targets, true),
        };
        let q = self.path(vec![p, self.invariants(&next)]);
        Ok((next, q))
    }

    fn branch(
        &mut self,
        branches: &[(Formula, Vec<Step>)],
        else_body: &[Step],
        st: State,
        env: &mut Env,
        p: Bool,
        span: Span,
    ) -> Result<(State, Bool), StepErr> {
        let at = |u: Unsupported| (span, u);
        let mut ends: Vec<(State, Bool)> = Vec::new();
        let mut earlier_false: Vec<Bool> = Vec::new();
        for (c, body) in branches {
            let mut benv = env.clone();
            let cb = self
                .l
                .enc
                .assert_formula(c, &mut benv, &mut self.frame, &st)
                .map_err(at)?;
            let mut parts = vec![p.clone()];
            parts.extend(earlier_false.iter().cloned());
            parts.push(cb);
            let pk = self.path(parts);
            ends.push(self.steps(body, st.clone(), &mut benv, pk)?);
            self.frame.keep_only(env);
            earlier_false.push(self.l.enc.closed_formula(c, env, &st).map_err(at)?.not());
        }
        let mut parts = vec![p];
        parts.extend(earlier_false);
        let pe = self.path(parts);
        let mut eenv = env.clone();
        ends.push(self.steps(else_body, st.clone(), &mut eenv, pe)?);
        self.frame.keep_only(env);
        // Join: an atom whose value differs between branches gets the value of the branch
        // taken (the branches' path literals exclude each other).
        let pm = self.path(vec![or(ends.iter().map(|(_, q)| q.clone()).collect())]);
        let mut next = ends[0].0.clone();
        for i in 0..next.len() {
            if ends.iter().all(|(s, _)| s[i].ast_eq(&ends[0].0[i])) {
                continue;
            }
            let m = self.l.enc.fresh_bool("joined");
            for (s, q) in &ends {
                self.base.sess.solver.assert(q.implies(m.iff(&s[i])));
            }
            next[i] = m;
        }
        Ok((next, pm))
    }

    #[allow(clippy::too_many_arguments)]
    fn repeat(
        &mut self,
        c: &Formula,
        body: &[Step],
        is_while: bool,
        st: State,
        env: &mut Env,
        p: Bool,
        span: Span,
    ) -> Result<(State, Bool), StepErr> {
        let at = |u: Unsupported| (span, u);
        let mut eff = self.l.sum.steps(self.l.p, body);
        eff.absorb(&self.volatile.clone());
        // Any iteration starts from a state the body's summary allows.
        let (head, ph) = self.havoc_step(&st, &p, &eff);
        let mut lenv = env.clone();
        let cb = self
            .l
            .enc
            .assert_formula(c, &mut lenv, &mut self.frame, &head)
            .map_err(at)?;
        let pl = self.path(vec![ph, cb]);
        self.steps(body, head, &mut lenv, pl)?;
        self.frame.keep_only(env);
        let (after, pa) = self.havoc_step(&st, &p, &eff);
        if is_while {
            let done = self.l.enc.closed_formula(c, env, &after).map_err(at)?.not();
            let q = self.path(vec![pa, done]);
            return Ok((after, q));
        }
        Ok((after, pa))
    }
}
