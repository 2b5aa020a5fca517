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
use crate::model::cond::Cond;
use crate::model::plans::Formula;
use crate::model::project::Project;
use crate::model::term::{Term, Var};
use crate::model::universe::{ObjectId, TypeId};
use std::cell::{Cell, RefCell};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use z3::ast::{Bool, Int};

mod count;
mod formula;
mod literal;
mod rules;

pub use count::pb;
pub use literal::tuples;
pub use rules::rule_clauses;
use rules::rules_of;

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
        Encoder::with_base(project, base)
    }

    /// An encoder with no atom constants, for checks that encode no state (a project
    /// with more atoms than [`crate::smt::MAX_LINT_ATOMS`]): encoding a state with it
    /// is a bug.
    pub fn without_atoms(project: &'p Project) -> Encoder<'p> {
        Encoder::with_base(project, Vec::new())
    }

    fn with_base(project: &'p Project, base: State) -> Encoder<'p> {
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
}

fn is_arith(f: &str) -> bool {
    matches!(f, "+" | "-" | "*" | "/" | "div" | "mod" | "**")
}
