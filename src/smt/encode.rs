//! The model in z3: states, ground conditions, plan contexts, triggers and rules.
//!
//! A state is one z3 Boolean per ground atom ([`State`]); ground conditions ([`Cond`]:
//! invariants, preconditions, `when` conditions) map onto it one to one, `.count` as a
//! pseudo-Boolean constraint. Plan formulas ([`Formula`]) are Jason queries whose meaning
//! depends on the order in which their variables get bound, so they are encoded left to
//! right along each conjunction, in one of two modes:
//!
//! * [`Mode::Assert`], for a formula asserted to hold (a context the plan was chosen with):
//!   every variable bound at a positive position becomes a z3 integer constant holding an
//!   object id, constrained to the objects of its type (a *symbolic* variable), and stays in
//!   the environment for the plan body;
//! * [`Mode::Closed`], for a formula that may be negated (another plan's context in a
//!   coverage or shadowing query): a variable bound by one conjunct and read by a later one is
//!   expanded over the objects of its type (`∃X. φ` as `φ[a] ∨ φ[b] ∨ ...`), a variable read
//!   only where it is bound becomes a disjunction over the instances of that literal.
//!
//! `not` is always closed (negation as failure binds nothing). A disjunction whose branches
//! bind a variable that a later conjunct reads is distributed over the rest of the
//! conjunction, which is exactly Jason's answer semantics (`(a(X) | b) & c(X)` is
//! `∃X(a(X) ∧ c(X)) ∨ (b ∧ ∃X c(X))`). Rules of the agent are inlined clause by clause.
//! Anything else (annotations, strong negation, recursive rules, internal actions beyond
//! `.count`, `.member`, `.desire`, `.intend`) is [`Unsupported`]: the check that meets it
//! answers `unknown` rather than guess.

use crate::model::atoms::AtomId;
use crate::model::cond::{Cond, CountCmp};
use crate::model::from_ast::{ConvertError, Converter};
use crate::model::plans::Formula;
use crate::model::project::Project;
use crate::model::term::{Term, Var};
use crate::model::universe::{ObjectId, TypeId};
use crate::syntax::ast::{Expr, Item, RelOp};
use std::cell::{Cell, RefCell};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use z3::ast::{Bool, Int};

/// A state: one Boolean per ground atom, indexed by [`AtomId`].
pub type State = Vec<Bool>;

/// A construct the encoding does not cover, with what it is. A check that meets one
/// answers `unknown`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

/// The result of encoding something that may be unsupported.
pub type Enc<T> = Result<T, Unsupported>;

/// Instance enumerations beyond this are refused rather than built.
const MAX_INSTANCES: usize = 1_000_000;

/// The value of a variable (or of a ground term) during encoding.
#[derive(Clone, Debug)]
pub enum Val {
    /// An object known at encoding time.
    Obj(ObjectId),
    /// An object the solver chooses: an integer holding its id.
    Sym(Int),
    /// An integer (a `.count` result, arithmetic).
    Num(Int),
    /// Another ground term (a string, a non-integral number, an atom that is no object, a
    /// list), compared structurally.
    Other(Term),
}

/// Variable bindings.
pub type Env = BTreeMap<Var, Val>;

/// How a formula is encoded: see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Asserted to hold: positively bound variables become symbolic and stay bound.
    Assert,
    /// Closed: every variable the formula binds is local to it.
    Closed,
}

/// One use of a plan or rule clause: its variables' symbolic constants.
#[derive(Debug)]
pub struct Frame {
    tag: u32,
    made: u32,
    syms: BTreeMap<Var, Int>,
}

impl Frame {
    /// The symbolic constant of `v` in this frame.
    pub fn sym(&mut self, v: &Var) -> Int {
        if let Some(x) = self.syms.get(v) {
            return x.clone();
        }
        self.made += 1;
        let x = Int::new_const(format!("{v}#{}.{}", self.tag, self.made));
        self.syms.insert(v.clone(), x.clone());
        x
    }

    /// Forgets the constants of variables not bound in `env`: a later binding of the same
    /// variable (after an `if` whose branch bound it) gets a new constant.
    pub fn keep_only(&mut self, env: &Env) {
        self.syms.retain(|v, _| env.contains_key(v));
    }
}

/// How a conjunct binds a variable that was unbound before it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Binder {
    /// By matching an atom: the variable ranges over the objects of this type.
    Domain(TypeId),
    /// By computing a value (`X = a`, `.count(q, N)`).
    Value,
}

