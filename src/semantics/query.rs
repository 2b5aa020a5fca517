//! Answering formulas against the beliefs: Jason's logical consequence, as a list of
//! answers (substitutions), in a fixed order.
//!
//! A literal's answers are the believed atoms that unify with it in Jason's belief-base
//! order (`DefaultBeliefBase`: a predicate's beliefs newest first, kept in
//! [`State::order`] for the predicates where it can show, atom order elsewhere), then the
//! answers of the rules for it, in source order (`Literal.logicalConsequence`).
//! Environment atoms carry `source(percept)` and mental notes `source(self)`, as in Jason,
//! so `p[source(percept)]` matches percepts only.

use super::state::State;
use crate::model::arith::{self, ArithError, OPERATORS};
use crate::model::atoms::{AtomId, AtomTable};
use crate::model::internal;
use crate::model::plans::{Formula, Rule};
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
    /// The goals of the intention whose step asks, out of the state while it runs: Jason's
    /// `.intend` and `.desire` see it too (`Circumstance.getAllIntentions`, `C.SI`).
    pub running: &'a [Term],
    /// The rules of the belief base.
    pub rules: &'a [Rule],
    /// How deep in rule calls the query being answered is (rules' variables are renamed
    /// apart by depth).
    pub depth: std::cell::Cell<u32>,
    /// The agent's name, for `.my_name`.
    pub agent_name: &'a str,
    /// Every agent's name, by index (for the sources of told beliefs).
    pub agents: &'a [String],
    /// Per predicate: whether answers follow [`State::order`] (else atom order).
    pub ordered: &'a [bool],
}

/// Why a query or a step has an outcome bdi-check does not model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Trouble {
    /// Arithmetic with no value.
    Arith(ArithError),
    /// Rules calling each other deeper than [`MAX_RULE_DEPTH`].
    RuleDepth,
}

impl From<ArithError> for Trouble {
    fn from(e: ArithError) -> Trouble {
        Trouble::Arith(e)
    }
}

thread_local! {
    /// The first trouble met by a query since [`take_trouble`] (queries answer with
    /// substitutions only; the phase that asked turns this into a refusal).
    static TROUBLE: std::cell::Cell<Option<Trouble>> = const { std::cell::Cell::new(None) };
}

/// Notes trouble met while answering a query or evaluating a step.
pub(super) fn note_trouble(e: impl Into<Trouble>) {
    let e = e.into();
    TROUBLE.with(|t| {
        if t.get().is_none() {
            t.set(Some(e));
        }
    });
}

/// The trouble met since the last call, if any (and forgets it).
pub(super) fn take_trouble() -> Option<Trouble> {
    TROUBLE.with(|t| t.take())
}

/// Why a run with this trouble leaves the model, as Jason 3 behaves there.
pub(super) fn trouble_reason(e: Trouble) -> String {
    match e {
        Trouble::Arith(ArithError::DivisionByZero) => "an integer division by zero: Jason 3 throws ArithmeticException out of the reasoning cycle here, logs \"*** ERROR in the transition system\" and creates a new circumstance, dropping every intention and event (TransitionSystem.act and deliberate, C.create()); bdi-check does not model that".into(),
        Trouble::Arith(ArithError::NotFinite) => "the result is not a finite number: Jason goes on with Infinity or NaN (Java's double arithmetic), which bdi-check does not model".into(),
        Trouble::RuleDepth => format!("rules call each other more than {MAX_RULE_DEPTH} deep: Jason recurses on its Java stack (Rule.logicalConsequence) until it overflows or answers, which bdi-check does not model"),
    }
}

/// Variables of a rule called at depth `d` have generation `RULE_GENERATION + d`.
const RULE_GENERATION: u32 = 2_000_000;

/// Deeper rule calls than this are refused ([`Trouble::RuleDepth`]).
const MAX_RULE_DEPTH: u32 = 256;

/// Applies `s` to `t` and evaluates every arithmetic subterm whose operands are numbers,
/// as Jason's `capply` does (`ArithExpr.capply`); an operator with an unbound operand
/// stays a structure. Fails when some arithmetic has no value ([`ArithError`]).
pub fn eval(t: &Term, s: &Substitution) -> Result<Term, ArithError> {
    eval_ground(&s.apply(t))
}

