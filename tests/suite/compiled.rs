//! The compiled reasoning cycle (`semantics::compiled`) against the reference one: on every
//! reachable state of every example project, the same successors in the same order, with
//! the same notes and the same fingerprints. And `verify` with either gives the same report,
//! with symmetry reduction and without.

use bdi_check::check::explore::fingerprint;
use bdi_check::model::atoms::{AtomId, AtomSet};
use bdi_check::model::project::{load_project, load_system};
use bdi_check::semantics::compiled::{Sizes, Words};
use bdi_check::semantics::{Compiled, Packed, Semantics, State};
use std::collections::{HashSet, VecDeque};
use std::path::{Path, PathBuf};

/// Every project the tests verify (`specs/*`, `tests/verify/*`) and `tests/compiled/*`.
fn projects() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in ["specs", "tests/verify", "tests/compiled"] {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for e in std::fs::read_dir(&root)
            .expect("the folder exists")
            .flatten()
        {
            if e.path().join("bdi-check.toml").is_file() {
                out.push(e.path());
            }
        }
    }
    out.sort();
    out
}

/// Walks the reference transition system breadth first (up to `cap` states) and compares
/// each state's successors with the compiled system's: the states, what the search asks of
/// them, and how they compare. Returns the states compared and the compiled tables' sizes.
fn agree(dir: &Path, cap: usize) -> (usize, Option<Sizes>) {
    // Each agent of a project of several is compared alone (its own transition system).
    let agents = load_system(dir).unwrap_or_else(|e| panic!("{}: {e:?}", dir.display()));
    let mut total = 0;
    let mut sizes = None;
    for p in &agents {
        let (n, s) = agree_agent(dir, p, cap);
        total += n;
        sizes = sizes.or(s);
    }
    (total, sizes)
}

fn agree_agent(
    dir: &Path,
    p: &bdi_check::model::project::Project,
    cap: usize,
) -> (usize, Option<Sizes>) {
    let sem = Semantics::new(p).expect("the semantics");
    let Some(compiled) = Compiled::new(&sem) else {
        return (0, None);
    };
    let mut seen: HashSet<u64> = HashSet::new();
    let mut queue: VecDeque<State> = VecDeque::new();
    // Every belief base a compiled state has had: the interner holds these and no more.
    let mut bases: HashSet<(AtomSet, Vec<AtomId>)> = HashSet::new();
    for s in sem.initial_states() {
        let packed = compiled.pack(&s);
        assert_eq!(fingerprint(&packed), fingerprint(&s), "{}", dir.display());
        bases.insert((s.beliefs.clone(), s.order.clone()));
        if seen.insert(fingerprint(&s)) {
            queue.push_back(s);
        }
    }
    let mut compared = 0;
    while let Some(s) = queue.pop_front() {
        if compared == cap {
            break;
        }
        compared += 1;
        let want = sem.successors(&s);
        let packed = compiled.pack(&s);
        let got = compiled.successors(&packed);
        assert_eq!(
            want.len(),
            got.len(),
            "{}: successor count of {s:?}",
            dir.display()
        );
        let mut states: Vec<(&State, &Packed)> = vec![(&s, &packed)];
        states.extend(want.iter().map(|w| &w.next).zip(got.iter().map(|g| &g.1)));
        for (i, (a, pa)) in states.iter().enumerate() {
            same_view(dir, a, pa);
            // Packed states are equal exactly when the states they stand for are.
            assert_eq!(compiled.pack(a), **pa, "{}: {a:?}", dir.display());
            for (b, pb) in &states[i + 1..] {
                assert_eq!(pa == pb, a == b, "{}: {a:?} and {b:?}", dir.display());
            }
        }
        for (w, (notes, next)) in want.into_iter().zip(got) {
            bases.insert((w.next.beliefs.clone(), w.next.order.clone()));
            assert_eq!(
                w.notes,
                notes.to_vec(),
                "{}: notes from {s:?}",
                dir.display()
            );
            assert_eq!(
                w.next,
                compiled.unpack(&next),
                "{}: from {s:?}",
                dir.display()
            );
            assert_eq!(
                fingerprint(&w.next),
                fingerprint(&next),
                "{}",
                dir.display()
            );
            if seen.insert(fingerprint(&w.next)) {
                queue.push_back(w.next);
            }
        }
    }
    let sizes = compiled.sizes();
    assert_eq!(sizes.beliefs, bases.len(), "{}", dir.display());
    (compared, Some(sizes))
}

/// What the search and the checks read of a packed state is what they read of the state.
fn same_view(dir: &Path, s: &State, p: &Packed) {
    let at = dir.display();
    assert_eq!(p.beliefs(), &s.beliefs, "{at}: {s:?}");
    assert_eq!(p.order(), &s.order[..], "{at}: {s:?}");
    assert_eq!(p.first_event(), s.events.first(), "{at}: {s:?}");
    assert_eq!(p.is_idle(), s.is_idle(), "{at}: {s:?}");
    assert_eq!(p.pending_requests(), s.pending_requests(), "{at}: {s:?}");
}

