//! Algorithm 1 (explanation demand): when an action surprises a user.
//!
//! A user's expectations are a relation `N` of expected successors: pairs `(before, after)`
//! of observations. The *observed sequence* of a run is what the user sees: the requests
//! they make (`!g`, when they arrive) and the environment actions the robot executes, in
//! order. At each executed action `o_j` an explanation is due exactly when the pair
//! `(o_{j-1}, o_j)` matches no pair of the current `N`; the pair is then added to `N`, so the
//! user is not surprised by it again. Requests never need an explanation themselves
//! ([`ExpectedSuccessors::observe`], [`demand_over`]).
//!
//! Pairs are patterns: variables match any object, and a variable shared by the two sides
//! must match the same object on both. `N` starts from the user's patterns (the manifest's
//! `expected`) and grows by *ground* pairs: what the user saw is what they learn, so
//! `(!storeCup(cup1), navigateTo(dishwasher))` once seen does not make
//! `(!storeCup(cup2), navigateTo(dishwasher))` expected.
//!
//! The first observation of a run has no predecessor; its pair is `(start, o_0)`
//! (`prev == None`), which no pattern written in a manifest matches, so an action that opens
//! a run (an initial goal's, before any request) is explained the first time.
//!
//! [`demand_on_adoption`] is the algorithm as the paper wrote it, for comparison.

use crate::model::{match_pattern, Converter, Substitution, Term};
use crate::syntax::ast::{ExprKind, Step, StepKind};
use crate::syntax::parser::parse_step;
use crate::syntax::FileId;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// One element of an observed sequence: a user's request or an executed environment action.
///
/// Ordered (requests before actions, then by Jason's term order) so that sets of pairs are
/// deterministic.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Observation {
    /// The user's request of a goal, `!g` (the term is `g`).
    Request(Term),
    /// An environment action the robot executed.
    Action(Term),
}

impl Observation {
    /// The goal or action term.
    pub fn term(&self) -> &Term {
        match self {
            Observation::Request(t) | Observation::Action(t) => t,
        }
    }

    /// Whether this is an action (the only observations that may need an explanation).
    pub fn is_action(&self) -> bool {
        matches!(self, Observation::Action(_))
    }

    /// The observation a body formula denotes: `!g` is a request, `a(x)` an action (the
    /// shapes the manifest accepts in `expected` and as phrase patterns). `conv` numbers
    /// anonymous variables: use one converter for the two sides of a pair so that their
    /// `_`s stay distinct.
    pub fn from_step(step: &Step, conv: &mut Converter) -> Result<Observation, String> {
        let (e, request) = match &step.kind {
            StepKind::Achieve(e) => (e, true),
            StepKind::Action(e) => (e, false),
            _ => return Err("expected an action `a(x)` or a request `!g(x)`".into()),
        };
        let ExprKind::Literal(l) = &e.kind else {
            return Err("expected a literal, not a variable".into());
        };
        if l.is_internal_action() {
            return Err("an internal action is not observed by the user".into());
        }
        let t = conv.literal(l).map_err(|e| e.message)?;
        Ok(if request {
            Observation::Request(t)
        } else {
            Observation::Action(t)
        })
    }

    /// Parses `!g(x)` or `a(x)` (see [`Observation::from_step`]).
    pub fn parse(text: &str) -> Result<Observation, String> {
        Observation::from_step(&parse_one(text)?, &mut Converter::new())
    }
}

fn parse_one(text: &str) -> Result<Step, String> {
    parse_step(FileId(0), text).map_err(|ds| {
        let msgs: Vec<String> = ds.into_iter().map(|d| d.message).collect();
        format!("`{text}`: {}", msgs.join("; "))
    })
}

impl fmt::Display for Observation {
    /// `!g` for a request, the action as Jason prints it otherwise.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Observation::Request(g) => write!(f, "!{g}"),
            Observation::Action(a) => write!(f, "{a}"),
        }
    }
}

/// A pair `(prev, next)` of `N`: `next` is expected right after `prev`. `prev == None` is the
/// start of the run.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Pair {
    /// The earlier observation, or `None` for the start of the run.
    pub prev: Option<Observation>,
    /// The observation that follows it.
    pub next: Observation,
}

impl Pair {
    /// The pair `(prev, next)`.
    pub fn new(prev: Observation, next: Observation) -> Pair {
        Pair {
            prev: Some(prev),
            next,
        }
    }

    /// The pattern pair of two body formulas, converted with one [`Converter`] so that named
    /// variables are shared between the sides and each `_` is its own variable.
    pub fn from_steps(prev: &Step, next: &Step) -> Result<Pair, String> {
        let mut conv = Converter::new();
        let prev = Observation::from_step(prev, &mut conv)?;
        let next = Observation::from_step(next, &mut conv)?;
        Ok(Pair::new(prev, next))
    }

    /// Parses a pattern pair written as in the manifest: `("!storeCup(C)", "pickUp(C)")`.
    pub fn parse(prev: &str, next: &str) -> Result<Pair, String> {
        Pair::from_steps(&parse_one(prev)?, &parse_one(next)?)
    }

