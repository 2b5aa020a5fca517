//! Manifest formulas (constraints, invariants, state properties) compiled to ground
//! conditions.
//!
//! SPEC §1: "A variable free in a formula ranges over the objects of the type that the PDDL
//! predicate signature gives it; the formula must hold for all of them." So every named
//! variable is universally closed over its type, even inside `.count`: in
//! `.count(cupAt(C,_), 1)` the variable `C` ranges over the cups and the formula says that
//! every cup stands in exactly one place. Anonymous variables (`_`, `_Name`) are what is
//! counted inside `.count`, and existential elsewhere (`not robotAt(_)`: the robot is
//! nowhere). Strong negation on an environment atom means `not` (the environment is
//! closed-world: every atom not perceived true is false).

use super::atoms::{AtomId, AtomTable, PredId};
use super::cond::{Cond, CountCmp};
use super::ground::product;
use super::universe::{ObjectId, TypeId, Universe};
use crate::syntax::ast::{Expr, ExprKind, Literal, RelOp, UnaryOp};
use crate::syntax::Diagnostic;
use std::collections::BTreeMap;

/// Compiles a formula to a ground condition that holds exactly when the formula holds for
/// every object assigned to its free variables.
pub fn compile(expr: &Expr, atoms: &AtomTable, universe: &Universe) -> Result<Cond, Diagnostic> {
    compile_in(expr, atoms, universe, &[])
}

/// [`compile`] in a project of several agents: `ag::b` is agent `ag`'s belief `b` (Jason's
/// namespace syntax), the atom `(k + 1) * agent_stride(atoms) + b` for the agent of index
/// `k` in `agents`; a literal without a namespace is the shared environment's.
pub fn compile_in(
    expr: &Expr,
    atoms: &AtomTable,
    universe: &Universe,
    agents: &[String],
) -> Result<Cond, Diagnostic> {
    let c = Compiler {
        atoms,
        universe,
        agents,
    };
    let mut types: BTreeMap<String, TypeId> = BTreeMap::new();
    c.infer(expr, &mut types)?;
    let names: Vec<&String> = types.keys().collect();
    let tys: Vec<TypeId> = types.values().copied().collect();
    let mut parts = Vec::new();
    for objs in product(universe, &tys) {
        let env: BTreeMap<&str, ObjectId> = names.iter().map(|n| n.as_str()).zip(objs).collect();
        let part = c.ground(expr, &env)?;
        if part == Cond::False {
            return Ok(Cond::False);
        }
        parts.push(part);
    }
    Ok(Cond::and(parts))
}

/// Adds to `types` the type of every named variable of the state formula `expr`, from the
/// predicate positions it fills (a variable in several takes their meet). For formulas whose
/// variables are shared with others, as in an `ltl` property.
pub fn infer_types(
    expr: &Expr,
    atoms: &AtomTable,
    universe: &Universe,
    agents: &[String],
    types: &mut BTreeMap<String, TypeId>,
) -> Result<(), Diagnostic> {
    Compiler {
        atoms,
        universe,
        agents,
    }
    .infer(expr, types)
}

/// The state formula `expr` as a ground condition, its named variables bound by `env`.
pub fn ground_with(
    expr: &Expr,
    atoms: &AtomTable,
    universe: &Universe,
    agents: &[String],
    env: &BTreeMap<&str, ObjectId>,
) -> Result<Cond, Diagnostic> {
    Compiler {
        atoms,
        universe,
        agents,
    }
    .ground(expr, env)
}

fn is_anonymous(name: &str) -> bool {
    name.starts_with('_')
}

struct Compiler<'a> {
    atoms: &'a AtomTable,
    universe: &'a Universe,
    /// The agents a namespace may name (none in a project of one agent).
    agents: &'a [String],
}

/// Where the atoms of the agents begin in a condition of [`compile_in`]: agent `k`'s atom
/// `a` is `(k + 1) * stride + a` (a whole number of 64-bit words per agent).
pub fn agent_stride(atoms: &AtomTable) -> usize {
    atoms.len().div_ceil(64) * 64
}

type Env<'e> = BTreeMap<&'e str, ObjectId>;