#[test]
fn a_word_gives_back_the_state_it_was_made_of_on_every_project() {
    // The first states of every compiled agent, each packed in one word (as the agent's
    // stored graph keeps them) and read back: the same parts and requests. States that
    // share an agenda and requests share its number, and only those.
    let mut packed = 0;
    for dir in projects() {
        for p in &load_system(&dir).unwrap_or_else(|e| panic!("{}: {e:?}", dir.display())) {
            let sem = Semantics::new(p).expect("the semantics");
            let Some(compiled) = Compiled::new(&sem) else {
                continue;
            };
            let mut words = Words::default();
            let mut met: HashSet<Packed> = HashSet::new();
            let mut made = Vec::new();
            let mut queue: VecDeque<Packed> = compiled.initial_states().into();
            while let Some(s) = queue.pop_front() {
                if made.len() == 2_000 || !met.insert(s) {
                    continue;
                }
                let word = words.word(&s).expect("an address within 47 bits");
                made.push((s, word));
                queue.extend(compiled.successors(&s).into_iter().map(|(_, n)| n));
            }
            let mut rests = HashSet::new();
            for (s, word) in &made {
                // SAFETY: `word` was made by `words.word`.
                let (beliefs, rest) = unsafe { words.split(*word) };
                assert!(words.packed(beliefs, rest) == *s, "{}", dir.display());
                assert_eq!(words.agenda_key(rest), s.agenda_key());
                rests.insert((s.agenda_key(), s.requested()));
            }
            assert_eq!(words.numbered(), rests.len(), "{}", dir.display());
            packed += made.len();
        }
    }
    assert!(packed > 5_000, "{packed}");
}

#[test]
fn compiled_successors_are_the_reference_ones_on_every_project() {
    let mut total = 0;
    for dir in projects() {
        let (n, sizes) = agree(&dir, 40_000);
        total += n;
        if dir.ends_with("specs/kitchen") {
            // Many parts, and many phases memoized (each counted once).
            let s = sizes.expect("the kitchen is compiled");
            let least = s.beliefs.min(s.events).min(s.intentions);
            assert!(least > 1 && s.deliberations > 1 && s.acts > 1, "{s:?}");
        }
    }
    assert!(total > 10_000, "states compared: {total}");
}

#[test]
fn compiled_successors_are_the_reference_ones_on_every_jason_conformance_agent() {
    // The conformance agents use the constructs the examples do not (rules, `.count`,
    // `.findall`, loops, `.wait`, plans added at run time, percept order): the memo keys
    // must hold every belief each of them reads.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/jason");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .expect("tests/jason")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("bdi-check.toml").is_file())
        .collect();
    dirs.sort();
    let (mut total, mut compiled) = (0, 0);
    for dir in &dirs {
        let (n, _) = agree(dir, 5_000);
        total += n;
        compiled += usize::from(n > 0);
    }
    assert!(
        compiled >= 40,
        "{compiled} of {} agents compiled",
        dirs.len()
    );
    assert!(total > 2_000, "states compared: {total}");
}

#[test]
fn verify_reports_the_same_with_the_compiled_and_the_reference_cycle() {
    use bdi_check::check::explore::Limits;
    use bdi_check::check::{verify_with, VerifyOptions};
    let limits = Limits {
        max_states: 200_000,
        max_depth: 10_000,
        timeout: None,
    };
    let mut compared = 0;
    let mut explained = false;
    for dir in projects() {
        if load_system(&dir).expect("the project loads").len() > 1 {
            continue;
        }
        let p = load_project(&dir).expect("the project loads");
        if !Semantics::new(&p).is_ok_and(|s| s.is_local()) {
            continue;
        }
        let lint: Vec<_> = bdi_check::smt::lint(&p, &bdi_check::smt::LintOptions::default())
            .into_iter()
            .map(|l| l.finding)
            .collect();
        for symmetry in [false, true] {
            let run = |compiled, stored_users| {
                let opts = VerifyOptions {
                    threads: 2,
                    symmetry,
                    compiled,
                    stored_users,
                    ..VerifyOptions::default()
                };
                verify_with(&p, limits, &opts, |_, _, _, _| {}, &lint).expect("verify runs")
            };
            let (fast, slow) = (run(true, true), run(false, true));
            let at = format!("{} (symmetry {symmetry})", dir.display());
            // The users' searches on the agent's stored graph and on the cycle run again.
            let again = run(true, false);
            assert_eq!(fast.findings, again.findings, "{at}: stored graph");
            assert_eq!(fast.stats.phases.len(), again.stats.phases.len(), "{at}");
            for (a, b) in fast.stats.phases.iter().zip(&again.stats.phases) {
                assert_eq!(
                    (&a.name, a.states),
                    (&b.name, b.states),
                    "{at}: stored graph"
                );
            }
            assert_eq!(fast.findings, slow.findings, "{at}");
            assert_eq!(fast.stats.states, slow.stats.states, "{at}");
            assert_eq!(fast.stats.transitions, slow.stats.transitions, "{at}");
            assert_eq!(fast.memory.0, slow.memory.0, "{at}");
            assert_eq!(fast.symmetry_caveat, slow.symmetry_caveat, "{at}");
            // The users' searches (explanation properties) run on either cycle too.
            let phases = |v: &bdi_check::check::Verification| -> Vec<(String, Option<usize>)> {
                v.stats
                    .phases
                    .iter()
                    .map(|p| (p.name.clone(), p.states))
                    .collect()
            };
            assert_eq!(phases(&fast), phases(&slow), "{at}");
            explained |= phases(&fast)
                .iter()
                .any(|p| p.0.starts_with("explanation:"));
        }
        compared += 1;
    }
    assert!(compared >= 5, "projects compared: {compared}");
    assert!(explained, "no project with explanation users was compared");
}