/// A rule clause `head :- body`, in model terms.
#[derive(Clone, Debug)]
pub struct Clause {
    /// The head literal.
    pub head: Term,
    /// The body (`True` for a fact-like rule).
    pub body: Formula,
}

/// Encodes a project's formulas over z3 states. One encoder per z3 context.
pub struct Encoder<'p> {
    /// The project.
    pub project: &'p Project,
    /// The state every check starts from: one named constant per atom.
    pub base: State,
    rules: HashMap<(String, usize), Enc<Vec<Clause>>>,
    frames: Cell<u32>,
    fresh: Cell<u32>,
    /// Expanded combinations in the formula being encoded (nested expansions multiply).
    expanded: Cell<usize>,
    reads: RefCell<Option<BTreeSet<AtomId>>>,
    call_reads: RefCell<Option<BTreeSet<String>>>,
    calls: RefCell<BTreeMap<String, Bool>>,
    active_rules: RefCell<Vec<(String, usize)>>,
}

fn tt() -> Bool {
    Bool::from_bool(true)
}

fn ff() -> Bool {
    Bool::from_bool(false)
}

/// The conjunction, simplified when trivial.
pub fn and(parts: Vec<Bool>) -> Bool {
    match parts.len() {
        0 => tt(),
        1 => parts.into_iter().next().unwrap_or_else(tt),
        _ => Bool::and(&parts),
    }
}

/// The disjunction, simplified when trivial.
pub fn or(parts: Vec<Bool>) -> Bool {
    match parts.len() {
        0 => ff(),
        1 => parts.into_iter().next().unwrap_or_else(ff),
        _ => Bool::or(&parts),
    }
}

/// An object id as a z3 integer.
pub fn obj(o: ObjectId) -> Int {
    Int::from_i64(i64::from(o.0))
}

/// Whether two values are equal.
pub fn val_eq(a: &Val, b: &Val) -> Bool {
    match (a, b) {
        (Val::Obj(x), Val::Obj(y)) => Bool::from_bool(x == y),
        (Val::Obj(o), Val::Sym(s)) | (Val::Sym(s), Val::Obj(o)) => s.eq(obj(*o)),
        (Val::Sym(s), Val::Sym(t)) => s.eq(t),
        (Val::Num(x), Val::Num(y)) => x.eq(y),
        (Val::Other(x), Val::Other(y)) => Bool::from_bool(x == y),
        _ => ff(),
    }
}

/// Whether two values are the same encoding (not merely equal in every model).
fn same_val(a: &Val, b: &Val) -> bool {
    match (a, b) {
        (Val::Obj(x), Val::Obj(y)) => x == y,
        (Val::Sym(x), Val::Sym(y)) | (Val::Num(x), Val::Num(y)) => x.ast_eq(y),
        (Val::Other(x), Val::Other(y)) => x == y,
        _ => false,
    }
}

/// Every named variable of a formula (bound or not), for "is it read later" questions.
pub fn formula_vars(f: &Formula, out: &mut BTreeSet<Var>) {
    match f {
        Formula::True => {}
        Formula::Literal(t) | Formula::Call(t) => out.extend(t.vars()),
        Formula::Not(g) => formula_vars(g, out),
        Formula::And(a, b) | Formula::Or(a, b) => {
            formula_vars(a, out);
            formula_vars(b, out);
        }
        Formula::Rel(_, a, b) => {
            out.extend(a.vars());
            out.extend(b.vars());
        }
    }
}

/// The conjuncts of a formula, in order (`a & (b & c)` is `[a, b, c]`).
pub fn conjuncts(f: &Formula) -> Vec<&Formula> {
    let mut out = Vec::new();
    fn go<'f>(f: &'f Formula, out: &mut Vec<&'f Formula>) {
        match f {
            Formula::And(a, b) => {
                go(a, out);
                go(b, out);
            }
            other => out.push(other),
        }
    }
    go(f, &mut out);
    out
}

