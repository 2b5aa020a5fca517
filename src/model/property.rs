//! Properties decided on runs rather than on beliefs alone: `ltl` formulas, and
//! `always`/`eventually`/`reachable` formulas that use BDI modalities (SPEC §1). Each is
//! compiled to [`Ltl`] over a project-wide table of [`Atomic`] propositions, one formula per
//! assignment of its free variables (a variable ranges over its type, and the property must
//! hold for every object: `requested(storeCup(C)) ~> cupAt(C, dishwasher)` is one formula per
//! cup).
//!
//! The modalities, after AJPF's `B`, `G`, `I`, `D` and `P`:
//! - `believes(f)`: the agent believes the state formula `f`;
//! - `holds(f)`: `f` holds in the environment (the agent perceives it exactly, so in a
//!   project of one agent this is `f` on the environment's atoms of its beliefs);
//! - `desires(g)` and `.desire(g)`: Jason's `.desire`: `+!g` is an event, or some intention
//!   has `g` as a goal;
//! - `intends(g)` and `.intend(g)`: Jason's `.intend`: some intention has `g` as a goal;
//! - `did(a)`: the step into this state executed the environment action `a` (it did not
//!   fail);
//! - `requested(g)`: the user's request `!g` has arrived and is still served (an intention
//!   or an event of it remains).
//!
//! The agent argument (`believes(ag, f)`) may be given in a project of one agent (it must
//! name that agent) and must be given in a project of several ([`compile_in`]), where
//! `ag::b` in a state formula is agent `ag`'s belief too.
//!
//! `explained(user, a)`: the step into this state gave the user `user` (of the manifest's
//! `[explanation.users]`) an explanation of the action `a`. A property that uses it is
//! decided on that user's explanation search (the runs with the user's expected
//! successors), so it may name one user only.

use super::atoms::AtomTable;
use super::cond::Cond;
use super::formula::{ground_with, infer_types};
use super::ground::product;
use super::ltl::Ltl;
use super::project::Project;
use super::term::Term;
use super::universe::{ObjectId, TypeId};
use crate::syntax::ast::{Expr, ExprKind, Literal};
use crate::syntax::manifest::{LtlBinary, LtlExpr, LtlKind, LtlUnary, PropertyKind};
use crate::syntax::{Diagnostic, Span};
use std::collections::{BTreeMap, HashMap};

/// The modalities a property may use, by functor.
const MODALITIES: &[&str] = &[
    "believes",
    "holds",
    "desires",
    "intends",
    ".desire",
    ".intend",
    "did",
    "requested",
    "explained",
];

/// Most distinct atomic propositions one formula may speak of (a letter is a `u64`).
pub const MAX_PROPS: usize = 64;

/// Most formulas one property may stand for (assignments of its free variables): each is
/// a product search of its own.
pub const MAX_INSTANCES: usize = 10_000;

/// What one atomic proposition asks of a state of a run.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Atomic {
    /// A condition on the beliefs (a plain state formula, `believes(f)` or `holds(f)`).
    Beliefs(Cond),
    /// Some intention of the agent (its index among the project's agents, 0 when there
    /// is one) has a goal that unifies with this one.
    Intends(u8, Term),
    /// `+!g` is an event of the agent, or some intention of it has the goal `g`.
    Desires(u8, Term),
    /// The request of a goal that unifies with this one is being served.
    Requested(Term),
    /// The step into the state was the agent's, and executed an action that unifies with
    /// this one.
    Did(u8, Term),
    /// The step into the state gave the user an explanation of an action that unifies
    /// with this one.
    Explained(Term),
}

/// The atomic propositions of every property of a project, numbered.
#[derive(Clone, Debug, Default)]
pub struct Atomics {
    /// By number.
    pub list: Vec<Atomic>,
    index: HashMap<Atomic, u32>,
}

impl Atomics {
    fn intern(&mut self, a: Atomic) -> Ltl {
        match a {
            Atomic::Beliefs(Cond::True) => return Ltl::True,
            Atomic::Beliefs(Cond::False) => return Ltl::False,
            _ => {}
        }
        let next = self.list.len() as u32;
        let id = *self.index.entry(a.clone()).or_insert(next);
        if id == next {
            self.list.push(a);
        }
        Ltl::Prop(id)
    }

    /// Whether some proposition is about the step into a state rather than the state.
    pub fn reads_steps(&self) -> bool {
        self.list.iter().any(|a| matches!(a, Atomic::Did(..)))
    }

