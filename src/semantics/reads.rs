//! What the phases may read, worked out from the plans once: the beliefs deliberating on an
//! event or running an intention's next step may read (the compiled search memoizes each
//! phase on them), the atoms each rule's proof may read, the predicates whose belief order
//! can decide an answer, and whether every phase is local to its part of the state. No
//! method of `TransitionSystem.java` matches it: Jason reads its whole belief base.

use super::cycle::Semantics;
use super::query::eval;
use super::state::{CursorKind, Event, Intention};
use crate::model::atoms::AtomSet;
use crate::model::plans::{BodyStep, Formula, Step};
use crate::model::project::Project;
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::model::{unify, Substitution};
use std::collections::HashMap;

impl Semantics<'_> {
    /// The atoms each rule head's proof may read: those its bodies query, and those of
    /// the rules they call, to a fixed point (bindings are not followed).
    pub(super) fn compute_rule_reads(&self) -> HashMap<(String, usize), AtomSet> {
        let rules = &self.project.plans.rules;
        let key = |t: &Term| (t.functor().unwrap_or("").to_string(), t.arity());
        let mut reads: HashMap<(String, usize), AtomSet> = rules
            .iter()
            .map(|r| (key(&r.head), AtomSet::empty(self.project.atoms.len())))
            .collect();
        let empty = Substitution::new();
        loop {
            let mut changed = false;
            for r in rules {
                let mut out = AtomSet::empty(self.project.atoms.len());
                self.formula_reads_with(&r.body, &empty, &mut out, &reads);
                let k = key(&r.head);
                let mut now = reads[&k].clone();
                for a in out.iter() {
                    if !now.contains(a) {
                        now.insert(a);
                        changed = true;
                    }
                }
                reads.insert(k, now);
            }
            if !changed {
                return reads;
            }
        }
    }

    /// Whether one reasoning cycle's phases depend only on their own part of the state:
    /// deliberation on the event and the beliefs, acting on the intention and the beliefs.
    /// True unless some plan uses `.desire`, `.intend` (which read the other intentions),
    /// `.succeed_goal`, `.fail_goal`, `.drop_desire`, `.drop_intention` (which change
    /// them), changes the plan library (which deliberation reads), or is atomic (an atomic
    /// intention decides whether an event is selected and which intention runs). The
    /// compiled search ([`super::compiled::Compiled`]) relies on it.
    pub fn is_local(&self) -> bool {
        self.local
    }

    /// Every belief deliberating on `ev` may read: the atoms the contexts of its relevant
    /// plans may query (an over-approximation; see [`Semantics::literal_reads`]). The
    /// compiled search memoizes deliberation on the beliefs restricted to these atoms.
    pub(super) fn event_reads(&self, ev: &Event) -> AtomSet {
        let mut out = AtomSet::empty(self.project.atoms.len());
        for &pi in self.relevant_plans(&ev.trigger) {
            let plan = self.plan(pi);
            let mut u = Substitution::new();
            if unify(&plan.trigger.literal, &ev.trigger.literal, &mut u) {
                self.formula_reads(&plan.context, &u, &mut out);
            }
            // A new frame is normalized at the first step of its body, which reads nothing
            // unless the body is empty (then there is no cursor at all).
        }
        out
    }

    /// Every belief the act phase may read when `int` runs: its next step's queries and
    /// the atoms of its action (precondition, conditions and effects), or, at the end of
    /// a `while` body, the loop's condition.
    pub(super) fn intention_reads(&self, int: &Intention) -> AtomSet {
        let mut out = AtomSet::empty(self.project.atoms.len());
        let Some(f) = int.frames.last() else {
            return out;
        };
        let Some(c) = f.cursors.last() else {
            return out;
        };
        let blocks = &self.blocks[f.plan as usize];
        let Some(step) = blocks.blocks[c.block as usize].get(c.pos as usize) else {
            if let CursorKind::While { outer, at, base } = &c.kind {
                if let BodyStep::While(cond, _) = &blocks.blocks[*outer as usize][*at as usize].kind
                {
                    self.formula_reads(cond, base, &mut out);
                }
            }
            return out;
        };
        match &step.kind {
            BodyStep::Action(t) if self.is_emission(t) => {}
            BodyStep::Action(t) => {
                if let Some(ga) = eval(t, &f.subst)
                    .ok()
                    .and_then(|t| self.ground_action(&t).ok())
                {
                    let conds = std::iter::once(&ga.pre).chain(ga.effects.iter().map(|e| &e.when));
                    conds.flat_map(|c| c.atoms()).for_each(|a| out.insert(a));
                    for e in &ga.effects {
                        e.add.iter().chain(&e.del).for_each(|a| out.insert(*a));
                    }
                }
            }
            BodyStep::Internal(t) => {
                self.formula_reads(&Formula::Call(t.clone()), &f.subst, &mut out)
            }
            // An agent that waits is not compiled (see `step_is_local`); the condition is
            // what the step itself reads.
            BodyStep::Wait { condition, .. } => {
                if let Some(cond) = condition {
                    self.formula_reads(cond, &f.subst, &mut out)
                }
            }
            BodyStep::Test(cond) | BodyStep::While(cond, _) | BodyStep::For(cond, _) => {
                self.formula_reads(cond, &f.subst, &mut out)
            }
            BodyStep::If { branches, .. } => {
                for (cond, _) in branches {
                    self.formula_reads(cond, &f.subst, &mut out);
                }
            }
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                let lit = eval(t, &f.subst).unwrap_or_else(|_| f.subst.apply(t));
                if matches!(step.kind, BodyStep::DelAddBel(_)) {
                    // `-+b` removes any belief of the predicate.
                    let p = self.project.atoms.pred_of_literal(&lit);
                    for a in p.into_iter().flat_map(|p| self.project.atoms.atoms_of(p)) {
                        out.insert(a);
                    }
                } else {
                    self.literal_reads(&lit, &mut out);
                }
                if let Some(a) = self.ground_atom(&lit) {
                    out.insert(a);
                }
            }
            BodyStep::Achieve { .. } | BodyStep::Constraint(..) | BodyStep::Library { .. } => {}
        }
        out
    }

    /// The atoms a formula's answers may depend on under `s` (bindings made inside the
    /// formula are not followed: their variables count as unbound).
    fn formula_reads(&self, f: &Formula, s: &Substitution, out: &mut AtomSet) {
        self.formula_reads_with(f, s, out, &self.rule_reads)
    }

    fn formula_reads_with(
        &self,
        f: &Formula,
        s: &Substitution,
        out: &mut AtomSet,
        rules: &HashMap<(String, usize), AtomSet>,
    ) {
        let literal = |t: &Term, out: &mut AtomSet| {
            let t = s.apply(t);
            self.literal_reads(&t, out);
            let k = (t.functor().unwrap_or("").to_string(), t.arity());
            if let Some(r) = rules.get(&k) {
                r.iter().for_each(|a| out.insert(a));
            }
        };
        match f {
            Formula::True | Formula::Rel(..) => {}
            Formula::Literal(t) => literal(t, out),
            Formula::Not(g) => self.formula_reads_with(g, s, out, rules),
            Formula::And(a, b) | Formula::Or(a, b) => {
                self.formula_reads_with(a, s, out, rules);
                self.formula_reads_with(b, s, out, rules);
            }
            Formula::Call(t) => match (t.functor(), t.args()) {
                (Some(".count"), [q, _])
                | (Some(".findall"), [_, q, _])
                | (Some(".abolish"), [q]) => literal(q, out),
                _ => {}
            },
        }
    }

    /// The atoms [`Beliefs::literal_answers`](super::query::Beliefs::literal_answers) may
    /// look at for `lit`: those of its predicate whose arguments agree with its object
    /// arguments.
    fn literal_reads(&self, lit: &Term, out: &mut AtomSet) {
        let atoms = &self.project.atoms;
        let Some(p) = atoms.pred_of_literal(lit) else {
            return;
        };
        if atoms.pred_params(p).len() != lit.arity() {
            return;
        }
        let fixed: Vec<Option<ObjectId>> = lit
            .args()
            .iter()
            .map(|a| self.project.universe.object_of(a))
            .collect();
        let any_fixed = fixed.iter().any(Option::is_some);
        for a in atoms.atoms_of(p) {
            if any_fixed {
                let (_, args) = atoms.decode(a);
                if fixed
                    .iter()
                    .zip(&args)
                    .any(|(f, o)| f.is_some_and(|f| f != *o))
                {
                    continue;
                }
            }
            out.insert(a);
        }
    }
}

