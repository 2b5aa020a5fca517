//! Answering formulas against the beliefs: Jason's logical consequence, as a list of
//! answers (substitutions), in a fixed order.
//!
//! A literal's answers are the believed atoms that unify with it, in atom order (predicate,
//! then arguments in object order). Jason walks its belief base instead, newest mental note
//! first; the two orders differ only for contexts with several answers, and a fixed order
//! keeps every run and report reproducible. Environment atoms carry `source(percept)` and
//! mental notes `source(self)`, as in Jason, so `p[source(percept)]` matches percepts only.

use super::state::{Intention, State};
use crate::model::atoms::{AtomId, AtomTable};
use crate::model::plans::Formula;
use crate::model::term::Term;
use crate::model::universe::Universe;
use crate::model::{unify, Substitution};
use crate::syntax::ast::{RelOp, TriggerKind, TriggerOp};

/// What formulas are evaluated against.
pub struct Beliefs<'a> {
    /// The ground atoms.
    pub atoms: &'a AtomTable,
    /// Objects.
    pub universe: &'a Universe,
    /// For each predicate, whether it is an environment predicate (else a mental note).
    pub environment: &'a [bool],
    /// The state (beliefs, and intentions for `.desire`/`.intend`).
    pub state: &'a State,
    /// The event being deliberated on, already out of the queue: Jason's `.intend` and
    /// `.desire` see its intention (and its goal) too.
    pub selected: Option<&'a super::state::Event>,
}

/// Arithmetic operators kept as structures by the plan compiler.
const ARITH: [&str; 7] = ["+", "-", "*", "/", "div", "mod", "**"];

/// Evaluates the arithmetic in a term under `s` (numbers only); other terms are returned
/// with `s` applied.
pub fn eval(t: &Term, s: &Substitution) -> Term {
    let t = s.apply(t);
    eval_ground(&t).unwrap_or(t)
}

fn eval_ground(t: &Term) -> Option<Term> {
    let f = t.functor()?;
    if !ARITH.contains(&f) || t.is_negated() {
        return None;
    }
    let args: Vec<f64> = t
        .args()
        .iter()
        .map(|a| eval_ground(a).unwrap_or_else(|| a.clone()).as_f64())
        .collect::<Option<Vec<_>>>()?;
    let v = match (f, args.as_slice()) {
        ("-", [x]) => -x,
        ("+", [x, y]) => x + y,
        ("-", [x, y]) => x - y,
        ("*", [x, y]) => x * y,
        ("/", [x, y]) if *y != 0.0 => x / y,
        ("div", [x, y]) if *y as i64 != 0 => ((*x as i64) / (*y as i64)) as f64,
        ("mod", [x, y]) if *y as i64 != 0 => ((*x as i64) % (*y as i64)) as f64,
        ("**", [x, y]) => x.powf(*y),
        _ => return None,
    };
    v.is_finite().then(|| Term::num(v))
}

