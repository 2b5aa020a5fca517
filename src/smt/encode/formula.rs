//! Plan formulas as Jason queries: encoded left to right along each conjunction, in assert or
//! closed mode (see the module documentation), with disjunctions distributed where their
//! bindings are read later, and the trigger matched against an event.

use super::{
    and, conjuncts, ff, formula_vars, or, same_val, tt, tuples, val_eq, Enc, Encoder, Env, Frame,
    Mode, State, Unsupported, Val, MAX_INSTANCES,
};
use crate::model::plans::Formula;
use crate::model::term::{Term, Var};
use crate::model::universe::{ObjectId, TypeId};
use crate::syntax::ast::RelOp;
use std::collections::BTreeSet;
use z3::ast::Bool;

/// How a conjunct binds a variable that was unbound before it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Binder {
    /// By matching an atom: the variable ranges over the objects of this type.
    Domain(TypeId),
    /// By computing a value (`X = a`, `.count(q, N)`).
    Value,
}

impl Encoder<'_> {
    /// Whether the plan's trigger literal matches the event `event` (one value per
    /// argument), binding the trigger's variables in `env`.
    pub fn relevant(&self, trigger: &Term, event: &[Val], env: &mut Env) -> Enc<Bool> {
        if trigger.is_negated() {
            return Err(Unsupported(format!(
                "the strongly negated trigger `{trigger}` is not modelled by lint"
            )));
        }
        if trigger
            .annots()
            .iter()
            .any(|a| a.functor() != Some("source"))
        {
            return Err(Unsupported(format!(
                "annotations other than `source(...)` in the trigger `{trigger}` are not modelled by lint"
            )));
        }
        if trigger.arity() != event.len() {
            return Ok(ff());
        }
        let mut eqs = Vec::new();
        for (t, e) in trigger.args().iter().zip(event) {
            match t {
                Term::Var(v) => match env.get(v) {
                    None => {
                        env.insert(v.clone(), e.clone());
                    }
                    Some(x) => eqs.push(val_eq(x, e)),
                },
                _ => match self.term_val(t, env)? {
                    Some(x @ Val::Obj(_)) => eqs.push(val_eq(&x, e)),
                    // The event stands for goals over objects; a subgoal may pass any term
                    // (`!state([])`), so a trigger that asks for another says nothing here.
                    Some(_) => {
                        return Err(Unsupported(format!(
                            "the trigger argument `{t}` is not an object: lint models events over objects"
                        )))
                    }
                    None => {
                        return Err(Unsupported(format!(
                            "the trigger argument `{t}` is not modelled by lint"
                        )))
                    }
                },
            }
        }
        Ok(and(eqs))
    }

    /// Encodes `f` as holding on `st`, binding its variables in `env` (symbolically, in
    /// `frame`) for what follows it.
    pub fn assert_formula(
        &self,
        f: &Formula,
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
    ) -> Enc<Bool> {
        self.expanded.set(0);
        self.chain(&[f], env, frame, st, Mode::Assert)
    }

    /// Encodes `f` on `st` as a closed formula: the bindings it makes stay inside.
    pub fn closed_formula(&self, f: &Formula, env: &Env, st: &State) -> Enc<Bool> {
        let mut frame = self.frame();
        let mut env = env.clone();
        self.expanded.set(0);
        self.chain(&[f], &mut env, &mut frame, st, Mode::Closed)
    }

    /// The conjuncts of a formula asserted one by one (for unsat cores): the formula is
    /// their conjunction. A leading disjunction that must be distributed makes one item.
    pub fn assert_conjuncts(
        &self,
        f: &Formula,
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
    ) -> Enc<Vec<(String, Bool)>> {
        let elems = conjuncts(f);
        let mut out = Vec::new();
        self.expanded.set(0);
        for (i, e) in elems.iter().enumerate() {
            let rest = &elems[i + 1..];
            if let Formula::Or(..) = e {
                let later = vars_of(rest);
                if self.binds(e, env).iter().any(|(v, _)| later.contains(v)) {
                    let text = elems[i..]
                        .iter()
                        .map(|f| crate::smt::text::formula(f))
                        .collect::<Vec<_>>()
                        .join(" & ");
                    out.push((text, self.chain(&elems[i..], env, frame, st, Mode::Assert)?));
                    return Ok(out);
                }
            }
            out.push((
                crate::smt::text::formula(e),
                self.element(e, env, frame, st, Mode::Assert)?,
            ));
        }
        Ok(out)
    }

    pub(super) fn chain(
        &self,
        elems: &[&Formula],
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
        mode: Mode,
    ) -> Enc<Bool> {
        let Some((&first, rest)) = elems.split_first() else {
            return Ok(tt());
        };
        if let Formula::And(a, b) = first {
            let mut v: Vec<&Formula> = vec![a, b];
            v.extend_from_slice(rest);
            return self.chain(&v, env, frame, st, mode);
        }
        let later = vars_of(rest);
        if let Formula::Or(a, b) = first {
            if self
                .binds(first, env)
                .iter()
                .any(|(v, _)| later.contains(v))
            {
                // Distribute: each branch with its own bindings, followed by the rest.
                let mut ea = env.clone();
                let mut va: Vec<&Formula> = vec![a];
                va.extend_from_slice(rest);
                let x = self.chain(&va, &mut ea, frame, st, mode)?;
                let mut eb = env.clone();
                let mut vb: Vec<&Formula> = vec![b];
                vb.extend_from_slice(rest);
                let y = self.chain(&vb, &mut eb, frame, st, mode)?;
                let (x, y) = if mode == Mode::Assert {
                    self.merge(env, &ea, &eb, x, y)
                } else {
                    (x, y)
                };
                return Ok(or(vec![x, y]));
            }
        }
        match mode {
            Mode::Assert => {
                let b = self.element(first, env, frame, st, mode)?;
                let r = self.chain(rest, env, frame, st, mode)?;
                Ok(and(vec![b, r]))
            }
            Mode::Closed => {
                let needed: Vec<(Var, TypeId)> = self
                    .binds(first, env)
                    .into_iter()
                    .filter_map(|(v, b)| match b {
                        Binder::Domain(t) if later.contains(&v) => Some((v, t)),
                        _ => None,
                    })
                    .collect();
                let domains: Vec<&[ObjectId]> = needed
                    .iter()
                    .map(|(_, t)| self.project.universe.objects_of(*t))
                    .collect();
                let total: usize = domains.iter().map(|d| d.len()).product();
                let so_far = self.expanded.get().saturating_add(total);
                self.expanded.set(so_far);
                if so_far > MAX_INSTANCES {
                    return Err(Unsupported(format!(
                        "`{}` binds variables over more than {MAX_INSTANCES} combinations of objects",
                        crate::smt::text::formula(first)
                    )));
                }
                let mut parts = Vec::new();
                for tuple in tuples(&domains) {
                    let mut e2 = env.clone();
                    for ((v, _), o) in needed.iter().zip(tuple) {
                        e2.insert(v.clone(), Val::Obj(o));
                    }
                    let b = self.element(first, &mut e2, frame, st, mode)?;
                    let r = self.chain(rest, &mut e2, frame, st, mode)?;
                    parts.push(and(vec![b, r]));
                }
                Ok(or(parts))
            }
        }
    }

    /// Joins the bindings of two branches of a disjunction (assert mode): a variable bound
    /// alike in both stays; bound differently, it becomes a fresh constant equal to each
    /// branch's value in that branch; bound in one only, it is left unbound.
    fn merge(&self, env: &mut Env, ea: &Env, eb: &Env, x: Bool, y: Bool) -> (Bool, Bool) {
        let (mut xs, mut ys) = (vec![x], vec![y]);
        for (v, va) in ea {
            if env.contains_key(v) {
                continue;
            }
            let Some(vb) = eb.get(v) else { continue };
            if same_val(va, vb) {
                env.insert(v.clone(), va.clone());
                continue;
            }
            let objectish = |x: &Val| matches!(x, Val::Obj(_) | Val::Sym(_));
            let merged = if objectish(va) && objectish(vb) {
                Val::Sym(self.fresh_int("join"))
            } else if matches!((va, vb), (Val::Num(_), Val::Num(_))) {
                Val::Num(self.fresh_int("join"))
            } else {
                continue;
            };
            xs.push(val_eq(&merged, va));
            ys.push(val_eq(&merged, vb));
            env.insert(v.clone(), merged);
        }
        (and(xs), and(ys))
    }

    /// The variables a conjunct binds that are unbound in `env`, in order.
    fn binds(&self, f: &Formula, env: &Env) -> Vec<(Var, Binder)> {
        let mut out: Vec<(Var, Binder)> = Vec::new();
        let mut bound: BTreeSet<Var> = env.keys().cloned().collect();
        self.binds_into(f, &mut bound, &mut out);
        out
    }

    fn binds_into(&self, f: &Formula, bound: &mut BTreeSet<Var>, out: &mut Vec<(Var, Binder)>) {
        let mut push = |v: &Var, b: Binder, bound: &mut BTreeSet<Var>| {
            if bound.insert(v.clone()) {
                out.push((v.clone(), b));
            }
        };
        match f {
            Formula::True | Formula::Not(_) => {}
            Formula::Literal(t) => {
                let types = self.arg_types(t);
                for (i, a) in t.args().iter().enumerate() {
                    if let Term::Var(v) = a {
                        push(v, Binder::Domain(types[i]), bound);
                    }
                }
            }
            Formula::And(a, b) => {
                self.binds_into(a, bound, out);
                self.binds_into(b, bound, out);
            }
            Formula::Or(a, b) => {
                let mut ba = bound.clone();
                self.binds_into(a, &mut ba, out);
                let mut bb = bound.clone();
                self.binds_into(b, &mut bb, out);
                bound.extend(ba);
                bound.extend(bb);
            }
            Formula::Rel(RelOp::Unify, x, y) => {
                let unbound =
                    |t: &Term, bound: &BTreeSet<Var>| t.vars().iter().any(|v| !bound.contains(v));
                match (x, y) {
                    (Term::Var(v), other) if !bound.contains(v) && !unbound(other, bound) => {
                        push(v, Binder::Value, bound)
                    }
                    (other, Term::Var(v)) if !bound.contains(v) && !unbound(other, bound) => {
                        push(v, Binder::Value, bound)
                    }
                    _ => {}
                }
            }
            Formula::Rel(..) => {}
            Formula::Call(t) => {
                if t.functor() == Some(".count") {
                    if let Some(Term::Var(v)) = t.args().get(1) {
                        push(v, Binder::Value, bound);
                    }
                }
            }
        }
    }

    /// The parameter types of a literal's predicate or rule (`object` where unknown).
    pub(super) fn arg_types(&self, t: &Term) -> Vec<TypeId> {
        let name = t.functor().unwrap_or("");
        let n = t.arity();
        let voc = &self.project.vocabulary;
        if let Some((_, r)) = voc.rule(name, n) {
            return r.params.clone();
        }
        if let Some(p) = self.project.atoms.pred(name) {
            let params = self.project.atoms.pred_params(p);
            if params.len() == n {
                return params.to_vec();
            }
        }
        vec![TypeId::OBJECT; n]
    }

    /// One conjunct (bindings it makes go into `env`).
    fn element(
        &self,
        f: &Formula,
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
        mode: Mode,
    ) -> Enc<Bool> {
        match f {
            Formula::True => Ok(tt()),
            Formula::Literal(t) => self.literal(t, env, frame, st, mode),
            Formula::Not(g) => {
                let mut e2 = env.clone();
                Ok(self.chain(&[g], &mut e2, frame, st, Mode::Closed)?.not())
            }
            Formula::And(..) => self.chain(&[f], env, frame, st, mode),
            Formula::Or(a, b) => {
                let mut ea = env.clone();
                let x = self.chain(&[a], &mut ea, frame, st, mode)?;
                let mut eb = env.clone();
                let y = self.chain(&[b], &mut eb, frame, st, mode)?;
                let (x, y) = if mode == Mode::Assert {
                    self.merge(env, &ea, &eb, x, y)
                } else {
                    (x, y)
                };
                Ok(or(vec![x, y]))
            }
            Formula::Rel(op, a, b) => self.relation(*op, a, b, env),
            Formula::Call(t) => self.call(t, env, st),
        }
    }

    fn relation(&self, op: RelOp, a: &Term, b: &Term, env: &mut Env) -> Enc<Bool> {
        let va = self.term_val(a, env)?;
        let vb = self.term_val(b, env)?;
        let text = || format!("{a} {} {b}", op.symbol());
        match op {
            RelOp::Unify => match (va, vb, a, b) {
                (Some(x), Some(y), _, _) => Ok(val_eq(&x, &y)),
                (None, Some(y), Term::Var(v), _) => {
                    env.insert(v.clone(), y);
                    Ok(tt())
                }
                (Some(x), None, _, Term::Var(v)) => {
                    env.insert(v.clone(), x);
                    Ok(tt())
                }
                _ => Err(Unsupported(format!(
                    "`{}` unifies unbound terms; lint does not model that",
                    text()
                ))),
            },
            RelOp::Eq | RelOp::Ne => match (va, vb) {
                (Some(x), Some(y)) => {
                    let e = val_eq(&x, &y);
                    Ok(if op == RelOp::Eq { e } else { e.not() })
                }
                _ => Err(Unsupported(format!(
                    "`{}` compares an unbound variable; lint does not model that",
                    text()
                ))),
            },
            RelOp::Lt | RelOp::Le | RelOp::Gt | RelOp::Ge => match (va, vb) {
                (Some(Val::Num(x)), Some(Val::Num(y))) => Ok(match op {
                    RelOp::Lt => x.lt(&y),
                    RelOp::Le => x.le(&y),
                    RelOp::Gt => x.gt(&y),
                    _ => x.ge(&y),
                }),
                _ => Err(Unsupported(format!(
                    "`{}` is not a comparison of integers; lint does not model it",
                    text()
                ))),
            },
            RelOp::Univ => Err(Unsupported(format!(
                "`{}`: `=..` is not modelled by lint",
                text()
            ))),
        }
    }
}

fn vars_of(fs: &[&Formula]) -> BTreeSet<Var> {
    let mut out = BTreeSet::new();
    for f in fs {
        formula_vars(f, &mut out);
    }
    out
}
