//! Literals and calls in formulas: a literal is the disjunction of its ground instances (its
//! symbolic arguments equal to their objects), and the internal actions lint models
//! (`.count`, `.desire`, `.intend`, `.member`) are encoded here.

use super::count::sum;
use super::{
    and, ff, obj, or, pb, tt, val_eq, Enc, Encoder, Env, Frame, Mode, State, Unsupported, Val,
    MAX_INSTANCES,
};
use crate::model::cond::CountCmp;
use crate::model::term::{Term, Var};
use crate::model::universe::{ObjectId, TypeId};
use z3::ast::{Bool, Int};

impl Encoder<'_> {
    pub(super) fn call(&self, t: &Term, env: &mut Env, st: &State) -> Enc<Bool> {
        let f = t.functor().unwrap_or("");
        match (f, t.args()) {
            (".count", [q, n]) => {
                if self.rule_of(q).is_some() {
                    return Err(Unsupported(format!(
                        "`.count` over the rule `{q}` is not modelled by lint"
                    )));
                }
                let bs = self.instances(q, env, st)?;
                match self.term_val(n, env)? {
                    Some(Val::Num(k)) => match k.as_i64() {
                        Some(k) => Ok(pb(&bs, CountCmp::Eq, k)),
                        None => Ok(sum(&bs).eq(&k)),
                    },
                    Some(_) => Ok(ff()),
                    None => match n {
                        Term::Var(v) => {
                            env.insert(v.clone(), Val::Num(sum(&bs)));
                            Ok(tt())
                        }
                        _ => Err(Unsupported(format!("`{t}` is not modelled by lint"))),
                    },
                }
            }
            (".desire" | ".intend", [g]) => {
                // The agent's own goals are not part of the state: an unconstrained Boolean
                // per goal (one per ground goal, so every mention agrees).
                let mut key = g.clone();
                let mut symbolic = false;
                for v in g.vars() {
                    match env.get(&v) {
                        Some(Val::Obj(o)) => {
                            let name = self.project.universe.object_name(*o).to_string();
                            key = key.map_vars(&mut |w| {
                                if *w == v {
                                    Term::atom(&name)
                                } else {
                                    Term::Var(w.clone())
                                }
                            });
                        }
                        Some(_) => symbolic = true,
                        None => {
                            return Err(Unsupported(format!(
                                "`{t}` binds `{v}` from the agent's goals; lint does not model that"
                            )))
                        }
                    }
                }
                if symbolic {
                    return Ok(self.fresh_bool(f));
                }
                let text = format!("{f}({key})");
                if let Some(r) = self.call_reads.borrow_mut().as_mut() {
                    r.insert(text.clone());
                }
                Ok(self
                    .calls
                    .borrow_mut()
                    .entry(text.clone())
                    .or_insert_with(|| Bool::new_const(text))
                    .clone())
            }
            (".member", [x, l]) => {
                let Some(Val::Other(list)) = self.term_val(l, env)? else {
                    return Err(Unsupported(format!("`{t}` needs a ground list for lint")));
                };
                let Some((elems, None)) = list.list_elements() else {
                    return Err(Unsupported(format!("`{t}` needs a list")));
                };
                let Some(xv) = self.term_val(x, env)? else {
                    return Err(Unsupported(format!(
                        "`{t}` binds a variable; lint models `.member` on bound terms only"
                    )));
                };
                let mut parts = Vec::new();
                for e in &elems {
                    if let Some(ev) = self.term_val(e, &Env::new())? {
                        parts.push(val_eq(&xv, &ev));
                    }
                }
                Ok(or(parts))
            }
            _ => Err(Unsupported(format!(
                "`{f}` in a formula is not modelled by lint"
            ))),
        }
    }

    /// Binds the literal's variables that nothing bound yet to fresh symbolic values (a
    /// positive occurrence binds them), returning the constraints that keep each within
    /// its type.
    pub(super) fn bind_args(&self, t: &Term, env: &mut Env, frame: &mut Frame) -> Vec<Bool> {
        let types = self.arg_types(t);
        let mut constraints = Vec::new();
        for (i, a) in t.args().iter().enumerate() {
            if let Term::Var(v) = a {
                if !env.contains_key(v) && !v.is_anonymous() {
                    let x = frame.sym(v);
                    constraints.push(self.dom(&x, types[i]));
                    env.insert(v.clone(), Val::Sym(x));
                }
            }
        }
        constraints
    }

    pub(super) fn literal(
        &self,
        t: &Term,
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
        mode: Mode,
    ) -> Enc<Bool> {
        if let Some(clauses) = self.rule_of(t) {
            let clauses = clauses.clone()?;
            return self.rule_call(t, &clauses, env, frame, st, mode);
        }
        let mut extra = if mode == Mode::Assert {
            self.bind_args(t, env, frame)
        } else {
            Vec::new()
        };
        let inst = self.instances(t, env, st)?;
        extra.push(or(inst));
        Ok(and(extra))
    }

    /// One Boolean per ground instance of the literal `t` under `env`: the instance is
    /// selected (its symbolic arguments equal its objects) and its atom holds. Unbound
    /// variables range over their positions' types.
    fn instances(&self, t: &Term, env: &Env, st: &State) -> Enc<Vec<Bool>> {
        if !t.annots().is_empty() {
            return Err(Unsupported(format!(
                "annotations in `{t}` are not modelled by lint"
            )));
        }
        if !t.is_literal() {
            return Err(Unsupported(format!("`{t}` is not a literal")));
        }
        let atoms = &self.project.atoms;
        let universe = &self.project.universe;
        let Some(p) = atoms.pred_of_literal(t) else {
            // Closed world: a belief that nothing can add never holds.
            return Ok(Vec::new());
        };
        let params = atoms.pred_params(p);
        if params.len() != t.arity() {
            return Ok(Vec::new());
        }
        // Each position is a fixed object or a group: one variable (symbolic or free).
        enum Pos {
            Fixed(ObjectId),
            Group(usize),
        }
        let mut groups: Vec<(Var, Option<Int>, TypeId)> = Vec::new();
        let mut pos = Vec::new();
        for (i, a) in t.args().iter().enumerate() {
            let fixed = match a {
                Term::Var(v) => match env.get(v) {
                    Some(Val::Obj(o)) => Some(*o),
                    Some(Val::Sym(x)) => {
                        pos.push(Pos::Group(group(&mut groups, v, Some(x), params[i])));
                        continue;
                    }
                    Some(_) => return Ok(Vec::new()),
                    None => {
                        pos.push(Pos::Group(group(&mut groups, v, None, params[i])));
                        continue;
                    }
                },
                Term::Atom(name) => universe.object(name),
                _ => None,
            };
            match fixed {
                Some(o) => pos.push(Pos::Fixed(o)),
                None => return Ok(Vec::new()),
            }
        }
        let domains: Vec<&[ObjectId]> = groups
            .iter()
            .map(|(_, _, ty)| universe.objects_of(*ty))
            .collect();
        let total: usize = domains.iter().map(|d| d.len()).product();
        if total > MAX_INSTANCES {
            return Err(Unsupported(format!(
                "`{t}` has more than {MAX_INSTANCES} instances"
            )));
        }
        let mut out = Vec::new();
        for tuple in tuples(&domains) {
            let args: Vec<ObjectId> = pos
                .iter()
                .map(|p| match p {
                    Pos::Fixed(o) => *o,
                    Pos::Group(g) => tuple[*g],
                })
                .collect();
            let Some(a) = atoms.id(p, &args) else {
                continue;
            };
            let mut parts: Vec<Bool> = groups
                .iter()
                .zip(&tuple)
                .filter_map(|((_, x, _), o)| x.as_ref().map(|x| x.eq(obj(*o))))
                .collect();
            parts.push(self.atom(st, a));
            out.push(and(parts));
        }
        Ok(out)
    }
}

fn group(
    groups: &mut Vec<(Var, Option<Int>, TypeId)>,
    v: &Var,
    x: Option<&Int>,
    ty: TypeId,
) -> usize {
    match groups.iter().position(|(w, _, _)| w == v) {
        Some(i) => i,
        None => {
            groups.push((v.clone(), x.cloned(), ty));
            groups.len() - 1
        }
    }
}

/// Every combination of one object from each domain, in order.
pub fn tuples(domains: &[&[ObjectId]]) -> Vec<Vec<ObjectId>> {
    let mut out = vec![Vec::new()];
    for d in domains {
        out = out
            .into_iter()
            .flat_map(|prefix| {
                d.iter().map(move |o| {
                    let mut v = prefix.clone();
                    v.push(*o);
                    v
                })
            })
            .collect();
    }
    out
}