    /// Whether this pattern pair matches the observed pair `(prev, next)`: both sides have
    /// the same kind (request or action), and one substitution of the pattern's variables
    /// turns the two sides into the observations together (so shared variables agree). The
    /// observations' own variables, if any, are constants here.
    pub fn matches(&self, prev: Option<&Observation>, next: &Observation) -> bool {
        // Most patterns are about other steps: told apart by name and arity, no unifier.
        if !may_match(&self.next, next) {
            return false;
        }
        let mut s = Substitution::new();
        let first = match (&self.prev, prev) {
            (None, None) => true,
            (Some(p), Some(o)) => match_observation(p, o, &mut s),
            _ => false,
        };
        first && match_observation(&self.next, next, &mut s)
    }
}

/// Whether `pattern` may match `seen`: the same kind and, when the pattern is a literal,
/// the same functor and arity (a necessary condition of [`match_observation`]).
fn may_match(pattern: &Observation, seen: &Observation) -> bool {
    let (p, o) = match (pattern, seen) {
        (Observation::Request(p), Observation::Request(o))
        | (Observation::Action(p), Observation::Action(o)) => (p, o),
        _ => return false,
    };
    match p.functor() {
        Some(f) => o.functor() == Some(f) && o.arity() == p.arity(),
        None => true,
    }
}

fn match_observation(pattern: &Observation, seen: &Observation, s: &mut Substitution) -> bool {
    match (pattern, seen) {
        (Observation::Request(p), Observation::Request(o))
        | (Observation::Action(p), Observation::Action(o)) => match_pattern(p, o, s),
        _ => false,
    }
}

impl fmt::Display for Pair {
    /// `(prev, next)`, with `start` for the start of the run.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.prev {
            Some(p) => write!(f, "({p}, {})", self.next),
            None => write!(f, "(start, {})", self.next),
        }
    }
}

/// A user's expected-successor relation `N`: the initial pattern pairs and the ground pairs
/// learned since.
///
/// Cheap to clone (the patterns are shared; the learned pairs are a small sorted vector of
/// shared terms) and `Eq + Hash + Ord`, so a model checker can keep it in its states: two
/// relations are equal when they have the same patterns and have learned the same pairs.
#[derive(Clone, Debug, Eq, PartialOrd, Ord)]
pub struct ExpectedSuccessors {
    initial: Arc<[Pair]>,
    /// Sorted, without duplicates; none of them matches a pattern of `initial` or another.
    /// Shared: a search copies `N` at every step and changes it at few.
    learned: Arc<[Pair]>,
    /// The hash of `learned` (the sum of its pairs'), made as it grows.
    learned_hash: u64,
}

impl PartialEq for ExpectedSuccessors {
    fn eq(&self, o: &ExpectedSuccessors) -> bool {
        // The pairs are shared (a user's patterns, and sets grown alike: [`grown`]), so
        // most equal relations have the same pairs by address: comparing them pair by pair
        // was most of interning a user's view.
        let same = |a: &Arc<[Pair]>, b: &Arc<[Pair]>| Arc::ptr_eq(a, b) || a[..] == b[..];
        self.learned_hash == o.learned_hash
            && same(&self.learned, &o.learned)
            && same(&self.initial, &o.initial)
    }
}

impl Hash for ExpectedSuccessors {
    fn hash<H: Hasher>(&self, h: &mut H) {
        // The learned pairs only, hashed when they grow: `initial` is the manifest's, one for
        // every view of a user, and hashing it at every step of a search cost more than the
        // rest.
        h.write_u64(self.learned_hash);
    }
}

impl Default for ExpectedSuccessors {
    /// The empty relation: every action is surprising the first time.
    fn default() -> ExpectedSuccessors {
        ExpectedSuccessors::new([])
    }
}

impl ExpectedSuccessors {
    /// `N_0`: the user's pattern pairs, in the manifest's order.
    pub fn new(initial: impl IntoIterator<Item = Pair>) -> ExpectedSuccessors {
        ExpectedSuccessors {
            initial: initial.into_iter().collect(),
            learned: Arc::new([]),
            learned_hash: 0,
        }
    }

    /// The initial pattern pairs.
    pub fn initial(&self) -> &[Pair] {
        &self.initial
    }

    /// The pairs learned so far, sorted.
    pub fn learned(&self) -> &[Pair] {
        &self.learned
    }

    /// Whether some pair of `N` matches `(prev, next)`: an initial pattern, or a learned
    /// pair equal to it (learned pairs are observations, compared as they are).
    pub fn is_expected(&self, prev: Option<&Observation>, next: &Observation) -> bool {
        self.initial.iter().any(|p| p.matches(prev, next))
            || self
                .learned
                .binary_search_by(|p| cmp_pair(p, prev, next))
                .is_ok()
    }

