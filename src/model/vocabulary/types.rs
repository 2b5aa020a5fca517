//! Passes 3 and 4, the types: parameter types of goals, rules and mental notes inferred to a
//! fixed point, then a final pass in which every position constrains and conflicts, bad
//! constants and free variables are reported (see "Types" in the module documentation).

use super::diagnostics::a_type;
use super::{Arg, Checker, Clause, Role, Sig, Types, VarInfo};
use crate::model::universe::{TypeId, Universe};
use crate::syntax::Diagnostic;
use std::collections::{HashMap, HashSet};

impl Checker<'_> {
    // ----- pass 3: inference ------------------------------------------------------------------

    fn initial_types(&self) -> Types {
        Types {
            preds: (0..self.preds.len())
                .map(|p| match self.pddl_params.get(p) {
                    Some(ps) if self.preds[p].env => ps.iter().map(|&t| Some(t)).collect(),
                    _ => vec![None; self.preds[p].arity],
                })
                .collect(),
            goals: self.goals.iter().map(|g| vec![None; g.arity]).collect(),
            rules: self.rules.iter().map(|r| vec![None; r.arity]).collect(),
        }
    }

    /// Parameter types of goals, rules and mental notes, to a fixed point.
    pub(super) fn infer(&self) -> Types {
        let mut types = self.initial_types();
        let rounds = 8 + 2 * (self.goals.len() + self.rules.len() + self.preds.len());
        for _ in 0..rounds {
            let mut next = self.initial_types();
            for cl in &self.clauses {
                let vars = self.resolve(cl, &types, None);
                for o in cl.occs.iter().filter(|o| o.role == Role::Define) {
                    let t = match &o.arg {
                        Arg::Var(v) => vars.get(v).map(|i| i.ty),
                        Arg::Const(c) => self
                            .universe
                            .object(c)
                            .map(|o| self.universe.object_type(o)),
                    };
                    let slot = match o.sig {
                        Sig::Pred(p) if !self.preds[p].env => Some((
                            &mut next.preds[p][o.index],
                            Some(t.unwrap_or(TypeId::OBJECT)),
                        )),
                        Sig::Goal(g) => Some((&mut next.goals[g][o.index], t)),
                        Sig::Rule(r) => Some((&mut next.rules[r][o.index], t)),
                        _ => None,
                    };
                    if let Some((slot, Some(t))) = slot {
                        *slot = Some(match *slot {
                            None => t,
                            Some(s) => lca(self.universe, s, t),
                        });
                    }
                }
            }
            if next == types {
                break;
            }
            types = next;
        }
        types
    }

    /// The parameter type of a position.
    fn param(&self, types: &Types, sig: Sig, i: usize) -> Option<TypeId> {
        match sig {
            Sig::Pred(p) => types.preds[p].get(i).copied().flatten(),
            Sig::Action(a) => self.actions[a].params.get(i).copied(),
            Sig::Goal(g) => types.goals[g].get(i).copied().flatten(),
            Sig::Rule(r) => types.rules[r].get(i).copied().flatten(),
        }
    }

    /// The variables' types in one clause. With `diags`, the final pass: every position
    /// constrains, and conflicts, bad constants and free variables are reported.
    fn resolve(
        &self,
        cl: &Clause,
        types: &Types,
        mut diags: Option<&mut Vec<Diagnostic>>,
    ) -> HashMap<String, VarInfo> {
        let last = diags.is_some();
        let mut vars: HashMap<String, VarInfo> = HashMap::new();
        // Uses first: a defining position (typed by what the uses infer) only refines, and a
        // conflict is best reported between the positions that caused it.
        let uses = cl.occs.iter().filter(|o| o.role == Role::Use);
        let defines = cl.occs.iter().filter(|o| o.role == Role::Define && last);
        for o in uses.chain(defines) {
            let Some(want) = self.param(types, o.sig, o.index) else {
                continue;
            };
            match &o.arg {
                Arg::Var(v) => match vars.get_mut(v) {
                    None => {
                        vars.insert(
                            v.clone(),
                            VarInfo {
                                ty: want,
                                span: o.span,
                                sig: o.sig,
                                index: o.index,
                            },
                        );
                    }
                    Some(info) => match self.universe.meet(info.ty, want) {
                        Some(m) => {
                            if m != info.ty {
                                *info = VarInfo {
                                    ty: m,
                                    span: o.span,
                                    sig: o.sig,
                                    index: o.index,
                                };
                            }
                        }
                        None => {
                            if let Some(d) = diags.as_deref_mut() {
                                d.push(self.conflict(v, info, o, want));
                            }
                        }
                    },
                },
                Arg::Const(c) => {
                    if let Some(d) = diags.as_deref_mut() {
                        match self.universe.object(c) {
                            None => d.push(self.not_an_object(c, o.span)),
                            Some(obj) => {
                                let has = self.universe.object_type(obj);
                                if !self.universe.is_subtype(has, want) {
                                    let tn = |t| self.universe.type_name(t);
                                    d.push(
                                        Diagnostic::error(
                                            "input",
                                            format!(
                                                "`{c}` is {}, but {}",
                                                a_type(tn(has)),
                                                self.expects(o.sig, o.index, want)
                                            ),
                                        )
                                        .with_label(o.span, format!("{} here", a_type(tn(has))))
                                        .with_secondary(
                                            self.universe.object_origin(obj).span(),
                                            format!("`{c}` is declared here"),
                                        ),
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
        if let Some(d) = diags {
            if cl.free_check {
                let mut seen = HashSet::new();
                for (v, span) in &cl.vars {
                    if vars.contains_key(v) || cl.counted.contains(v) || !seen.insert(v) {
                        continue;
                    }
                    d.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "variable `{v}` is in no typed position, so it would range over nothing in particular"
                            ),
                        )
                        .with_label(*span, "untyped variable")
                        .with_help(
                            "use it as an argument of a predicate, an action or a goal, whose signature gives its type",
                        ),
                    );
                }
            }
        }
        vars
    }

    // ----- pass 4: the final check ------------------------------------------------------------

    pub(super) fn final_pass(&mut self, types: &Types) {
        let mut finals = types.clone();
        for ps in finals
            .goals
            .iter_mut()
            .chain(finals.rules.iter_mut())
            .chain(finals.preds.iter_mut())
        {
            for p in ps.iter_mut() {
                p.get_or_insert(TypeId::OBJECT);
            }
        }
        let mut diags = Vec::new();
        for cl in &self.clauses {
            self.resolve(cl, &finals, Some(&mut diags));
        }
        self.diags.extend(diags);
    }
}

/// The least common ancestor of two types.
fn lca(u: &Universe, a: TypeId, b: TypeId) -> TypeId {
    if u.is_subtype(a, b) {
        return b;
    }
    if u.is_subtype(b, a) {
        return a;
    }
    // The common ancestors form a chain; the most specific is below all the others.
    let common: Vec<TypeId> = (0..u.type_count() as u16)
        .map(TypeId)
        .filter(|&t| u.is_subtype(a, t) && u.is_subtype(b, t))
        .collect();
    common
        .iter()
        .copied()
        .find(|&t| common.iter().all(|&s| u.is_subtype(t, s)))
        .unwrap_or(TypeId::OBJECT)
}