fn eval_ground(t: &Term) -> Result<Term, ArithError> {
    match t {
        Term::Struct(_) if !has_arith(t) => Ok(t.clone()),
        Term::Struct(st) => {
            let args = st
                .args()
                .iter()
                .map(eval_ground)
                .collect::<Result<Vec<_>, _>>()?;
            let f = t.functor().unwrap_or("");
            if OPERATORS.contains(&f) && !st.negated() && st.annots().is_empty() {
                if let Some(nums) = args.iter().map(Term::as_f64).collect::<Option<Vec<_>>>() {
                    if let Some(v) = arith::apply(f, &nums) {
                        return v.map(Term::num);
                    }
                }
            }
            // Arithmetic functions (`math.abs(X)`), once their arguments are ground.
            if args.iter().all(Term::is_ground) {
                if let Some(v) = internal::function(f, &args) {
                    return v.map_err(|_| ArithError::NotFinite);
                }
            }
            Ok(Term::literal(
                st.functor(),
                st.negated(),
                args,
                st.annots().to_vec(),
            ))
        }
        Term::Cons(c) if has_arith(t) => {
            Ok(Term::cons(eval_ground(c.head())?, eval_ground(c.tail())?))
        }
        _ => Ok(t.clone()),
    }
}

/// Whether a term holds an arithmetic operator structure anywhere in its arguments.
fn has_arith(t: &Term) -> bool {
    match t {
        Term::Struct(st) => {
            OPERATORS.contains(&st.functor())
                || internal::FUNCTIONS.iter().any(|(f, _)| *f == st.functor())
                || st.args().iter().any(has_arith)
        }
        Term::Cons(c) => has_arith(c.head()) || has_arith(c.tail()),
        _ => false,
    }
}

