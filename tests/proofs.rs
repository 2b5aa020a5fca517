//! The twins of the Kani harnesses in `proofs/`: each kernel's property (the same function
//! the harness calls) driven by an exhaustive enumeration of every input up to a bound, and
//! by proptest (fixed seed) beyond it; then each property given a deliberately broken kernel,
//! to show that it fails.
//!
//! The property modules name the crate as `crate::model`, `crate::explain`, ...: the
//! re-exports below make those paths mean `bdi_check`'s modules here.

use bdi_check::{check, explain, model, semantics};

#[path = "../proofs/mod.rs"]
mod proofs;

use explain::{ExpectedSuccessors, FrameSnapshot, Observation};
use model::atoms::AtomSet;
use model::cond::Cond;
use model::ground::GroundAction;
use model::{unifier, Substitution, Term};
use proofs::{cond, content, demand, effects, store, symmetry, unify};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use semantics::State;
use std::collections::{HashSet, VecDeque};

/// A fixed seed keeps runs reproducible; `PROPTEST_RNG_SEED` and `PROPTEST_CASES` still
/// override it.
fn config(cases: u32) -> Config {
    let mut c = Config::default();
    if matches!(c.rng_seed, RngSeed::Random) {
        c.rng_seed = RngSeed::Fixed(0x9e0f5);
    }
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    c.failure_persistence = None;
    c
}

