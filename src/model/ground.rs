//! Ground actions and PDDL's semantics on states.
//!
//! Each action schema is grounded over the objects of its parameter types. A ground action
//! keeps its precondition as a [`Cond`] and its effect as a list of conditional effects
//! `(when, add, delete)`: unconditional effects have `when = True`, `forall` is expanded,
//! nested `when`s are conjoined. Applying it follows PDDL: every `when` is evaluated in the
//! state *before* the action, then all deletions are applied, then all additions (so an
//! action that deletes and adds one atom leaves it true).

use super::atoms::{AtomId, AtomSet, AtomTable};
use super::cond::Cond;
use super::universe::{ObjectId, TypeId, Universe};
use crate::syntax::pddl::{ActionDecl, Domain, Effect, EffectKind, Gd, GdKind, PddlTerm};
use crate::syntax::{Diagnostic, Span};
use std::collections::HashMap;
use std::sync::Arc;

/// One conditional effect of a ground action.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CondEffect {
    /// Evaluated in the state before the action.
    pub when: Cond,
    /// Atoms made true.
    pub add: Vec<AtomId>,
    /// Atoms made false.
    pub del: Vec<AtomId>,
}

/// An action schema applied to objects.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GroundAction {
    /// The schema's index in the PDDL domain's `actions`.
    pub schema: usize,
    /// The schema's name.
    pub name: Arc<str>,
    /// The arguments.
    pub args: Vec<ObjectId>,
    /// When the action may run.
    pub pre: Cond,
    /// What it changes.
    pub effects: Vec<CondEffect>,
}

impl GroundAction {
    /// Whether the precondition holds in `s`.
    pub fn applicable(&self, s: &AtomSet) -> bool {
        self.pre.eval(s)
    }

    /// The state after the action (its precondition is not checked here).
    pub fn apply(&self, s: &AtomSet) -> AtomSet {
        let fired: Vec<&CondEffect> = self.effects.iter().filter(|e| e.when.eval(s)).collect();
        let mut next = s.clone();
        for e in &fired {
            e.del.iter().for_each(|a| next.remove(*a));
        }
        for e in &fired {
            e.add.iter().for_each(|a| next.insert(*a));
        }
        next
    }

    /// Every atom any of its effects may add or delete: the paper's `Eff+ ∪ Eff-`.
    pub fn touched(&self) -> Vec<AtomId> {
        let mut out: Vec<AtomId> = self
            .effects
            .iter()
            .flat_map(|e| e.add.iter().chain(&e.del).copied())
            .collect();
        out.sort();
        out.dedup();
        out
    }

    /// The action as Jason writes it, e.g. `navigateTo(table)`.
    pub fn display(&self, universe: &Universe) -> String {
        if self.args.is_empty() {
            self.name.to_string()
        } else {
            let args: Vec<&str> = self.args.iter().map(|o| universe.object_name(*o)).collect();
            format!("{}({})", self.name, args.join(","))
        }
    }
}

/// Every ground action of a domain, looked up by name and arguments.
#[derive(Clone, Debug, Default)]
pub struct GroundActions {
    actions: Vec<GroundAction>,
    index: HashMap<(Arc<str>, Vec<ObjectId>), usize>,
}

impl GroundActions {
    /// Grounds every action schema of `domain`. Names the grounding cannot resolve (a
    /// constant that is no object, an undeclared predicate) are located errors; the type
    /// checker normally reports them first.
    pub fn new(
        domain: &Domain,
        universe: &Universe,
        atoms: &AtomTable,
    ) -> Result<GroundActions, Vec<Diagnostic>> {
        let mut g = Grounder {
            universe,
            atoms,
            errors: Vec::new(),
        };
        let mut out = GroundActions::default();
        for (schema, decl) in domain.actions.iter().enumerate() {
            let types: Vec<TypeId> = decl
                .params
                .iter()
                .map(|p| g.type_of(&p.ty, p.ty_span.unwrap_or(p.span)))
                .collect();
            for args in product(universe, &types) {
                let action = g.ground_action(schema, decl, &args);
                out.index.insert(
                    (action.name.clone(), action.args.clone()),
                    out.actions.len(),
                );
                out.actions.push(action);
            }
        }
        if g.errors.is_empty() {
            Ok(out)
        } else {
            g.errors.dedup();
            Err(g.errors)
        }
    }