    /// Whether some proposition reads more than the beliefs.
    pub fn reads_mind(&self) -> bool {
        self.list.iter().any(|a| !matches!(a, Atomic::Beliefs(_)))
    }
}

/// One formula of a property: the property with its free variables bound.
#[derive(Clone, Debug)]
pub struct Instance {
    /// `C = cup1, ...` (empty when the formula has no free variable).
    pub binding: String,
    /// The formula, over the numbers of [`Atomics`].
    pub formula: Ltl,
}

/// A property decided on runs.
#[derive(Clone, Debug)]
pub struct RunProperty {
    /// Its name.
    pub name: String,
    /// `ltl`, or the state kind it was written with.
    pub kind: PropertyKind,
    /// Its formula in the manifest.
    pub span: Span,
    /// For `ltl`: one formula per assignment of the free variables, all of which must hold.
    /// For the state kinds: exactly one, a formula without temporal operators (the
    /// conjunction over the assignments), which `always`, `eventually` or `reachable`
    /// applies to.
    pub instances: Vec<Instance>,
    /// The user whose explanation search decides it, when it uses `explained`.
    pub user: Option<String>,
}

/// The users whose explanation searches decide some of `props` (`explained`), each once,
/// in name order.
pub fn explained_users(props: &[RunProperty]) -> Vec<&str> {
    let mut users: Vec<&str> = props.iter().filter_map(|p| p.user.as_deref()).collect();
    users.sort_unstable();
    users.dedup();
    users
}

/// Whether a state formula uses a modality (and so is decided on runs).
pub fn is_modal(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Literal(l) => {
            MODALITIES.contains(&l.functor.as_str()) || l.args.iter().any(is_modal)
        }
        ExprKind::Not(a) => is_modal(a),
        ExprKind::And(a, b) | ExprKind::Or(a, b) | ExprKind::Rel(_, a, b) => {
            is_modal(a) || is_modal(b)
        }
        _ => false,
    }
}

/// Whether a state formula uses a modality other than Jason's `.intend` and `.desire`
/// (which the vocabulary checks know).
pub fn uses_modality(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Literal(l) => {
            (MODALITIES.contains(&l.functor.as_str()) && !l.functor.starts_with('.'))
                || l.args.iter().any(uses_modality)
        }
        ExprKind::Not(a) => uses_modality(a),
        ExprKind::And(a, b) | ExprKind::Or(a, b) | ExprKind::Rel(_, a, b) => {
            uses_modality(a) || uses_modality(b)
        }
        _ => false,
    }
}

/// Whether a manifest property is decided on runs (see the module's documentation).
pub fn is_run_property(p: &crate::syntax::manifest::Property) -> bool {
    p.kind == PropertyKind::Ltl || is_modal(&p.formula.expr)
}

/// Compiles every property of the project that is decided on runs, in manifest order.
pub fn compile(project: &Project) -> Result<(Vec<RunProperty>, Atomics), Vec<Diagnostic>> {
    compile_in(project, &[])
}

/// [`compile`] in a project of several agents, named by `agents` (empty for one agent): a
/// modality names its agent (`believes(ag, f)`), and a state formula's `ag::b` is agent
/// `ag`'s belief, as [`crate::model::formula::compile_in`] reads it.
pub fn compile_in(
    project: &Project,
    agents: &[String],
) -> Result<(Vec<RunProperty>, Atomics), Vec<Diagnostic>> {
    compile_where(project, agents, is_run_property)
}

/// [`compile_in`] for the properties `select` picks (those decided on runs and more: a
/// state property a symmetric search cannot decide on its reduced graph).
pub fn compile_where(
    project: &Project,
    agents: &[String],
    select: impl Fn(&crate::syntax::manifest::Property) -> bool,
) -> Result<(Vec<RunProperty>, Atomics), Vec<Diagnostic>> {
    let mut atomics = Atomics::default();
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for p in &project.manifest.properties {
        if !select(p) {
            continue;
        }
        let c = Compiler {
            project,
            atoms: &project.atoms,
            agents,
        };
        let mut user = None;
        match c.property(p, &mut atomics, &mut user) {
            Ok(instances) => out.push(RunProperty {
                name: p.name.value.clone(),
                kind: p.kind,
                span: p.formula.span,
                instances,
                user,
            }),
            Err(d) => errors.push(d),
        }
    }
    if errors.is_empty() {
        Ok((out, atomics))
    } else {
        Err(errors)
    }
}