impl Compiler<'_> {
    fn pred(&self, l: &Literal) -> Result<PredId, Diagnostic> {
        self.atoms.pred(&l.functor).ok_or_else(|| {
            Diagnostic::error(
                "input",
                format!("`{}` is not a predicate of this project", l.functor),
            )
            .with_label(l.span, "unknown predicate")
        })
    }

    /// The type of every named variable, from the predicate positions it occupies.
    fn infer(&self, e: &Expr, types: &mut BTreeMap<String, TypeId>) -> Result<(), Diagnostic> {
        match &e.kind {
            ExprKind::Literal(l) if l.functor == ".count" => match l.args.first() {
                Some(q) => self.infer(q, types),
                None => Ok(()),
            },
            ExprKind::Literal(l) if l.functor == "true" || l.functor == "false" => Ok(()),
            ExprKind::Literal(l) if l.is_internal_action() => Err(Diagnostic::error(
                "input",
                format!("`{}` cannot be used in a state formula here", l.functor),
            )
            .with_label(l.span, "only `.count` is evaluated on a state")),
            ExprKind::Literal(l) => {
                let p = self.pred(l)?;
                let params = self.atoms.pred_params(p).to_vec();
                for (arg, ty) in l.args.iter().zip(params) {
                    if let ExprKind::Var(v) = &arg.kind {
                        if is_anonymous(&v.name) {
                            continue;
                        }
                        let t = match types.get(&v.name) {
                            None => ty,
                            Some(&prev) => self.universe.meet(prev, ty).ok_or_else(|| {
                                Diagnostic::error(
                                    "input",
                                    format!(
                                        "variable `{}` would be both a `{}` and a `{}`",
                                        v.name,
                                        self.universe.type_name(prev),
                                        self.universe.type_name(ty)
                                    ),
                                )
                                .with_label(arg.span, "here")
                            })?,
                        };
                        types.insert(v.name.clone(), t);
                    }
                }
                Ok(())
            }
            ExprKind::Not(a) => self.infer(a, types),
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                self.infer(a, types)?;
                self.infer(b, types)
            }
            // A variable compared with `==` gets its type from the literals around it;
            // `ground` reports one that has none.
            _ => Ok(()),
        }
    }

    fn ground(&self, e: &Expr, env: &Env) -> Result<Cond, Diagnostic> {
        match &e.kind {
            ExprKind::Literal(l) if l.functor == "true" && l.args.is_empty() => Ok(Cond::True),
            ExprKind::Literal(l) if l.functor == "false" && l.args.is_empty() => Ok(Cond::False),
            ExprKind::Literal(l) if l.functor == ".count" => self.count(l, env),
            ExprKind::Literal(l) => {
                let atoms = self.instances(l, env)?;
                let c = Cond::or(atoms.into_iter().map(Cond::Atom).collect());
                // `~p` on a closed-world atom is `not p`.
                Ok(if l.negated { Cond::negate(c) } else { c })
            }
            ExprKind::Not(a) => Ok(Cond::negate(self.ground(a, env)?)),
            ExprKind::And(a, b) => Ok(Cond::and(vec![self.ground(a, env)?, self.ground(b, env)?])),
            ExprKind::Or(a, b) => Ok(Cond::or(vec![self.ground(a, env)?, self.ground(b, env)?])),
            ExprKind::Rel(op, a, b) => self.relation(*op, a, b, env),
            _ => Err(
                Diagnostic::error("input", "not a state formula").with_label(
                    e.span,
                    "expected a literal, `not`, `&`, `|`, a comparison or `.count`",
                ),
            ),
        }
    }

    /// The atoms `l` stands for under `env`: one when every argument is bound, every
    /// instance of the anonymous positions otherwise.
    fn instances(&self, l: &Literal, env: &Env) -> Result<Vec<AtomId>, Diagnostic> {
        let p = self.pred(l)?;
        let params = self.atoms.pred_params(p).to_vec();
        if l.args.len() != params.len() {
            return Err(Diagnostic::error(
                "input",
                format!(
                    "`{}` takes {} arguments, not {}",
                    l.functor,
                    params.len(),
                    l.args.len()
                ),
            )
            .with_label(l.span, "wrong number of arguments"));
        }
        let mut fixed: Vec<Option<ObjectId>> = Vec::new();
        let mut open_types = Vec::new();
        for (arg, ty) in l.args.iter().zip(&params) {
            match &arg.kind {
                ExprKind::Var(v) if is_anonymous(&v.name) => {
                    fixed.push(None);
                    open_types.push(*ty);
                }
                _ => fixed.push(Some(self.object(arg, env)?)),
            }
        }
        let mut out = Vec::new();
        for fill in product(self.universe, &open_types) {
            let mut fill = fill.into_iter();
            let args: Vec<ObjectId> = fixed
                .iter()
                .map(|f| f.unwrap_or_else(|| fill.next().unwrap_or(ObjectId(0))))
                .collect();
            // An object outside the predicate's types makes an atom that cannot exist.
            if let Some(a) = self.atoms.id(p, &args) {
                out.push(a);
            }
        }
        out.sort();
        out.dedup();
        if let Some(ns) = &l.namespace {
            let agent = match &ns.kind {
                crate::syntax::ast::NamespaceKind::Named(n) => {
                    self.agents.iter().position(|a| a == n)
                }
                _ => None,
            };
            let Some(k) = agent else {
                let what = if self.agents.is_empty() {
                    "a namespace in a formula names an agent, and this project has one".to_string()
                } else {
                    format!(
                        "a namespace in a formula names an agent: one of {}",
                        self.agents
                            .iter()
                            .map(|a| format!("`{a}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                };
                return Err(Diagnostic::error("input", what).with_label(ns.span, "no such agent"));
            };
            let base = (k + 1) * agent_stride(self.atoms);
            for a in &mut out {
                a.0 += base as u32;
            }
        }
        Ok(out)
    }

    fn object(&self, arg: &Expr, env: &Env) -> Result<ObjectId, Diagnostic> {
        match &arg.kind {
            ExprKind::Var(v) => env.get(v.name.as_str()).copied().ok_or_else(|| {
                Diagnostic::error("input", format!("variable `{}` has no type here", v.name))
                    .with_label(
                        arg.span,
                        "use it as an argument of a predicate to give it a type",
                    )
            }),
            ExprKind::Literal(l) if l.args.is_empty() && !l.negated && l.annots.is_none() => {
                self.universe.object(&l.functor).ok_or_else(|| {
                    Diagnostic::error("input", format!("`{}` is not an object", l.functor))
                        .with_label(arg.span, "unknown object")
                })
            }
            _ => Err(
                Diagnostic::error("input", "expected an object or a variable")
                    .with_label(arg.span, "states hold atoms over objects only"),
            ),
        }
    }

    fn count(&self, l: &Literal, env: &Env) -> Result<Cond, Diagnostic> {
        let (q, n) = match l.args.as_slice() {
            [q, n] => (q, n),
            _ => {
                return Err(
                    Diagnostic::error("input", "`.count` takes a query and a number")
                        .with_label(l.span, "expected `.count(Query, N)`"),
                )
            }
        };
        let ExprKind::Literal(ql) = &q.kind else {
            return Err(
                Diagnostic::error("input", "the query of `.count` must be a literal")
                    .with_label(q.span, "expected a literal such as `cupAt(C, _)`"),
            );
        };
        let n = integer(n).ok_or_else(|| {
            Diagnostic::error("input", "the count of `.count` must be an integer here")
                .with_label(n.span, "expected an integer")
        })?;
        Ok(Cond::count(self.instances(ql, env)?, CountCmp::Eq, n))
    }

    fn relation(&self, op: RelOp, a: &Expr, b: &Expr, env: &Env) -> Result<Cond, Diagnostic> {
        let truth = match (integer(a), integer(b)) {
            (Some(x), Some(y)) => match op {
                RelOp::Lt => x < y,
                RelOp::Le => x <= y,
                RelOp::Gt => x > y,
                RelOp::Ge => x >= y,
                RelOp::Eq | RelOp::Unify => x == y,
                RelOp::Ne => x != y,
                RelOp::Univ => return Err(unsupported_relation(a, b)),
            },
            _ => {
                let x = self.object(a, env)?;
                let y = self.object(b, env)?;
                match op {
                    RelOp::Eq | RelOp::Unify => x == y,
                    RelOp::Ne => x != y,
                    _ => return Err(unsupported_relation(a, b)),
                }
            }
        };
        Ok(if truth { Cond::True } else { Cond::False })
    }
}

fn unsupported_relation(a: &Expr, b: &Expr) -> Diagnostic {
    Diagnostic::error(
        "input",
        "this comparison is not supported in a state formula",
    )
    .with_label(
        a.span.to(b.span),
        "compare objects with `==`/`\\==`, integers with `<`, `>`, ...",
    )
}

fn integer(e: &Expr) -> Option<i64> {
    match &e.kind {
        ExprKind::Int(n) => Some(*n),
        ExprKind::Unary(UnaryOp::Neg, inner) => integer(inner).map(|n| -n),
        ExprKind::Unary(UnaryOp::Plus, inner) => integer(inner),
        _ => None,
    }
}