    /// Every ground action, schema by schema, arguments in object order.
    pub fn all(&self) -> &[GroundAction] {
        &self.actions
    }

    /// The ground action `name(args)`.
    pub fn get(&self, name: &str, args: &[ObjectId]) -> Option<&GroundAction> {
        self.index
            .get(&(Arc::<str>::from(name), args.to_vec()))
            .map(|&i| &self.actions[i])
    }

    /// The ground action a Jason term such as `navigateTo(table)` names, if its arguments
    /// are objects and the action exists.
    pub fn of_term(
        &self,
        t: &crate::model::term::Term,
        universe: &Universe,
    ) -> Option<&GroundAction> {
        let args = t
            .args()
            .iter()
            .map(|a| match a {
                crate::model::term::Term::Atom(n) => universe.object(n),
                _ => None,
            })
            .collect::<Option<Vec<_>>>()?;
        self.get(t.functor()?, &args)
    }

    /// Number of ground actions.
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }
}

/// Every tuple of objects of the given types, in lexicographic object order.
pub fn product(universe: &Universe, types: &[TypeId]) -> Vec<Vec<ObjectId>> {
    let mut out = vec![Vec::new()];
    for t in types {
        let objs = universe.objects_of(*t);
        out = out
            .into_iter()
            .flat_map(|prefix| {
                objs.iter().map(move |o| {
                    let mut v = prefix.clone();
                    v.push(*o);
                    v
                })
            })
            .collect();
    }
    out
}

struct Grounder<'a> {
    universe: &'a Universe,
    atoms: &'a AtomTable,
    errors: Vec<Diagnostic>,
}

type Env<'e> = Vec<(&'e str, ObjectId)>;

impl<'a> Grounder<'a> {
    fn type_of(&mut self, name: &str, span: Span) -> TypeId {
        match self.universe.type_id(name) {
            Some(t) => t,
            None => {
                self.errors.push(
                    Diagnostic::error("input", format!("unknown type `{name}`"))
                        .with_label(span, "not declared"),
                );
                TypeId::OBJECT
            }
        }
    }

    fn ground_action(
        &mut self,
        schema: usize,
        decl: &ActionDecl,
        args: &[ObjectId],
    ) -> GroundAction {
        let env: Env = decl
            .params
            .iter()
            .map(|p| p.name.as_str())
            .zip(args.iter().copied())
            .collect();
        let pre = match &decl.precondition {
            Some(gd) => self.gd(gd, &env),
            None => Cond::True,
        };
        let mut effects = Vec::new();
        if let Some(e) = &decl.effect {
            self.effect(e, &env, Cond::True, &mut effects);
        }
        // Effects under one condition are merged so applying walks fewer entries.
        let mut merged: Vec<CondEffect> = Vec::new();
        for e in effects {
            match merged.iter_mut().find(|m| m.when == e.when) {
                Some(m) => {
                    m.add.extend(e.add);
                    m.del.extend(e.del);
                }
                None => merged.push(e),
            }
        }
        for m in &mut merged {
            m.add.sort();
            m.add.dedup();
            m.del.sort();
            m.del.dedup();
        }
        GroundAction {
            schema,
            name: decl.name.as_str().into(),
            args: args.to_vec(),
            pre,
            effects: merged,
        }
    }

    fn term(&mut self, t: &PddlTerm, env: &Env) -> Option<ObjectId> {
        match t {
            PddlTerm::Var { name, span } => match env.iter().rev().find(|(n, _)| n == name) {
                Some((_, o)) => Some(*o),
                None => {
                    self.errors.push(
                        Diagnostic::error("input", format!("`?{name}` is not bound here"))
                            .with_label(*span, "unbound variable"),
                    );
                    None
                }
            },
            PddlTerm::Const { name, span } => {
                match self.universe.object(name) {
                    Some(o) => Some(o),
                    None => {
                        self.errors.push(
                        Diagnostic::error(
                            "input",
                            format!("`{name}` is neither a PDDL constant nor an object of the manifest"),
                        )
                        .with_label(*span, "unknown object")
                        .with_help("declare it in `(:constants ...)` or in the manifest's `[objects]`"),
                    );
                        None
                    }
                }
            }
        }
    }