impl<'p> Encoder<'p> {
    /// An encoder for `project` in the current z3 context: one Boolean constant per atom,
    /// named as the atom prints, and the agent's rules converted.
    pub fn new(project: &'p Project) -> Encoder<'p> {
        let base = (0..project.atoms.len() as u32)
            .map(|a| Bool::new_const(project.atoms.display(AtomId(a), &project.universe)))
            .collect();
        Encoder {
            project,
            base,
            rules: rules_of(project),
            frames: Cell::new(0),
            fresh: Cell::new(0),
            expanded: Cell::new(0),
            reads: RefCell::new(None),
            call_reads: RefCell::new(None),
            calls: RefCell::new(BTreeMap::new()),
            active_rules: RefCell::new(Vec::new()),
        }
    }

    /// A new frame for one use of a plan or a rule clause.
    pub fn frame(&self) -> Frame {
        let tag = self.frames.get() + 1;
        self.frames.set(tag);
        Frame {
            tag,
            made: 0,
            syms: BTreeMap::new(),
        }
    }

    /// A fresh Boolean constant.
    pub fn fresh_bool(&self, prefix: &str) -> Bool {
        let n = self.fresh.get() + 1;
        self.fresh.set(n);
        Bool::new_const(format!("{prefix}!{n}"))
    }

    /// A fresh integer constant.
    pub fn fresh_int(&self, prefix: &str) -> Int {
        let n = self.fresh.get() + 1;
        self.fresh.set(n);
        Int::new_const(format!("{prefix}!{n}"))
    }

    /// Starts recording which atoms the encodings read.
    pub fn record_reads(&self) {
        *self.reads.borrow_mut() = Some(BTreeSet::new());
        *self.call_reads.borrow_mut() = Some(BTreeSet::new());
    }

    /// The `.desire`/`.intend` Booleans read since [`Encoder::record_reads`], with their
    /// text (`.desire(b)`), in order.
    pub fn take_call_reads(&self) -> Vec<(String, Bool)> {
        let names = self.call_reads.borrow_mut().take().unwrap_or_default();
        let calls = self.calls.borrow();
        names
            .into_iter()
            .filter_map(|n| calls.get(&n).map(|b| (n, b.clone())))
            .collect()
    }

    /// Stops recording and returns the atoms read since [`Encoder::record_reads`].
    pub fn take_reads(&self) -> BTreeSet<AtomId> {
        self.reads.borrow_mut().take().unwrap_or_default()
    }

    fn read(&self, a: AtomId) {
        if let Some(r) = self.reads.borrow_mut().as_mut() {
            r.insert(a);
        }
    }

    /// The Boolean of atom `a` in `st`.
    pub fn atom(&self, st: &State, a: AtomId) -> Bool {
        self.read(a);
        st[a.0 as usize].clone()
    }

    /// `x` is one of the objects of type `t`.
    pub fn dom(&self, x: &Int, t: TypeId) -> Bool {
        let objs = self.project.universe.objects_of(t);
        match (objs.first(), objs.last()) {
            (None, _) | (_, None) => ff(),
            (Some(lo), Some(hi)) if (hi.0 - lo.0) as usize + 1 == objs.len() => {
                Bool::and(&[x.ge(obj(*lo)), x.le(obj(*hi))])
            }
            _ => or(objs.iter().map(|o| x.eq(obj(*o))).collect()),
        }
    }

    /// A ground condition on `st`.
    pub fn cond(&self, c: &Cond, st: &State) -> Bool {
        match c {
            Cond::True => tt(),
            Cond::False => ff(),
            Cond::Atom(a) => self.atom(st, *a),
            Cond::Not(c) => self.cond(c, st).not(),
            Cond::And(cs) => and(cs.iter().map(|c| self.cond(c, st)).collect()),
            Cond::Or(cs) => or(cs.iter().map(|c| self.cond(c, st)).collect()),
            Cond::Count { atoms, cmp, n } => {
                let bs: Vec<Bool> = atoms.iter().map(|a| self.atom(st, *a)).collect();
                pb(&bs, *cmp, *n)
            }
        }
    }

    /// The value of a term under `env`: `None` when it holds an unbound variable.
    pub fn term_val(&self, t: &Term, env: &Env) -> Enc<Option<Val>> {
        Ok(match t {
            Term::Var(v) => env.get(v).cloned(),
            Term::Atom(name) => Some(match self.project.universe.object(name) {
                Some(o) => Val::Obj(o),
                None => Val::Other(t.clone()),
            }),
            // A number of `[bounds] numbers` is an object of the model, as in its atoms.
            Term::Num(n) => Some(match (self.project.universe.object_of(t), n.as_i64()) {
                (Some(o), _) => Val::Obj(o),
                (None, Some(i)) => Val::Num(Int::from_i64(i)),
                (None, None) => Val::Other(t.clone()),
            }),
            Term::Str(_) => Some(Val::Other(t.clone())),
            Term::Struct(s) if is_arith(s.functor()) && !s.negated() && s.annots().is_empty() => {
                let mut nums = Vec::new();
                for a in s.args() {
                    match self.term_val(a, env)? {
                        None => return Ok(None),
                        Some(Val::Num(i)) => nums.push(i),
                        Some(_) => {
                            return Err(Unsupported(format!(
                                "arithmetic on something that is not an integer in `{t}`"
                            )))
                        }
                    }
                }
                Some(Val::Num(match (s.functor(), nums.as_slice()) {
                    ("+", [a, b]) => Int::add(&[a.clone(), b.clone()]),
                    ("-", [a, b]) => Int::sub(&[a.clone(), b.clone()]),
                    ("*", [a, b]) => Int::mul(&[a.clone(), b.clone()]),
                    ("-", [a]) => a.unary_minus(),
                    _ => {
                        return Err(Unsupported(format!(
                            "the arithmetic of `{t}` is not modelled by lint (only +, - and *)"
                        )))
                    }
                }))
            }
            _ if t.is_ground() => Some(Val::Other(t.clone())),
            _ => {
                return Err(Unsupported(format!(
                    "the structured term `{t}` with variables is not modelled by lint"
                )))
            }
        })
    }

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
                    Some(x) => eqs.push(val_eq(&x, e)),
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
                        .map(|f| super::text::formula(f))
                        .collect::<Vec<_>>()
                        .join(" & ");
                    out.push((text, self.chain(&elems[i..], env, frame, st, Mode::Assert)?));
                    return Ok(out);
                }
            }
            out.push((
                super::text::formula(e),
                self.element(e, env, frame, st, Mode::Assert)?,
            ));
        }
        Ok(out)
    }

    fn chain(
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
                        super::text::formula(first)
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
    fn arg_types(&self, t: &Term) -> Vec<TypeId> {
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

    fn call(&self, t: &Term, env: &mut Env, st: &State) -> Enc<Bool> {
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
    fn bind_args(&self, t: &Term, env: &mut Env, frame: &mut Frame) -> Vec<Bool> {
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

    fn rule_of(&self, t: &Term) -> Option<&Enc<Vec<Clause>>> {
        let key = (t.functor()?.to_string(), t.arity());
        self.rules.get(&key)
    }

    fn literal(
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

    fn rule_call(
        &self,
        t: &Term,
        clauses: &[Clause],
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
        mode: Mode,
    ) -> Enc<Bool> {
        let key = (t.functor().unwrap_or("").to_string(), t.arity());
        if self.active_rules.borrow().contains(&key) {
            return Err(Unsupported(format!(
                "the rule `{}/{}` is recursive; lint inlines non-recursive rules only",
                key.0, key.1
            )));
        }
        let mut extra = if mode == Mode::Assert {
            self.bind_args(t, env, frame)
        } else {
            Vec::new()
        };
        self.active_rules.borrow_mut().push(key);
        let result = (|| {
            let mut parts = Vec::new();
            for clause in clauses {
                let mut cenv = Env::new();
                let mut cframe = self.frame();
                let mut eqs = Vec::new();
                for (h, c) in clause.head.args().iter().zip(t.args()) {
                    let cv = self.term_val(c, env)?;
                    match h {
                        Term::Var(hv) => match (cenv.get(hv).cloned(), cv) {
                            (None, Some(cv)) => {
                                cenv.insert(hv.clone(), cv);
                            }
                            (Some(prev), Some(cv)) => eqs.push(val_eq(&prev, &cv)),
                            _ => {}
                        },
                        _ => {
                            let Some(hv) = self.term_val(h, &cenv)? else {
                                return Err(Unsupported(format!(
                                    "the rule head `{}` has structured arguments",
                                    clause.head
                                )));
                            };
                            if let Some(cv) = cv {
                                eqs.push(val_eq(&hv, &cv));
                            }
                        }
                    }
                }
                let body = self.chain(&[&clause.body], &mut cenv, &mut cframe, st, mode)?;
                eqs.push(body);
                parts.push(and(eqs));
            }
            Ok(or(parts))
        })();
        self.active_rules.borrow_mut().pop();
        extra.push(result?);
        Ok(and(extra))
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

fn vars_of(fs: &[&Formula]) -> BTreeSet<Var> {
    let mut out = BTreeSet::new();
    for f in fs {
        formula_vars(f, &mut out);
    }
    out
}

fn is_arith(f: &str) -> bool {
    matches!(f, "+" | "-" | "*" | "/" | "div" | "mod" | "**")
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

/// The number of true Booleans, as an integer.
fn sum(bs: &[Bool]) -> Int {
    if bs.is_empty() {
        return Int::from_i64(0);
    }
    let terms: Vec<Int> = bs
        .iter()
        .map(|b| b.ite(&Int::from_i64(1), &Int::from_i64(0)))
        .collect();
    Int::add(&terms)
}

/// A cardinality constraint: the number of true `bs` compares with `n` by `cmp`.
pub fn pb(bs: &[Bool], cmp: CountCmp, n: i64) -> Bool {
    let len = bs.len() as i64;
    let holds = |k: i64| match cmp {
        CountCmp::Eq => k == n,
        CountCmp::Lt => k < n,
        CountCmp::Le => k <= n,
        CountCmp::Gt => k > n,
        CountCmp::Ge => k >= n,
        CountCmp::Ne => k != n,
    };
    if (0..=len).all(holds) {
        return tt();
    }
    if !(0..=len).any(holds) {
        return ff();
    }
    // Within 0..=len the bound fits an i32 (len is a number of atoms).
    let k = n.clamp(-1, len + 1) as i32;
    let ws: Vec<(&Bool, i32)> = bs.iter().map(|b| (b, 1)).collect();
    match cmp {
        CountCmp::Eq => Bool::pb_eq(&ws, k),
        CountCmp::Ne => Bool::pb_eq(&ws, k).not(),
        CountCmp::Lt => Bool::pb_le(&ws, k - 1),
        CountCmp::Le => Bool::pb_le(&ws, k),
        CountCmp::Gt => Bool::pb_ge(&ws, k + 1),
        CountCmp::Ge => Bool::pb_ge(&ws, k),
    }
}

// ----- rules ------------------------------------------------------------------------------

/// The agent's rules, converted clause by clause (a clause that cannot be converted makes
/// its rule unsupported).
fn rules_of(project: &Project) -> HashMap<(String, usize), Enc<Vec<Clause>>> {
    let mut out: HashMap<(String, usize), Enc<Vec<Clause>>> = HashMap::new();
    for item in project.agent.items() {
        let Item::Rule(r) = item else { continue };
        let key = (r.head.functor.clone(), r.head.args.len());
        let mut conv = Converter::new();
        let clause = conv
            .literal(&r.head)
            .map_err(|e| convert_unsupported(&e))
            .and_then(|head| {
                Ok(Clause {
                    head,
                    body: expr_formula(&mut conv, &r.body)?,
                })
            });
        let entry = out.entry(key).or_insert_with(|| Ok(Vec::new()));
        match (entry.as_mut(), clause) {
            (Ok(v), Ok(c)) => v.push(c),
            (Ok(_), Err(e)) => *entry = Err(e),
            (Err(_), _) => {}
        }
    }
    out
}

fn convert_unsupported(e: &ConvertError) -> Unsupported {
    Unsupported(format!("a rule: {}", e.message))
}

/// A rule body as a formula, converted exactly as the plan library converts contexts.
fn expr_formula(c: &mut Converter, e: &Expr) -> Enc<Formula> {
    crate::model::plans::formula(c, e).map_err(|d| Unsupported(format!("a rule: {}", d.message)))
}

/// The agent's rules as clauses, for evaluators outside the encoding (tests, reports).
pub fn rule_clauses(project: &Project) -> HashMap<(String, usize), Result<Vec<Clause>, String>> {
    rules_of(project)
        .into_iter()
        .map(|(k, v)| (k, v.map_err(|u| u.0)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use z3::{SatResult, Solver};

    /// Every way `pb` can be asked, against counting on every assignment of three atoms.
    #[test]
    fn cardinality_constraints_count_exactly() {
        let bs: Vec<Bool> = (0..3).map(|i| Bool::new_const(format!("b{i}"))).collect();
        let cmps = [
            CountCmp::Eq,
            CountCmp::Lt,
            CountCmp::Le,
            CountCmp::Gt,
            CountCmp::Ge,
            CountCmp::Ne,
        ];
        let s = Solver::new();
        for cmp in cmps {
            for n in -1..=4i64 {
                let c = pb(&bs, cmp, n);
                for bits in 0u32..8 {
                    let k = bits.count_ones() as i64;
                    let expected = match cmp {
                        CountCmp::Eq => k == n,
                        CountCmp::Lt => k < n,
                        CountCmp::Le => k <= n,
                        CountCmp::Gt => k > n,
                        CountCmp::Ge => k >= n,
                        CountCmp::Ne => k != n,
                    };
                    let values: Vec<Bool> = bs
                        .iter()
                        .enumerate()
                        .map(|(i, b)| {
                            if bits >> i & 1 == 1 {
                                b.clone()
                            } else {
                                b.not()
                            }
                        })
                        .collect();
                    s.push();
                    s.assert(&c);
                    let sat = s.check_assumptions(&values) == SatResult::Sat;
                    s.pop(1);
                    assert_eq!(sat, expected, "{cmp:?} {n} with {bits:03b}");
                }
            }
        }
    }
}