impl Beliefs<'_> {
    /// The believed atom as a Jason literal with its source annotation.
    pub fn atom_term(&self, a: AtomId) -> Term {
        let (p, args) = self.atoms.decode(a);
        let source = if self.environment[p.0 as usize] {
            "percept"
        } else {
            "self"
        };
        Term::literal(
            self.atoms.pred_name(p),
            false,
            args.iter()
                .map(|o| Term::atom(self.universe.object_name(*o)))
                .collect(),
            vec![Term::structure("source", vec![Term::atom(source)])],
        )
    }

    /// The believed atoms that unify with `lit` under `s`, each with its answer.
    pub fn literal_answers(&self, lit: &Term, s: &Substitution) -> Vec<(AtomId, Substitution)> {
        let lit = s.apply(lit);
        // `~p` is never believed: no strong negations are ever added in this model.
        if lit.is_negated() {
            return Vec::new();
        }
        let Some(p) = lit.functor().and_then(|f| self.atoms.pred(f)) else {
            return Vec::new();
        };
        if self.atoms.pred_params(p).len() != lit.arity() {
            return Vec::new();
        }
        let mut out = Vec::new();
        for a in self.atoms.atoms_of(p) {
            if !self.state.beliefs.contains(a) {
                continue;
            }
            let mut s2 = s.clone();
            if unify(&lit, &self.atom_term(a), &mut s2) {
                out.push((a, s2));
            }
        }
        out
    }

    /// Every answer of `f` extending `s`, in order.
    pub fn answers(&self, f: &Formula, s: &Substitution) -> Vec<Substitution> {
        match f {
            Formula::True => vec![s.clone()],
            Formula::Literal(t) => self
                .literal_answers(t, s)
                .into_iter()
                .map(|(_, s)| s)
                .collect(),
            Formula::Not(g) => {
                if self.answers(g, s).is_empty() {
                    vec![s.clone()]
                } else {
                    Vec::new()
                }
            }
            Formula::And(a, b) => self
                .answers(a, s)
                .iter()
                .flat_map(|s1| self.answers(b, s1))
                .collect(),
            Formula::Or(a, b) => {
                let mut out = self.answers(a, s);
                out.extend(self.answers(b, s));
                out
            }
            Formula::Rel(op, a, b) => relation(*op, &eval(a, s), &eval(b, s), s)
                .into_iter()
                .collect(),
            Formula::Call(t) => self.call(t, s),
        }
    }

    /// Whether `f` has an answer.
    pub fn holds(&self, f: &Formula, s: &Substitution) -> bool {
        !self.answers(f, s).is_empty()
    }

    fn call(&self, t: &Term, s: &Substitution) -> Vec<Substitution> {
        let args = t.args();
        let unify_with = |x: &Term, y: Term| {
            let mut s2 = s.clone();
            unify(&s.apply(x), &y, &mut s2).then_some(s2)
        };
        match (t.functor().unwrap_or(""), args) {
            (".count", [q, n]) => {
                let k = self.answers(&Formula::Literal(q.clone()), s).len();
                unify_with(n, Term::int(k as i64)).into_iter().collect()
            }
            (".member", [x, l]) => match s.apply(l).list_elements() {
                Some((elems, _)) => elems.into_iter().filter_map(|e| unify_with(x, e)).collect(),
                None => Vec::new(),
            },
            (".length", [l, n]) => match s.apply(l).list_elements() {
                Some((elems, None)) => unify_with(n, Term::int(elems.len() as i64))
                    .into_iter()
                    .collect(),
                _ => Vec::new(),
            },
            (".findall", [x, q, l]) => {
                let items: Vec<Term> = self
                    .answers(&Formula::Literal(q.clone()), s)
                    .iter()
                    .map(|a| a.apply(x))
                    .collect();
                unify_with(l, Term::list(items)).into_iter().collect()
            }
            (".desire", [g]) => self.goals(g, s, true),
            (".intend", [g]) => self.goals(g, s, false),
            _ => Vec::new(),
        }
    }

    /// Answers of `.desire(g)` (goals in events or intentions) or `.intend(g)` (goals of
    /// intentions only).
    fn goals(&self, g: &Term, s: &Substitution, with_events: bool) -> Vec<Substitution> {
        let g = s.apply(g);
        let mut out = Vec::new();
        let mut consider = |lit: &Term| {
            let mut s2 = s.clone();
            if unify(&g, lit, &mut s2) && !out.contains(&s2) {
                out.push(s2);
            }
        };
        let frames = |i: &Intention| -> Vec<Term> {
            i.frames
                .iter()
                .filter(|f| {
                    f.trigger.op == TriggerOp::Add && f.trigger.kind == TriggerKind::Achieve
                })
                .map(|f| f.trigger.literal.clone())
                .collect()
        };
        let selected = self.selected.and_then(|e| e.intention.as_ref());
        for i in self.state.all_intentions().chain(selected) {
            frames(i).iter().for_each(&mut consider);
        }
        if with_events {
            for e in self.state.events.iter().chain(self.selected) {
                if e.trigger.op == TriggerOp::Add && e.trigger.kind == TriggerKind::Achieve {
                    consider(&e.trigger.literal);
                }
            }
        }
        out
    }
}

/// A relation between two evaluated terms.
pub fn relation(op: RelOp, a: &Term, b: &Term, s: &Substitution) -> Option<Substitution> {
    let ok = match op {
        RelOp::Unify => {
            let mut s2 = s.clone();
            return unify(a, b, &mut s2).then_some(s2);
        }
        RelOp::Eq => a == b,
        RelOp::Ne => a != b,
        RelOp::Univ => return None,
        RelOp::Lt | RelOp::Le | RelOp::Gt | RelOp::Ge => {
            // Jason compares numbers by value and other terms by its term order.
            let ord = match (a.as_f64(), b.as_f64()) {
                (Some(x), Some(y)) => x.partial_cmp(&y)?,
                _ => a.cmp(b),
            };
            match op {
                RelOp::Lt => ord.is_lt(),
                RelOp::Le => ord.is_le(),
                RelOp::Gt => ord.is_gt(),
                _ => ord.is_ge(),
            }
        }
    };
    ok.then(|| s.clone())
}