    /// Adds `(prev, next)` to `N` unless it is already expected; returns whether it was
    /// added (whether it was novel).
    pub fn learn(&mut self, prev: Option<&Observation>, next: &Observation) -> bool {
        if self.initial.iter().any(|p| p.matches(prev, next)) {
            return false;
        }
        match self.learned.binary_search_by(|p| cmp_pair(p, prev, next)) {
            Ok(_) => false,
            Err(at) => {
                let pair = Pair {
                    prev: prev.cloned(),
                    next: next.clone(),
                };
                // The hash of a set: the sum of its pairs' hashes, so that adding a pair
                // costs one hash, not one per pair learned so far.
                let hash = crate::semantics::state::part_hash(&pair);
                self.learned_hash = self.learned_hash.wrapping_add(hash);
                self.learned = grown(&self.learned, at, pair, hash);
                true
            }
        }
    }

    /// Algorithm 1 at one observation `next`, which follows `prev` (`None` at the start of
    /// the run): returns whether an explanation is due, and if so learns the pair. A request
    /// is never due and teaches nothing, so `N` grows by exactly the pairs that were
    /// explained.
    pub fn observe(&mut self, prev: Option<&Observation>, next: &Observation) -> bool {
        next.is_action() && self.learn(prev, next)
    }
}

/// How many grown sets each thread keeps at hand ([`grown`]; a power of two).
const GROWN: usize = 1 << 12;

/// A set of learned pairs, a pair it grew by, and the set it grew into.
type Growth = (Arc<[Pair]>, Pair, Arc<[Pair]>);

thread_local! {
    /// The sets learned pairs grew into lately, by the set before (by address: the entry
    /// keeps it alive, so no other set has it) and the pair. A user's search grows the same
    /// set by the same pair from many states, and each growth copied the set; one shared
    /// set for equal ones also makes comparing two views' `N` (interning them) a pointer
    /// comparison instead of one of every pair (4-cup kitchen: `learn` and interning were
    /// a fifth of the users' instructions).
    static GROWN_SETS: std::cell::RefCell<Vec<Option<Growth>>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// `learned` with `pair` (of hash `hash`) inserted at `at`, shared with the last growth of
/// the same set by the same pair on this thread.
fn grown(learned: &Arc<[Pair]>, at: usize, pair: Pair, hash: u64) -> Arc<[Pair]> {
    let address = Arc::as_ptr(learned) as *const Pair as usize as u64;
    let slot = crate::semantics::compiled::mix(address ^ hash) as usize & (GROWN - 1);
    GROWN_SETS.with_borrow_mut(|sets| {
        if sets.is_empty() {
            sets.resize(GROWN, None);
        }
        if let Some((before, by, after)) = &sets[slot] {
            if Arc::ptr_eq(before, learned) && *by == pair {
                return after.clone();
            }
        }
        let after: Arc<[Pair]> = (learned[..at].iter().cloned())
            .chain(std::iter::once(pair.clone()))
            .chain(learned[at..].iter().cloned())
            .collect();
        sets[slot] = Some((learned.clone(), pair, after.clone()));
        after
    })
}

/// Compares a stored pair with `(prev, next)` without building a pair (no clones).
fn cmp_pair(p: &Pair, prev: Option<&Observation>, next: &Observation) -> std::cmp::Ordering {
    p.prev.as_ref().cmp(&prev).then_with(|| p.next.cmp(next))
}

/// Algorithm 1 over a whole observed sequence: element `j` of the result says whether
/// `seq[j]` needs an explanation (always `false` for a request). `n` learns every novel pair
/// on the way, as it would during the run.
pub fn demand_over(n: &mut ExpectedSuccessors, seq: &[Observation]) -> Vec<bool> {
    let mut prev = None;
    seq.iter()
        .map(|o| {
            let due = n.observe(prev, o);
            prev = Some(o);
            due
        })
        .collect()
}

/// Algorithm 1 *as the paper writes it*: when a plan is adopted, walk the consecutive action
/// pairs `(a_t, a_{t+1})` of its body and mark `a_{t+1}` when the pair is not in `N`, adding
/// it. Element `t` of the result says whether `body[t]` is marked; `body[0]` never is (it
/// has no predecessor in the body).
///
/// `body` is the environment actions of the adopted plan's body in order, instantiated with
/// the bindings known at adoption (subgoals and other steps left out, so the actions around
/// a subgoal form a pair). This differs from [`demand_over`], which follows what the run
/// really shows the user: the paper's version looks ahead at one body in isolation, so it
/// ignores the user's requests, the actions of subgoals executed between two steps, the
/// interleaving of other intentions, the first action's predecessor, and whether the body
/// runs to its end at all (a failed action leaves later pairs marked but never executed).
pub fn demand_on_adoption(n: &mut ExpectedSuccessors, body: &[Term]) -> Vec<bool> {
    let mut marks = vec![false; body.len()];
    for t in 1..body.len() {
        let prev = Observation::Action(body[t - 1].clone());
        let next = Observation::Action(body[t].clone());
        marks[t] = n.learn(Some(&prev), &next);
    }
    marks
}