impl Beliefs<'_> {
    /// The believed atom as a Jason literal with its source annotation.
    pub fn atom_term(&self, a: AtomId) -> Term {
        let (p, args) = self.atoms.decode(a);
        let source = |who: &str| Term::structure("source", vec![Term::atom(who)]);
        let sources = match self.state.told(a) {
            // Told by others (and perhaps its own too): Jason keeps every source.
            Some(t) => {
                let mut v: Vec<Term> = (0..64)
                    .filter(|k| t.from >> k & 1 == 1)
                    .filter_map(|k| self.agents.get(k))
                    .map(|n| source(n))
                    .collect();
                if t.own {
                    v.push(source("self"));
                }
                v.sort();
                v
            }
            None if self.environment[p.0 as usize] => vec![source("percept")],
            None => vec![source("self")],
        };
        let (name, negated) = self.atoms.pred_literal(p);
        Term::literal(
            name,
            negated,
            args.iter().map(|o| self.universe.object_term(*o)).collect(),
            sources,
        )
    }

    /// The believed atoms that unify with `lit` under `s`, each with its answer.
    pub fn literal_answers(&self, lit: &Term, s: &Substitution) -> Vec<(AtomId, Substitution)> {
        let lit = s.apply(lit);
        // `~p` is a predicate of its own (Jason: a different predicate indicator).
        let Some(p) = self.atoms.pred_of_literal(&lit) else {
            return Vec::new();
        };
        if self.atoms.pred_params(p).len() != lit.arity() {
            return Vec::new();
        }
        let mut out = Vec::new();
        // Jason's belief-base order: newest first, where the order can show.
        let ordered: Vec<AtomId>;
        let candidates: &mut dyn Iterator<Item = AtomId> = if self.ordered[p.0 as usize] {
            ordered = self
                .state
                .order
                .iter()
                .copied()
                .filter(|a| self.atoms.pred_of(*a) == p)
                .collect();
            &mut ordered.iter().copied()
        } else {
            &mut self.atoms.atoms_of(p)
        };
        for a in candidates {
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

    /// The answers of a literal from the rules whose head it unifies with, in source order
    /// (Jason's `Literal.logicalConsequence` on a `Rule`: its variables renamed apart,
    /// the head unified, the body proved), each kept in the caller's variables.
    fn rule_answers(&self, lit: &Term, s: &Substitution) -> Vec<Substitution> {
        let lit = s.apply(lit);
        let (f, n, neg) = (lit.functor(), lit.arity(), lit.is_negated());
        let depth = self.depth.get() + 1;
        if depth > MAX_RULE_DEPTH {
            note_trouble(Trouble::RuleDepth);
            return Vec::new();
        }
        let gen = RULE_GENERATION + depth;
        let mut out = Vec::new();
        for r in self.rules {
            if r.head.functor() != f || r.head.arity() != n || r.head.is_negated() != neg {
                continue;
            }
            let rename = |t: &Term| t.map_vars(&mut |v| Term::from(v.with_generation(gen)));
            let head = rename(&r.head);
            let mut u = s.clone();
            // The rule's annotations (none, for rules of the source) take the query's.
            if !unify(&lit.without_annots(), &head, &mut u) {
                continue;
            }
            let body = rename_formula(&r.body, &rename);
            self.depth.set(depth);
            let answers = self.answers(&body, &u);
            self.depth.set(depth - 1);
            for a in answers {
                // Keep the answer in the caller's variables: drop the rule's own.
                let mut kept = Substitution::new();
                for (v, t) in a.iter() {
                    if v.generation() < gen {
                        kept.bind(v.clone(), a.apply(t));
                    }
                }
                out.push(kept);
            }
        }
        out
    }

    /// Every answer of `f` extending `s`, in order.
    pub fn answers(&self, f: &Formula, s: &Substitution) -> Vec<Substitution> {
        match f {
            Formula::True => vec![s.clone()],
            Formula::Literal(t) => {
                let mut out: Vec<Substitution> = self
                    .literal_answers(t, s)
                    .into_iter()
                    .map(|(_, s)| s)
                    .collect();
                if !self.rules.is_empty() {
                    out.extend(self.rule_answers(t, s));
                }
                out
            }
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
            Formula::Rel(op, a, b) => match (eval(a, s), eval(b, s)) {
                (Ok(x), Ok(y)) => relation(*op, &x, &y, s).into_iter().collect(),
                (Err(e), _) | (_, Err(e)) => {
                    note_trouble(e);
                    Vec::new()
                }
            },
            Formula::Call(t) => self.call(t, s),
        }
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
            (".findall", [x, q, l]) => {
                let items: Vec<Term> = self
                    .answers(&Formula::Literal(q.clone()), s)
                    .iter()
                    .map(|a| a.apply(x))
                    .collect();
                unify_with(l, Term::list(items)).into_iter().collect()
            }
            // Jason's `kqml::bel_no_source_self` (kqmlPlans.asl): a belief that unifies,
            // with its annotations but `source(self)`.
            (".kqml_answer", [c, a]) => self
                .kqml_answers(c, s)
                .into_iter()
                .filter_map(|(mut s2, ans)| unify(&s2.apply(a), &ans, &mut s2).then_some(s2))
                .collect(),
            // `.findall` of those answers.
            (".kqml_answers", [c, l]) => {
                let items = self
                    .kqml_answers(c, s)
                    .into_iter()
                    .map(|(s2, ans)| s2.apply(&ans))
                    .collect();
                unify_with(l, Term::list(items)).into_iter().collect()
            }
            (".desire", [g]) => self.goals(g, s, true),
            (".intend", [g]) => self.goals(g, s, false),
            (".fail", []) => Vec::new(),
            (".my_name", [n]) => unify_with(n, Term::atom(self.agent_name))
                .into_iter()
                .collect(),
            (name, args) => {
                // Jason evaluates the arguments first (`prepareArguments`).
                let args = match args
                    .iter()
                    .map(|a| eval(a, s))
                    .collect::<Result<Vec<_>, _>>()
                {
                    Ok(args) => args,
                    Err(e) => {
                        note_trouble(e);
                        return Vec::new();
                    }
                };
                internal::call(name, &args, s).unwrap_or_default()
            }
        }
    }

    /// The answers of an `askOne` or `askAll` of `c`: each believed literal that unifies,
    /// in belief-base order, with its annotations but `source(self)`, then what the rules
    /// prove (`c` as it is then: a rule's conclusion has no annotation), each with the
    /// bindings of `c`.
    fn kqml_answers(&self, c: &Term, s: &Substitution) -> Vec<(Substitution, Term)> {
        let own = Term::structure("source", vec![Term::atom("self")]);
        let mut out: Vec<(Substitution, Term)> = self
            .literal_answers(c, s)
            .into_iter()
            .map(|(a, s2)| {
                let b = self.atom_term(a);
                let annots: Vec<Term> = b.annots().iter().filter(|x| **x != own).cloned().collect();
                (s2, b.without_annots().add_annots(annots).unwrap_or(b))
            })
            .collect();
        if !self.rules.is_empty() {
            for s2 in self.rule_answers(c, s) {
                let ans = s2.apply(c);
                out.push((s2, ans));
            }
        }
        out
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
        let selected = self.selected.and_then(|e| e.intention.as_ref());
        for i in self.state.all_intentions().chain(selected) {
            i.goals().for_each(&mut consider);
        }
        self.running.iter().for_each(&mut consider);
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

/// A formula with `rename` applied to every term in it.
fn rename_formula(f: &Formula, rename: &impl Fn(&Term) -> Term) -> Formula {
    match f {
        Formula::True => Formula::True,
        Formula::Literal(t) => Formula::Literal(rename(t)),
        Formula::Not(g) => Formula::Not(Box::new(rename_formula(g, rename))),
        Formula::And(a, b) => Formula::And(
            Box::new(rename_formula(a, rename)),
            Box::new(rename_formula(b, rename)),
        ),
        Formula::Or(a, b) => Formula::Or(
            Box::new(rename_formula(a, rename)),
            Box::new(rename_formula(b, rename)),
        ),
        Formula::Rel(op, a, b) => Formula::Rel(*op, rename(a), rename(b)),
        Formula::Call(t) => Formula::Call(rename(t)),
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