#[test]
fn libraries_that_touch_other_intentions_are_not_compiled() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let local = |dir: &str| {
        let p = load_project(&root.join(dir)).expect("the project loads");
        let sem = Semantics::new(&p).expect("the semantics");
        assert_eq!(sem.is_local(), Compiled::new(&sem).is_some(), "{dir}");
        sem.is_local()
    };
    // `.intend`, `.succeed_goal`, `.fail_goal` and `.drop_desire` read or change the
    // other intentions: a phase then depends on more than its own part of the state.
    assert!(!local("tests/verify/control"));
    assert!(local("tests/compiled/control"));
    assert!(local("specs/kitchen"));
}

#[test]
fn act_phases_share_a_memo_entry_only_where_the_percept_order_is_the_same() {
    // Jason perceives an action's effects in the order of a hash set whose buckets double
    // past 12 elements: far from that, every count gives one key; near it, the count
    // itself is the key (an act memoized at 11 percepts must not serve one at 12).
    let p = load_project(Path::new("specs/kitchen")).expect("the kitchen loads");
    let sem = Semantics::new(&p).expect("the semantics");
    assert_eq!(sem.env_class(2), sem.env_class(3));
    assert_ne!(sem.env_class(11), sem.env_class(12));
    assert_ne!(sem.env_class(3), sem.env_class(40));
}

#[test]
fn symmetry_on_compiled_parts_agrees_with_symmetry_on_whole_states() {
    // The canonical fingerprint and the equivariance check made part by part
    // (`Compiled::map`) against the same made on whole states, on every state of a
    // breadth-first walk of the kitchen (symmetric in its cups) and of hash_order (not
    // equivariant: Jason perceives in an order that depends on the names).
    use bdi_check::check::symmetry::Symmetry;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut broken = 0;
    for dir in [
        "specs/kitchen",
        "tests/verify/hash_order",
        "tests/verify/symmetric_order",
    ] {
        let p = load_project(&root.join(dir)).expect("the project loads");
        let sem = Semantics::new(&p).expect("the semantics");
        let sym = Symmetry::new(&p, &sem)
            .expect("symmetry is sound here")
            .expect("the manifest declares symmetry");
        let c = Compiled::new(&sem).expect("a local library");
        let mut seen: HashSet<u64> = HashSet::new();
        let mut queue: VecDeque<Packed> = c.initial_iter().collect();
        let mut compared = 0;
        let mut first = None;
        while let Some(s) = queue.pop_front() {
            if !seen.insert(fingerprint(&s)) || compared == 5_000 {
                continue;
            }
            compared += 1;
            let whole = c.unpack(&s);
            assert_eq!(
                sym.fingerprint_compiled(&c, &s),
                sym.fingerprint(&whole),
                "{dir}"
            );
            let parts = sym.equivariance_violation_compiled(&c, &s, None);
            assert_eq!(parts, sym.equivariance_violation(&sem, &whole), "{dir}");
            // Given the successors (as the search does), the same.
            let succ: Vec<Packed> = c.successors(&s).into_iter().map(|(_, t)| t).collect();
            let given = sym.equivariance_violation_compiled(&c, &s, Some(succ.iter().collect()));
            assert_eq!(given, parts, "{dir}");
            broken += usize::from(parts.is_some());
            first = first.or(parts);
            queue.extend(succ);
        }
        assert!(compared > 5, "{dir}: {compared} states");
        // Checked once on the phases the walk computed, as the search does: the same
        // verdict, with the same renaming (these projects have one generator).
        assert_eq!(sym.phase_violation(&c), first, "{dir}");
    }
    assert!(broken > 0, "hash_order breaks equivariance somewhere");
}