/// Runs `check` on every input; panics with the first violation; returns the outcomes.
fn exhaustively<I, S>(inputs: &[I], check: impl Fn(&I) -> Result<S, String>) -> Vec<S> {
    inputs
        .iter()
        .map(|i| check(i).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

/// The first violation `check` finds among `inputs`: what a broken kernel must produce.
fn first_violation<I, S>(inputs: &[I], check: impl Fn(&I) -> Result<S, String>) -> String {
    inputs
        .iter()
        .find_map(|i| check(i).err())
        .expect("the broken kernel must violate the property on some input")
}

// ----- unification ---------------------------------------------------------------------------

fn thetas() -> Vec<unify::Theta> {
    unify::all_thetas(&unify::all_terms(2, true))
}

/// Pairs of a term of depth ≤ 2 and a term of depth ≤ 1, both ways round.
fn unify_pairs() -> Vec<(unify::SmallTerm, unify::SmallTerm)> {
    let (deep, shallow) = (unify::all_terms(2, false), unify::all_terms(1, false));
    let mut out = Vec::new();
    for a in &deep {
        for b in &shallow {
            out.push((*a, *b));
            out.push((*b, *a));
        }
    }
    out
}

#[test]
fn unification_exhaustive() {
    let thetas = thetas();
    assert_eq!(unify::all_terms(2, false).len(), 604);
    assert_eq!(thetas.len(), 74 * 74);
    let pairs = unify_pairs();
    assert!(pairs.iter().any(|(a, _)| a.depth() == 2));
    let verdicts = exhaustively(&pairs, |(a, b)| {
        unify::unify_is_sound_and_most_general(a, b, unifier, thetas.iter().copied())
    });
    // Not vacuous: both answers occur.
    assert!(verdicts.contains(&unify::Verdict::Unified));
    assert!(verdicts.contains(&unify::Verdict::NotUnifiable));
}

fn unify_mutant_fails(mutant: impl Fn(&Term, &Term) -> Option<Substitution>) -> String {
    let thetas = thetas();
    first_violation(&unify_pairs(), |(a, b)| {
        unify::unify_is_sound_and_most_general(a, b, &mutant, thetas.iter().copied())
    })
}

#[test]
fn unification_twin_fails_on_broken_kernels() {
    // A unifier that forgets one of its bindings.
    let e = unify_mutant_fails(|a, b| {
        unifier(a, b).map(|s| {
            let mut t = Substitution::new();
            for (v, x) in s.iter().skip(1) {
                t.bind(v.clone(), x.clone());
            }
            t
        })
    });
    assert!(e.contains("gives"), "{e}");
    // A functor clash that "unifies".
    let e = unify_mutant_fails(|a, b| unifier(a, b).or_else(|| Some(Substitution::new())));
    assert!(e.contains("gives"), "{e}");
    // Incomplete: gives up when both terms have variables.
    let e = unify_mutant_fails(|a, b| {
        if a.is_ground() || b.is_ground() {
            unifier(a, b)
        } else {
            None
        }
    });
    assert!(e.contains("no unifier returned"), "{e}");
    // A unifier, but not a most general one: binds a variable it could leave free.
    let e = unify_mutant_fails(|a, b| {
        unifier(a, b).map(|mut s| {
            if let Some(v) = a
                .vars()
                .into_iter()
                .chain(b.vars())
                .find(|v| s.get(v).is_none())
            {
                s.bind(v, Term::atom("a"));
            }
            s
        })
    });
    assert!(e.contains("not most general"), "{e}");
}

// ----- formula evaluation --------------------------------------------------------------------

#[test]
fn evaluation_exhaustive() {
    let conds = cond::all_conds();
    assert_eq!(conds.len(), 197 + 252 + 2 * 252 * 252);
    assert!(conds.iter().any(|f| f.has_count()));
    let seen = exhaustively(&conds, |f| {
        cond::eval_agrees_with_truth_table(f, cond::Evaluators::real())
    });
    assert!(seen.iter().any(|s| s.contingent));
    assert!(seen.iter().any(|s| s.undecided));
}

fn or_as_and(c: &Cond) -> Cond {
    match c {
        Cond::Or(cs) | Cond::And(cs) => Cond::And(cs.iter().map(or_as_and).collect()),
        Cond::Not(c) => Cond::Not(Box::new(or_as_and(c))),
        other => other.clone(),
    }
}

fn count_off_by_one(c: &Cond) -> Cond {
    match c {
        Cond::Or(cs) => Cond::Or(cs.iter().map(count_off_by_one).collect()),
        Cond::And(cs) => Cond::And(cs.iter().map(count_off_by_one).collect()),
        Cond::Not(c) => Cond::Not(Box::new(count_off_by_one(c))),
        Cond::Count { atoms, cmp, n } => Cond::Count {
            atoms: atoms.clone(),
            cmp: *cmp,
            n: n + 1,
        },
        other => other.clone(),
    }
}

#[test]
fn evaluation_twin_fails_on_broken_kernels() {
    let conds = cond::all_conds();
    let check =
        |k: cond::Evaluators| first_violation(&conds, |f| cond::eval_agrees_with_truth_table(f, k));
    let e = check(cond::Evaluators {
        eval: |c, s| or_as_and(c).eval(s),
        eval3: Cond::eval3,
    });
    assert!(e.contains("eval gives"), "{e}");
    let e = check(cond::Evaluators {
        eval: |c, s| count_off_by_one(c).eval(s),
        eval3: Cond::eval3,
    });
    assert!(e.contains("eval gives"), "{e}");
    // eval3 that treats unknown atoms as false: unsound.
    let e = check(cond::Evaluators {
        eval: Cond::eval,
        eval3: |c, values, _known| Some(c.eval(values)),
    });
    assert!(e.contains("a completion gives"), "{e}");
    // eval3 that never decides anything: incomplete when every atom is known.
    let e = check(cond::Evaluators {
        eval: Cond::eval,
        eval3: |_, _, _| None,
    });
    assert!(e.contains("every atom known"), "{e}");
}

// ----- effect application --------------------------------------------------------------------

#[test]
fn effects_exhaustive() {
    let inputs = effects::all_applies(2);
    assert_eq!(inputs.len(), 8 * (1 + 512 + 512 * 512));
    let seen = exhaustively(&inputs, |i| {
        effects::apply_is_delete_then_add(i, GroundAction::apply)
    });
    assert!(seen.iter().any(|s| s.delete_and_add));
    assert!(seen.iter().any(|s| s.reads_old_state));
}

#[test]
fn effects_twin_fails_on_broken_kernels() {
    let inputs = effects::all_applies(2);
    // Add, then delete.
    first_violation(&inputs, |i| {
        effects::apply_is_delete_then_add(i, |a: &GroundAction, s: &AtomSet| {
            let fired: Vec<_> = a.effects.iter().filter(|e| e.when.eval(s)).collect();
            let mut next = s.clone();
            fired
                .iter()
                .for_each(|e| e.add.iter().for_each(|x| next.insert(*x)));
            fired
                .iter()
                .for_each(|e| e.del.iter().for_each(|x| next.remove(*x)));
            next
        })
    });
    // Each `when` read in the state the earlier effects left.
    first_violation(&inputs, |i| {
        effects::apply_is_delete_then_add(i, |a: &GroundAction, s: &AtomSet| {
            let mut next = s.clone();
            for e in &a.effects {
                if e.when.eval(&next) {
                    e.del.iter().for_each(|x| next.remove(*x));
                    e.add.iter().for_each(|x| next.insert(*x));
                }
            }
            next
        })
    });
    // Conditions ignored.
    first_violation(&inputs, |i| {
        effects::apply_is_delete_then_add(i, |a: &GroundAction, s: &AtomSet| {
            let mut all = a.clone();
            all.effects.iter_mut().for_each(|e| e.when = Cond::True);
            all.apply(s)
        })
    });
}

// ----- the visited-state store ----------------------------------------------------------------

#[test]
fn store_exhaustive() {
    let inputs = store::all_inserts(4);
    assert_eq!(
        inputs.len(),
        1 + 15 + 15 * 15 + 15 * 15 * 15 + 15 * 15 * 15 * 15
    );
    let seen = exhaustively(&inputs, |i| {
        store::store_numbers_first_insertions(i, check::store::Store::new())
    });
    assert!(seen.iter().any(|s| s.collision));
    assert!(seen.iter().any(|s| s.duplicate));
}

/// A store that never recognises a fingerprint it has seen.
#[derive(Default)]
struct Forgetful(Vec<(u64, Option<u32>)>);

impl store::VisitedStore for Forgetful {
    fn insert(&mut self, fp: u64, parent: Option<u32>) -> (u32, bool) {
        self.0.push((fp, parent));
        (self.0.len() as u32 - 1, true)
    }
    fn find(&self, fp: u64) -> Option<u32> {
        self.0.iter().position(|x| x.0 == fp).map(|i| i as u32)
    }
    fn fingerprint(&self, i: u32) -> u64 {
        self.0[i as usize].0
    }
    fn parent(&self, i: u32) -> Option<u32> {
        self.0[i as usize].1
    }
    fn len(&self) -> usize {
        self.0.len()
    }
}

/// A hash table without probing: a fingerprint whose home slot is taken overwrites it.
#[derive(Default)]
struct NoProbing {
    states: Vec<(u64, Option<u32>)>,
    slots: std::collections::BTreeMap<u32, u32>,
}

impl store::VisitedStore for NoProbing {
    fn insert(&mut self, fp: u64, parent: Option<u32>) -> (u32, bool) {
        if let Some(i) = self.find(fp) {
            return (i, false);
        }
        let i = self.states.len() as u32;
        self.states.push((fp, parent));
        self.slots.insert(fp as u32, i);
        (i, true)
    }
    fn find(&self, fp: u64) -> Option<u32> {
        let &i = self.slots.get(&(fp as u32))?;
        (self.states[i as usize].0 == fp).then_some(i)
    }
    fn fingerprint(&self, i: u32) -> u64 {
        self.states[i as usize].0
    }
    fn parent(&self, i: u32) -> Option<u32> {
        self.states[i as usize].1
    }
    fn len(&self) -> usize {
        self.states.len()
    }
}

/// The real store, keeping the parent of a state's last insertion instead of its first.
#[derive(Default)]
struct LastParent {
    store: check::store::Store,
    parents: Vec<Option<u32>>,
}

impl store::VisitedStore for LastParent {
    fn insert(&mut self, fp: u64, parent: Option<u32>) -> (u32, bool) {
        let (i, new) = self.store.insert(fp, parent).expect("memory");
        if new {
            self.parents.push(parent);
        } else {
            self.parents[i as usize] = parent;
        }
        (i, new)
    }
    fn find(&self, fp: u64) -> Option<u32> {
        self.store.find(fp)
    }
    fn fingerprint(&self, i: u32) -> u64 {
        self.store.fingerprint(i)
    }
    fn parent(&self, i: u32) -> Option<u32> {
        self.parents[i as usize]
    }
    fn len(&self) -> usize {
        self.store.len()
    }
}

#[test]
fn store_twin_fails_on_broken_kernels() {
    let inputs = store::all_inserts(3);
    let e = first_violation(&inputs, |i| {
        store::store_numbers_first_insertions(i, Forgetful::default())
    });
    assert!(e.contains("not (0, false)"), "{e}");
    let e = first_violation(&inputs, |i| {
        store::store_numbers_first_insertions(i, NoProbing::default())
    });
    assert!(e.contains("find("), "{e}");
    let e = first_violation(&inputs, |i| {
        store::store_numbers_first_insertions(i, LastParent::default())
    });
    assert!(e.contains("state 0 is"), "{e}");
}

// ----- Algorithm 1 ---------------------------------------------------------------------------

#[test]
fn demand_exhaustive() {
    let runs = demand::all_runs(5);
    assert_eq!(runs.len(), (1 + 5 + 25 + 125 + 625 + 3125) * 16);
    let seen = exhaustively(&runs, |r| {
        demand::demand_fires_exactly_at_novel_pairs(r, explain::demand_over)
    });
    assert!(seen.iter().any(|s| s.due));
    assert!(seen.iter().any(|s| s.by_pattern));
    assert!(seen.iter().any(|s| s.by_learning));
}

#[test]
fn demand_twin_fails_on_broken_kernels() {
    let runs = demand::all_runs(4);
    // Demand that never learns: a repeated novel pair is explained again.
    first_violation(&runs, |r| {
        demand::demand_fires_exactly_at_novel_pairs(r, |n, seq| {
            let mut prev = None;
            seq.iter()
                .map(|o| {
                    let due = o.is_action() && !n.is_expected(prev, o);
                    prev = Some(o);
                    due
                })
                .collect()
        })
    });
    // Demand that explains requests too.
    first_violation(&runs, |r| {
        demand::demand_fires_exactly_at_novel_pairs(r, |n, seq| {
            let mut prev = None;
            seq.iter()
                .map(|o| {
                    let due = n.learn(prev, o);
                    prev = Some(o);
                    due
                })
                .collect()
        })
    });
    // Demand that compares actions without their predecessor.
    first_violation(&runs, |r| {
        demand::demand_fires_exactly_at_novel_pairs(r, |n: &mut ExpectedSuccessors, seq| {
            let mut seen: Vec<&Observation> = Vec::new();
            let mut prev = None;
            seq.iter()
                .map(|o| {
                    let due = o.is_action() && !seen.contains(&o) && n.observe(prev, o);
                    seen.push(o);
                    prev = Some(o);
                    due
                })
                .collect()
        })
    });
}

// ----- Algorithm 2 ---------------------------------------------------------------------------

#[test]
fn content_exhaustive() {
    let stacks = content::all_stacks(2, 1, 3);
    assert_eq!(stacks.len(), (27 + 27 * 27) * (1 + 5 + 25 + 125));
    let seen = exhaustively(&stacks, |s| {
        content::content_is_gamma_up_to_first_modifier(s, content::real_content)
    });
    assert!(seen.iter().any(|s| s.stopped_early));
    assert!(seen.iter().any(|s| s.explained && !s.stopped_early));
    assert!(seen.iter().any(|s| !s.explained));
    assert!(seen.iter().any(|s| s.shared_literal));
}

#[test]
fn content_twin_fails_on_broken_kernels() {
    let stacks = content::all_stacks(2, 1, 3);
    // The content stops one step late.
    first_violation(&stacks, |s| {
        content::content_is_gamma_up_to_first_modifier(s, |stack: &[FrameSnapshot]| {
            let mut c = content::real_content(stack)?;
            let top = stack.last()?;
            if let Some(next) = top.body.get(c.actions.len()) {
                c.actions.push(match next {
                    explain::PlanStep::Action(t) => {
                        explain::PlanStep::Action(top.bindings.apply(t))
                    }
                    explain::PlanStep::Subgoal(t) => {
                        explain::PlanStep::Subgoal(top.bindings.apply(t))
                    }
                });
            }
            Some(c)
        })
    });
    // Γ from the top frame only.
    first_violation(&stacks, |s| {
        content::content_is_gamma_up_to_first_modifier(s, |stack: &[FrameSnapshot]| {
            content::real_content(&stack[stack.len().saturating_sub(1)..])
        })
    });
    // The frames' bindings ignored.
    first_violation(&stacks, |s| {
        content::content_is_gamma_up_to_first_modifier(s, |stack: &[FrameSnapshot]| {
            let bare: Vec<FrameSnapshot> = stack
                .iter()
                .map(|f| FrameSnapshot {
                    bindings: Substitution::new(),
                    ..f.clone()
                })
                .collect();
            content::real_content(&bare)
        })
    });
}

// ----- symmetry ------------------------------------------------------------------------------

/// Every state of the kitchen reachable in at most `depth` steps, breadth first.
fn reachable(fx: &symmetry::Fixture, depth: usize) -> Vec<State> {
    let mut seen: HashSet<State> = HashSet::new();
    let mut out = Vec::new();
    let mut queue: VecDeque<(State, usize)> = VecDeque::new();
    for s in fx.sem.initial_states() {
        if seen.insert(s.clone()) {
            queue.push_back((s, 0));
        }
    }
    while let Some((s, d)) = queue.pop_front() {
        if d < depth {
            for t in fx.sem.successors(&s) {
                if seen.insert(t.next.clone()) {
                    queue.push_back((t.next, d + 1));
                }
            }
        }
        out.push(s);
    }
    out
}

/// The kitchen, loaded once for the whole target.
fn kitchen() -> &'static symmetry::Fixture {
    static KITCHEN: std::sync::OnceLock<symmetry::Fixture> = std::sync::OnceLock::new();
    KITCHEN.get_or_init(symmetry::Fixture::kitchen)
}

#[test]
fn symmetry_exhaustive() {
    let fx = kitchen();
    assert_eq!(fx.renamings.len(), 2, "two cups: identity and swap");
    let states = reachable(fx, usize::MAX); // every reachable state
    assert!(states.len() > 1000, "{} states", states.len());
    let inputs: Vec<(&State, &Vec<model::ObjectId>)> = states
        .iter()
        .flat_map(|s| fx.renamings.iter().map(move |p| (s, p)))
        .collect();
    let seen = exhaustively(&inputs, |(s, p)| {
        symmetry::canonical_form_is_invariant(fx, s, p, |s| fx.symmetry.canonical(s))
    });
    assert!(seen.iter().any(|s| s.renaming_moved));
    assert!(seen.iter().any(|s| s.not_canonical));
    // The fingerprint the search stores is the canonical one.
    for s in states.iter().take(500) {
        assert_eq!(fx.symmetry.fingerprint(s), fx.symmetry.canonical(s).0);
    }
}

#[test]
fn symmetry_twin_fails_on_broken_kernels() {
    let fx = kitchen();
    let states = reachable(fx, 6);
    let inputs: Vec<(&State, &Vec<model::ObjectId>)> = states
        .iter()
        .flat_map(|s| fx.renamings.iter().map(move |p| (s, p)))
        .collect();
    let fp = check::explore::fingerprint::<State>;
    // No reduction at all: every state is its own canonical form.
    let e = first_violation(&inputs, |(s, p)| {
        symmetry::canonical_form_is_invariant(fx, s, p, |s| (fp(s), None))
    });
    assert!(e.contains("changes the canonical form"), "{e}");
    // The fingerprint of the state, not of its canonical form.
    let e = first_violation(&inputs, |(s, p)| {
        symmetry::canonical_form_is_invariant(fx, s, p, |s| (fp(s), fx.symmetry.canonical(s).1))
    });
    assert!(e.contains("fingerprint"), "{e}");
    // One "canonical form" for every state: invariant, but no renaming of the state.
    let e = first_violation(&inputs, |(s, p)| {
        symmetry::canonical_form_is_invariant(fx, s, p, |s| {
            let c = State {
                beliefs: AtomSet::empty(s.beliefs.words().len() * 64),
                order: Vec::new(),
                events: Vec::new(),
                intentions: Vec::new(),
                pending: None,
                waiting: Vec::new(),
                requested: 0,
                library: None,
                told: Vec::new(),
                asked: 0,
                atomic: false,
            };
            (fp(&c), Some(c))
        })
    });
    assert!(e.contains("no renaming"), "{e}");
}

// ----- proptest, beyond the exhaustive bounds -------------------------------------------------

fn applies() -> impl Strategy<Value = effects::SmallApply> {
    (
        0u8..8,
        0u8..=effects::MAX_EFFECTS as u8,
        prop::array::uniform3((0..effects::WHENS, 0u8..8, 0u8..8)),
    )
        .prop_map(|(s, n, es)| {
            let mut effects = [[0u8; 3]; effects::MAX_EFFECTS];
            for (i, (w, a, d)) in es.iter().enumerate().take(usize::from(n)) {
                effects[i] = [*w, *a, *d];
            }
            effects::SmallApply::new(s, n, effects).expect("canonical")
        })
}

fn runs() -> impl Strategy<Value = demand::SmallRun> {
    (
        0..=demand::MAX_LEN,
        prop::array::uniform6(0..demand::OBSERVATIONS),
        0u8..1 << demand::PATTERNS,
    )
        .prop_map(|(len, mut seq, patterns)| {
            seq[len..].iter_mut().for_each(|c| *c = 0);
            demand::SmallRun::new(len as u8, seq, patterns).expect("canonical")
        })
}

/// A list of codes in `1..limit` of length `len`, padded with 0.
fn list<const N: usize>(len: usize, codes: [u8; N]) -> [u8; N] {
    let mut out = codes;
    out[len..].iter_mut().for_each(|c| *c = 0);
    out
}

fn stacks() -> impl Strategy<Value = content::SmallStack> {
    let frame = (
        0..=content::MAX_LITERALS,
        prop::array::uniform2(1..content::LITERALS),
        0..content::BINDINGS,
    );
    (
        1..=content::MAX_FRAMES,
        prop::array::uniform3(frame),
        0..=content::MAX_STEPS,
        prop::array::uniform4(1..content::STEPS),
    )
        .prop_map(|(n, frames, steps, body)| {
            let mut literals = [[0; content::MAX_LITERALS]; content::MAX_FRAMES];
            let mut bindings = [0; content::MAX_FRAMES];
            for (i, (len, codes, b)) in frames.iter().enumerate().take(n) {
                literals[i] = list(*len, *codes);
                bindings[i] = *b;
            }
            content::SmallStack::new(n as u8, literals, bindings, list(steps, body))
                .expect("canonical")
        })
}

proptest! {
    #![proptest_config(config(256))]

    /// Both terms up to depth 2 (the exhaustive run pairs depth 2 with depth 1).
    #[test]
    fn unification_proptest(
        a in prop::sample::select(unify::all_terms(2, false)),
        b in prop::sample::select(unify::all_terms(2, false)),
    ) {
        let r = unify::unify_is_sound_and_most_general(&a, &b, unifier, thetas());
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    /// `.count` leaves at depth 2 too.
    #[test]
    fn evaluation_proptest(raw in prop::array::uniform7(0u16..cond::CODES)) {
        let f = cond::SmallCond::normalized(raw);
        let r = cond::eval_agrees_with_truth_table(&f, cond::Evaluators::real());
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    /// Up to 6 inserts.
    #[test]
    fn store_proptest(
        len in 0..=store::MAX_OPS,
        ops in prop::array::uniform6((0..store::FPS.len() as u8, 0..store::PARENTS)),
    ) {
        let mut codes = ops;
        codes[len..].iter_mut().for_each(|c| *c = (0, 0));
        let input = store::SmallInserts::new(len as u8, codes).expect("canonical");
        let r = store::store_numbers_first_insertions(&input, check::store::Store::new());
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    /// Up to 3 effects.
    #[test]
    fn effects_proptest(input in applies()) {
        let r = effects::apply_is_delete_then_add(&input, GroundAction::apply);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    /// Sequences of up to 6 observations.
    #[test]
    fn demand_proptest(run in runs()) {
        let r = demand::demand_fires_exactly_at_novel_pairs(&run, explain::demand_over);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    /// Up to 3 frames of 2 literals, bodies of up to 4 steps.
    #[test]
    fn content_proptest(stack in stacks()) {
        let r = content::content_is_gamma_up_to_first_modifier(&stack, content::real_content);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// Random walks of up to 12 steps, past the exhaustive depth's frontier states.
    #[test]
    fn symmetry_proptest(
        init in any::<u16>(),
        walk in prop::collection::vec(any::<u8>(), 0..=symmetry::MAX_WALK),
        perm in 0usize..2,
    ) {
        let fx = kitchen();
        let s = fx.state(init, &walk);
        let r = symmetry::canonical_form_is_invariant(fx, &s, &fx.renamings[perm], |s| {
            fx.symmetry.canonical(s)
        });
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}