    /// The atom, or `False` when its arguments do not fit the predicate's types (such an
    /// atom can never be true).
    fn atom(
        &mut self,
        a: &crate::syntax::pddl::AtomicFormula,
        env: &Env,
    ) -> Option<Option<AtomId>> {
        let Some(p) = self.atoms.pred(&a.predicate) else {
            self.errors.push(
                Diagnostic::error("input", format!("`{}` is not a predicate", a.predicate))
                    .with_label(a.predicate_span, "undeclared predicate"),
            );
            return None;
        };
        let mut args = Vec::with_capacity(a.args.len());
        for t in &a.args {
            args.push(self.term(t, env)?);
        }
        Some(self.atoms.id(p, &args))
    }

    fn gd(&mut self, gd: &Gd, env: &Env) -> Cond {
        match &gd.kind {
            GdKind::And(parts) => Cond::and(parts.iter().map(|g| self.gd(g, env)).collect()),
            GdKind::Or(parts) => Cond::or(parts.iter().map(|g| self.gd(g, env)).collect()),
            GdKind::Not(g) => Cond::negate(self.gd(g, env)),
            GdKind::Imply(a, b) => {
                let a = self.gd(a, env);
                let b = self.gd(b, env);
                Cond::or(vec![Cond::negate(a), b])
            }
            GdKind::Exists(vars, body) | GdKind::Forall(vars, body) => {
                let types: Vec<TypeId> = vars
                    .iter()
                    .map(|v| self.type_of(&v.ty, v.ty_span.unwrap_or(v.span)))
                    .collect();
                let mut parts = Vec::new();
                for objs in product(self.universe, &types) {
                    let mut inner = env.clone();
                    inner.extend(vars.iter().map(|v| v.name.as_str()).zip(objs));
                    parts.push(self.gd(body, &inner));
                }
                if matches!(gd.kind, GdKind::Exists(..)) {
                    Cond::or(parts)
                } else {
                    Cond::and(parts)
                }
            }
            GdKind::Atom(a) => match self.atom(a, env) {
                Some(Some(id)) => Cond::Atom(id),
                _ => Cond::False,
            },
            GdKind::Equal(x, y) => match (self.term(x, env), self.term(y, env)) {
                (Some(x), Some(y)) if x == y => Cond::True,
                _ => Cond::False,
            },
        }
    }

    fn effect(&mut self, e: &Effect, env: &Env, when: Cond, out: &mut Vec<CondEffect>) {
        match &e.kind {
            EffectKind::And(parts) => {
                for p in parts {
                    self.effect(p, env, when.clone(), out);
                }
            }
            EffectKind::Add(a) | EffectKind::Delete(a) => {
                // An atom outside the predicate's types cannot exist: adding or deleting
                // it changes nothing.
                if let Some(Some(id)) = self.atom(a, env) {
                    let adds = matches!(e.kind, EffectKind::Add(_));
                    out.push(CondEffect {
                        when,
                        add: if adds { vec![id] } else { vec![] },
                        del: if adds { vec![] } else { vec![id] },
                    });
                }
            }
            EffectKind::Forall(vars, body) => {
                let types: Vec<TypeId> = vars
                    .iter()
                    .map(|v| self.type_of(&v.ty, v.ty_span.unwrap_or(v.span)))
                    .collect();
                for objs in product(self.universe, &types) {
                    let mut inner = env.clone();
                    inner.extend(vars.iter().map(|v| v.name.as_str()).zip(objs));
                    self.effect(body, &inner, when.clone(), out);
                }
            }
            EffectKind::When(cond, body) => {
                let c = self.gd(cond, env);
                let both = Cond::and(vec![when, c]);
                if both != Cond::False {
                    self.effect(body, env, both, out);
                }
            }
        }
    }
}