/// The predicates whose belief order can decide something: those some formula of a plan
/// or rule queries with a variable argument (outside `.count`), and those `-b` or `-+b`
/// removes with a variable argument (the first belief that unifies goes). A predicate
/// asked only with ground arguments has at most one answer, so its order never shows.
pub(super) fn ordered_predicates(p: &Project) -> Vec<bool> {
    let mut out = vec![false; p.atoms.pred_count()];
    let mark = |t: &Term, out: &mut Vec<bool>| {
        if t.is_ground() {
            return;
        }
        if let Some(q) = p.atoms.pred_of_literal(t) {
            out[q.0 as usize] = true;
        }
    };
    fn formula(f: &Formula, mark: &mut dyn FnMut(&Term)) {
        match f {
            Formula::True | Formula::Rel(..) => {}
            Formula::Literal(t) => mark(t),
            Formula::Not(g) => formula(g, mark),
            Formula::And(a, b) | Formula::Or(a, b) => {
                formula(a, mark);
                formula(b, mark);
            }
            Formula::Call(t) => match (t.functor(), t.args()) {
                (Some(".count"), _) => {}
                (_, args) => args.iter().for_each(|a| {
                    if a.is_literal() {
                        mark(a)
                    }
                }),
            },
        }
    }
    fn steps(body: &[Step], mark: &mut dyn FnMut(&Term)) {
        for st in body {
            match &st.kind {
                BodyStep::Test(f) => formula(f, mark),
                BodyStep::Internal(t) => formula(&Formula::Call(t.clone()), mark),
                BodyStep::DelBel(t) => mark(t),
                BodyStep::DelAddBel(t) => {
                    let vars = (0..t.arity())
                        .map(|i| Term::var(&format!("_V{i}")))
                        .collect();
                    mark(&Term::structure(t.functor().unwrap_or(""), vars));
                }
                BodyStep::If {
                    branches,
                    else_body,
                } => {
                    for (c, b) in branches {
                        formula(c, mark);
                        steps(b, mark);
                    }
                    steps(else_body, mark);
                }
                BodyStep::While(c, b) | BodyStep::For(c, b) => {
                    formula(c, mark);
                    steps(b, mark);
                }
                _ => {}
            }
        }
    }
    let mut m = |t: &Term| mark(t, &mut out);
    for plan in &p.plans.plans {
        formula(&plan.context, &mut m);
        steps(&plan.body, &mut m);
    }
    for r in &p.plans.rules {
        formula(&r.body, &mut m);
    }
    out
}