struct Compiler<'a> {
    project: &'a Project,
    atoms: &'a AtomTable,
    /// The agents of a project of several (empty for one).
    agents: &'a [String],
}

type Env<'e> = BTreeMap<&'e str, ObjectId>;

/// An LTL formula with its state formulas still to ground.
enum Shape<'e> {
    State(&'e Expr),
    Unary(LtlUnary, Box<Shape<'e>>),
    Binary(LtlBinary, Box<Shape<'e>>, Box<Shape<'e>>),
}

fn shape(e: &LtlExpr) -> Shape<'_> {
    match &e.kind {
        LtlKind::State(x) => Shape::State(x),
        LtlKind::Unary(op, a) => Shape::Unary(*op, Box::new(shape(a))),
        LtlKind::Binary(op, a, b) => Shape::Binary(*op, Box::new(shape(a)), Box::new(shape(b))),
    }
}

impl Compiler<'_> {
    fn property(
        &self,
        p: &crate::syntax::manifest::Property,
        atomics: &mut Atomics,
        user: &mut Option<String>,
    ) -> Result<Vec<Instance>, Diagnostic> {
        let s = match &p.ltl {
            Some(l) => shape(l),
            None => Shape::State(&p.formula.expr),
        };
        let mut types = BTreeMap::new();
        self.infer_shape(&s, &mut types)?;
        let names: Vec<&String> = types.keys().collect();
        let tys: Vec<TypeId> = types.values().copied().collect();
        let count = tys.iter().fold(1usize, |n, t| {
            n.saturating_mul(self.project.universe.objects_of(*t).len())
        });
        if count > MAX_INSTANCES {
            return Err(Diagnostic::error(
                "input",
                format!(
                    "property `{}` stands for {count} formulas, one per assignment of its variables; at most {MAX_INSTANCES} are supported",
                    p.name.value
                ),
            )
            .with_label(p.formula.span, "fewer variables, or variables of smaller types"));
        }
        let mut instances: Vec<Instance> = Vec::new();
        for objs in product(&self.project.universe, &tys) {
            let env: Env = names
                .iter()
                .map(|n| n.as_str())
                .zip(objs.iter().copied())
                .collect();
            let formula = self.ground_shape(&s, &env, atomics, user)?;
            let binding = names
                .iter()
                .zip(&objs)
                .map(|(n, o)| format!("{n} = {}", self.project.universe.object_name(*o)))
                .collect::<Vec<_>>()
                .join(", ");
            if !instances.iter().any(|i| i.formula == formula) {
                instances.push(Instance { binding, formula });
            }
        }
        for i in &instances {
            let distinct = i.formula.named_props().len();
            if distinct > MAX_PROPS {
                return Err(Diagnostic::error(
                    "input",
                    format!(
                        "property `{}` speaks of {distinct} distinct state formulas at once; at most {MAX_PROPS} are supported",
                        p.name.value
                    ),
                )
                .with_label(p.formula.span, "split it into several properties"));
            }
        }
        if p.kind != PropertyKind::Ltl {
            // A state formula holds where it holds for every assignment.
            let all = instances
                .into_iter()
                .map(|i| i.formula)
                .reduce(Ltl::and)
                .unwrap_or(Ltl::True);
            instances = vec![Instance {
                binding: String::new(),
                formula: all,
            }];
        }
        Ok(instances)
    }

    fn infer_shape(
        &self,
        s: &Shape,
        types: &mut BTreeMap<String, TypeId>,
    ) -> Result<(), Diagnostic> {
        match s {
            Shape::State(e) => self.infer_state(e, types),
            Shape::Unary(_, a) => self.infer_shape(a, types),
            Shape::Binary(_, a, b) => {
                self.infer_shape(a, types)?;
                self.infer_shape(b, types)
            }
        }
    }

    fn infer_state(
        &self,
        e: &Expr,
        types: &mut BTreeMap<String, TypeId>,
    ) -> Result<(), Diagnostic> {
        if !is_modal(e) {
            return infer_types(e, self.atoms, &self.project.universe, self.agents, types);
        }
        match &e.kind {
            ExprKind::Not(a) => self.infer_state(a, types),
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                self.infer_state(a, types)?;
                self.infer_state(b, types)
            }
            ExprKind::Literal(l) if l.functor == "explained" => {
                let (_, a) = self.explained_args(l)?;
                self.infer_action(a, types)
            }
            ExprKind::Literal(l) if MODALITIES.contains(&l.functor.as_str()) => {
                let (what, _, arg) = self.modal_arg(l)?;
                match what {
                    "believes" | "holds" => self.infer_state(arg, types),
                    "did" => self.infer_action(arg, types),
                    _ => {
                        let ExprKind::Literal(g) = &arg.kind else {
                            return Ok(());
                        };
                        if let Some((_, sig)) =
                            self.project.vocabulary.goal(&g.functor, g.args.len())
                        {
                            for (x, ty) in g.args.iter().zip(&sig.params) {
                                self.type_var(x, Some(*ty), types)?;
                            }
                        }
                        Ok(())
                    }
                }
            }
            _ => Err(modal_inside(e)),
        }
    }

    /// Types the variables of an action pattern from the PDDL action's parameters.
    fn infer_action(
        &self,
        arg: &Expr,
        types: &mut BTreeMap<String, TypeId>,
    ) -> Result<(), Diagnostic> {
        let ExprKind::Literal(a) = &arg.kind else {
            return Ok(());
        };
        if let Some((_, sig)) = self.project.vocabulary.action(&a.functor) {
            for (i, x) in a.args.iter().enumerate() {
                let ty = sig.params.get(sig.param_of_arg(i)).copied();
                self.type_var(x, ty, types)?;
            }
        }
        Ok(())
    }

    /// `explained(user, a)`: the user (one of the manifest's) and the action pattern.
    fn explained_args<'l>(&self, l: &'l Literal) -> Result<(String, &'l Expr), Diagnostic> {
        let users: Vec<&str> = self
            .project
            .manifest
            .explanation
            .iter()
            .flat_map(|e| e.users.iter().map(|u| u.name.value.as_str()))
            .collect();
        let [u, a] = l.args.as_slice() else {
            return Err(Diagnostic::error(
                "input",
                "`explained` takes a user and an action: `explained(user, a)`",
            )
            .with_label(l.span, "wrong number of arguments"));
        };
        let named = match &u.kind {
            ExprKind::Literal(x) if x.args.is_empty() => Some(x.functor.as_str()),
            _ => None,
        };
        match named.filter(|n| users.contains(n)) {
            Some(n) => Ok((n.to_string(), a)),
            None => Err(Diagnostic::error(
                "input",
                format!(
                    "`explained` names a user of `[explanation.users]`: {}",
                    if users.is_empty() {
                        "this project has none".to_string()
                    } else {
                        users
                            .iter()
                            .map(|u| format!("`{u}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                ),
            )
            .with_label(u.span, "no such user")),
        }
    }

    /// Gives variable `x` the type `ty` (met with the one it has).
    fn type_var(
        &self,
        x: &Expr,
        ty: Option<TypeId>,
        types: &mut BTreeMap<String, TypeId>,
    ) -> Result<(), Diagnostic> {
        let (ExprKind::Var(v), Some(ty)) = (&x.kind, ty) else {
            return Ok(());
        };
        if v.name.starts_with('_') || ty == TypeId::OBJECT {
            return Ok(());
        }
        let u = &self.project.universe;
        let t = match types.get(&v.name) {
            None => ty,
            Some(&prev) => u.meet(prev, ty).ok_or_else(|| {
                Diagnostic::error(
                    "input",
                    format!(
                        "variable `{}` would be both a `{}` and a `{}`",
                        v.name,
                        u.type_name(prev),
                        u.type_name(ty)
                    ),
                )
                .with_label(x.span, "here")
            })?,
        };
        types.insert(v.name.clone(), t);
        Ok(())
    }

    /// The modality's name (`.intend` read as `intends`), its agent (index among the
    /// project's agents; 0 in a project of one) and its formula argument.
    fn modal_arg<'l>(&self, l: &'l Literal) -> Result<(&'static str, u8, &'l Expr), Diagnostic> {
        let what = match l.functor.as_str() {
            "believes" => "believes",
            "holds" => "holds",
            "desires" | ".desire" => "desires",
            "intends" | ".intend" => "intends",
            "did" => "did",
            "requested" => "requested",
            _ => {
                return Err(Diagnostic::error(
                    "input",
                    "`explained` cannot be used in a property yet: the explanations are checked by the explanation properties of each user",
                )
                .with_label(l.span, "not supported here"))
            }
        };
        let agent_arg = matches!(what, "believes" | "desires" | "intends" | "did")
            && !l.functor.starts_with('.');
        let several = !self.agents.is_empty();
        let (agent, arg) = match (l.args.as_slice(), agent_arg) {
            ([f], true) if several => {
                return Err(Diagnostic::error(
                    "input",
                    format!(
                    "`{}` must name its agent in a project of several: `{}(agent, ...)`, one of {}",
                    l.functor,
                    l.functor,
                    self.agents
                        .iter()
                        .map(|a| format!("`{a}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                )
                .with_label(l.span, "whose?"))
            }
            ([f], _) => (0, f),
            ([ag, f], true) => {
                let named = match &ag.kind {
                    ExprKind::Literal(a) if a.args.is_empty() => Some(a.functor.as_str()),
                    _ => None,
                };
                let found = if several {
                    self.agents.iter().position(|a| Some(a.as_str()) == named)
                } else {
                    (named == Some(self.project.name.as_str())).then_some(0)
                };
                let Some(k) = found else {
                    let have = if several {
                        self.agents
                            .iter()
                            .map(|a| format!("`{a}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    } else {
                        format!("`{}`", self.project.name)
                    };
                    return Err(Diagnostic::error(
                        "input",
                        format!(
                            "`{}` names an agent this project does not have: its agents are {have}",
                            l.functor
                        ),
                    )
                    .with_label(ag.span, "no such agent"));
                };
                (k as u8, f)
            }
            _ => {
                let how = if agent_arg {
                    format!("`{0}(f)` or `{0}(agent, f)`", l.functor)
                } else {
                    format!("`{}(f)`", l.functor)
                };
                return Err(Diagnostic::error(
                    "input",
                    format!("`{}` takes one formula: write {how}", l.functor),
                )
                .with_label(l.span, "wrong number of arguments"));
            }
        };
        Ok((what, agent, arg))
    }

    fn ground_shape(
        &self,
        s: &Shape,
        env: &Env,
        atomics: &mut Atomics,
        user: &mut Option<String>,
    ) -> Result<Ltl, Diagnostic> {
        Ok(match s {
            Shape::State(e) => self.ground_state(e, env, atomics, user)?,
            Shape::Unary(op, a) => {
                let a = self.ground_shape(a, env, atomics, user)?;
                match op {
                    LtlUnary::Not => Ltl::not(a),
                    LtlUnary::Next => Ltl::next(a),
                    LtlUnary::Always => Ltl::always(a),
                    LtlUnary::Eventually => Ltl::eventually(a),
                }
            }
            Shape::Binary(op, a, b) => {
                let a = self.ground_shape(a, env, atomics, user)?;
                let b = self.ground_shape(b, env, atomics, user)?;
                match op {
                    LtlBinary::And => Ltl::and(a, b),
                    LtlBinary::Or => Ltl::or(a, b),
                    LtlBinary::Implies => Ltl::implies(a, b),
                    LtlBinary::Iff => Ltl::iff(a, b),
                    LtlBinary::LeadsTo => Ltl::leads_to(a, b),
                    LtlBinary::Until => Ltl::until(a, b),
                    LtlBinary::Release => Ltl::release(a, b),
                    LtlBinary::WeakUntil => Ltl::weak_until(a, b),
                }
            }
        })
    }

    fn ground_state(
        &self,
        e: &Expr,
        env: &Env,
        atomics: &mut Atomics,
        user: &mut Option<String>,
    ) -> Result<Ltl, Diagnostic> {
        if !is_modal(e) {
            let c = ground_with(e, self.atoms, &self.project.universe, self.agents, env)?;
            return Ok(atomics.intern(Atomic::Beliefs(c)));
        }
        Ok(match &e.kind {
            ExprKind::Not(a) => Ltl::not(self.ground_state(a, env, atomics, user)?),
            ExprKind::And(a, b) => Ltl::and(
                self.ground_state(a, env, atomics, user)?,
                self.ground_state(b, env, atomics, user)?,
            ),
            ExprKind::Or(a, b) => Ltl::or(
                self.ground_state(a, env, atomics, user)?,
                self.ground_state(b, env, atomics, user)?,
            ),
            ExprKind::Literal(l) if l.functor == "explained" => {
                let (u, a) = self.explained_args(l)?;
                if user.as_ref().is_some_and(|x| *x != u) {
                    return Err(Diagnostic::error(
                        "input",
                        "a property may name one user in `explained`: it is decided on that user's explanation search",
                    )
                    .with_label(l.span, "a second user"));
                }
                *user = Some(u);
                let t = self.ground_term(a, env)?;
                atomics.intern(Atomic::Explained(t))
            }
            ExprKind::Literal(l) if MODALITIES.contains(&l.functor.as_str()) => {
                let (what, agent, arg) = self.modal_arg(l)?;
                match what {
                    "believes" | "holds" => {
                        if is_modal(arg) {
                            return Err(modal_inside(arg));
                        }
                        let c =
                            ground_with(arg, self.atoms, &self.project.universe, self.agents, env)?;
                        // Among several agents a belief is an atom of the agent's own part
                        // (`formula::agent_stride`); the environment's atoms are the plain ones.
                        let c = if what == "believes" && !self.agents.is_empty() {
                            let stride = super::formula::agent_stride(self.atoms) as u32;
                            map_atoms(&c, &|a| {
                                if a.0 < stride {
                                    super::atoms::AtomId(a.0 + (u32::from(agent) + 1) * stride)
                                } else {
                                    a
                                }
                            })
                        } else {
                            c
                        };
                        atomics.intern(Atomic::Beliefs(c))
                    }
                    _ => {
                        let t = self.ground_term(arg, env)?;
                        atomics.intern(match what {
                            "desires" => Atomic::Desires(agent, t),
                            "intends" => Atomic::Intends(agent, t),
                            "did" => Atomic::Did(agent, t),
                            _ => Atomic::Requested(t),
                        })
                    }
                }
            }
            _ => return Err(modal_inside(e)),
        })
    }

    /// A goal or action pattern with the bound variables replaced by their objects;
    /// anonymous variables stay (they match anything).
    fn ground_term(&self, arg: &Expr, env: &Env) -> Result<Term, Diagnostic> {
        if !matches!(arg.kind, ExprKind::Literal(_)) {
            return Err(Diagnostic::error("input", "expected a goal or an action")
                .with_label(arg.span, "such as `storeCup(C)` or `navigateTo(table)`"));
        }
        let t = super::from_ast::term_from_expr(arg).map_err(|e| {
            Diagnostic::error("input", e.message.clone()).with_label(e.span, "here")
        })?;
        let mut s = super::subst::Substitution::new();
        for (name, o) in env {
            s.bind(
                super::term::Var::named(name),
                Term::atom(self.project.universe.object_name(*o)),
            );
        }
        let t = s.apply(&t);
        if let Some(v) = free_named_var(&t) {
            return Err(
                Diagnostic::error("input", format!("variable `{v}` has no type here")).with_label(
                    arg.span,
                    "use it as an argument of a predicate, a goal or an action to give it a type",
                ),
            );
        }
        Ok(t)
    }
}

/// `c` with every atom `a` read as `f(a)`.
fn map_atoms(c: &Cond, f: &impl Fn(super::atoms::AtomId) -> super::atoms::AtomId) -> Cond {
    match c {
        Cond::True => Cond::True,
        Cond::False => Cond::False,
        Cond::Atom(a) => Cond::Atom(f(*a)),
        Cond::Not(x) => Cond::Not(Box::new(map_atoms(x, f))),
        Cond::And(xs) => Cond::And(xs.iter().map(|x| map_atoms(x, f)).collect()),
        Cond::Or(xs) => Cond::Or(xs.iter().map(|x| map_atoms(x, f)).collect()),
        Cond::Count { atoms, cmp, n } => Cond::Count {
            atoms: atoms.iter().map(|a| f(*a)).collect(),
            cmp: *cmp,
            n: *n,
        },
    }
}

fn free_named_var(t: &Term) -> Option<String> {
    if let Some(v) = t.as_var() {
        return (!v.is_anonymous()).then(|| v.name().to_string());
    }
    t.args().iter().chain(t.annots()).find_map(free_named_var)
}

fn modal_inside(e: &Expr) -> Diagnostic {
    Diagnostic::error(
        "input",
        "a modality can be combined with `not`, `&` and `|` only",
    )
    .with_label(
        e.span,
        "not inside `.count`, a comparison or another modality's formula",
    )
}