/// Internal actions that read or change intentions other than the one running them.
const GLOBAL_ACTIONS: [&str; 7] = [
    ".desire",
    ".intend",
    ".succeed_goal",
    ".fail_goal",
    ".drop_desire",
    ".drop_intention",
    // Not global, but a step with several outcomes, which the compiled act phase (one
    // outcome per intention and beliefs) does not hold.
    ".random",
];

pub(super) fn formula_is_local(f: &Formula) -> bool {
    match f {
        Formula::True | Formula::Literal(_) | Formula::Rel(..) => true,
        Formula::Not(g) => formula_is_local(g),
        Formula::And(a, b) | Formula::Or(a, b) => formula_is_local(a) && formula_is_local(b),
        Formula::Call(t) => !t.functor().is_some_and(|f| GLOBAL_ACTIONS.contains(&f)),
    }
}

pub(super) fn step_is_local(s: &Step) -> bool {
    match &s.kind {
        // A waiting intention is woken by events any other intention posts.
        BodyStep::Wait { .. } => false,
        BodyStep::Internal(t) => !t.functor().is_some_and(|f| GLOBAL_ACTIONS.contains(&f)),
        BodyStep::Test(f) => formula_is_local(f),
        BodyStep::If {
            branches,
            else_body,
        } => {
            branches
                .iter()
                .all(|(c, b)| formula_is_local(c) && b.iter().all(step_is_local))
                && else_body.iter().all(step_is_local)
        }
        BodyStep::While(c, b) | BodyStep::For(c, b) => {
            formula_is_local(c) && b.iter().all(step_is_local)
        }
        BodyStep::Action(_)
        | BodyStep::Achieve { .. }
        | BodyStep::AddBel(_)
        | BodyStep::DelBel(_)
        | BodyStep::DelAddBel(_)
        | BodyStep::Constraint(..) => true,
        // It changes what deliberation reads, the library: `Semantics::new` makes any
        // library with such a step not local.
        BodyStep::Library { .. } => true,
    }
}
