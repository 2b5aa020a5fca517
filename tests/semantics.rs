//! Facts of the reasoning cycle that the recorded Jason runs (tests/jason.rs) cannot show:
//! what the search may cache (`is_local`, `is_ordered`) and what a transition reports, on
//! one-plan libraries written for each construct.

mod common;

use bdi_check::model::project::{load_project, Project};
use bdi_check::semantics::{Note, Semantics, State};
use common::temp_dir;
use std::collections::{HashSet, VecDeque};

const DOMAIN: &str = "(define (domain d) (:types thing)
  (:predicates (p ?x - thing))
  (:action act :parameters (?x - thing) :precondition (and) :effect (p ?x))
  (:action ping :parameters () :precondition (and) :effect (and)))
";

/// The project of `asl` over things `a` and `b`, requesting `go` once.
fn project(tag: &str, asl: &str) -> Project {
    let d = temp_dir(&format!("semantics-{tag}"));
    std::fs::write(d.join("agent.asl"), asl).unwrap();
    std::fs::write(d.join("domain.pddl"), DOMAIN).unwrap();
    std::fs::write(
        d.join("bdi-check.toml"),
        "[agent]\nplans = \"agent.asl\"\nactions = \"domain.pddl\"\n\n\
         [objects]\nthing = [\"a\", \"b\"]\n\n[initial]\nvary = []\n\n\
         [requests]\ngoals = [\"go\"]\nmax = 1\n",
    )
    .unwrap();
    let p = load_project(&d).unwrap_or_else(|e| panic!("{asl}: {:?}", e.diagnostics));
    let _ = std::fs::remove_dir_all(&d);
    p
}

/// Every transition reachable from the initial states, with the state it leaves.
fn transitions(sem: &Semantics) -> Vec<(State, bdi_check::semantics::Transition)> {
    let mut seen = HashSet::new();
    let mut queue: VecDeque<State> = sem.initial_states().into_iter().collect();
    let mut out = Vec::new();
    while let Some(s) = queue.pop_front() {
        if !seen.insert(s.clone()) {
            continue;
        }
        assert!(seen.len() < 10_000, "the test's agent has few states");
        for t in sem.successors(&s) {
            queue.push_back(t.next.clone());
            out.push((s.clone(), t));
        }
    }
    out
}

#[test]
fn a_library_is_local_unless_some_context_or_step_reads_other_intentions() {
    // `Compiled` caches an act phase by the intention and the beliefs: sound only when no
    // plan asks about, or acts on, the other intentions (or waits for their events).
    let g = "+!g <- act(a).\n";
    let cases = [
        ("+!go <- act(a); !g.", true),
        (
            "+!go <- if (p(a)) { act(a) } elif (p(b)) { !g } else { act(b) }.",
            true,
        ),
        (
            "+!go <- while (p(a)) { act(b) }; for (p(X)) { act(X) }.",
            true,
        ),
        ("+!go : p(a) & not p(b) | p(b) <- act(a).", true),
        ("+!go : p(a) & .intend(g) <- act(a).", false),
        ("+!go : .desire(g) | p(a) <- act(a).", false),
        ("+!go : not .intend(g) <- act(a).", false),
        ("+!go <- .fail_goal(g).", false),
        ("+!go <- if (p(a) & .intend(g)) { act(a) }.", false),
        ("+!go <- if (p(a)) { .succeed_goal(g) }.", false),
        (
            "+!go <- if (p(a)) { act(a) } else { .drop_desire(g) }.",
            false,
        ),
        (
            "+!go <- if (p(a)) { act(a) } elif (p(b)) { .drop_intention(g) }.",
            false,
        ),
        ("+!go <- while (p(a)) { .fail_goal(g) }.", false),
        ("+!go <- while (.intend(g)) { act(a) }.", false),
        ("+!go <- for (p(X)) { .drop_intention(g) }.", false),
        ("+!go <- .wait(5); act(a).", false),
    ];
    for (i, (asl, local)) in cases.into_iter().enumerate() {
        let p = project(&format!("local-{i}"), &format!("{asl}\n{g}"));
        let sem = Semantics::new(&p).expect("the semantics");
        assert_eq!(sem.is_local(), local, "{asl}");
    }
}

#[test]
fn a_predicate_keeps_its_belief_order_when_a_query_can_see_it() {
    // Jason answers a query with variables newest belief first, so the order of `q`'s
    // beliefs is part of the state exactly when some query on `q` has a variable.
    let beliefs = "q(a). q(b).\n";
    let cases = [
        ("+!go <- ?q(a); -q(b); +q(b); act(a).", false),
        ("+!go : q(a) & not q(b) <- act(a).", false),
        ("+!go : q(X) <- act(X).", true),
        ("+!go <- ?q(X); act(X).", true),
        ("+!go <- .findall(X, q(X), L); act(a).", true),
        ("+!go <- -q(X); act(X).", true),
        ("+!go <- -+q(a).", true),
        ("+!go <- if (p(a)) { act(a) } elif (q(X)) { act(X) }.", true),
        ("+!go <- if (p(a)) { act(a) } else { ?q(X) }.", true),
        ("+!go <- while (p(a)) { ?q(X) }.", true),
        ("+!go <- for (q(X)) { act(X) }.", true),
        ("r(X) :- q(X).\n+!go : r(a) <- act(a).", true),
    ];
    for (i, (asl, ordered)) in cases.into_iter().enumerate() {
        let p = project(&format!("ordered-{i}"), &format!("{beliefs}{asl}\n"));
        let sem = Semantics::new(&p).expect("the semantics");
        let q = p.atoms.pred("q").expect("q is a predicate");
        assert_eq!(sem.is_ordered(q), ordered, "{asl}");
        let pp = p.atoms.pred("p").expect("p is a predicate");
        assert!(!sem.is_ordered(pp), "{asl}: only ground queries on p");
    }
}

#[test]
fn a_wait_that_ends_is_reported_before_the_event_its_cycle_handles() {
    // `.wait` ends at the start of a reasoning cycle, before the cycle selects its event
    // (Jason: the WaitEvent's resume runs as a task of the cycle's start).
    let p = project(
        "wait-notes",
        "+!go <- !!side; .wait({+p(b)}, 10); ping.\n+!side <- act(a); act(b).\n+p(X) <- ping.\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let mut seen = 0;
    for (from, t) in transitions(&sem) {
        if from.waiting.is_empty() || from.events.is_empty() || t.next.waiting == from.waiting {
            continue;
        }
        seen += 1;
        let ends = |n: &Note| {
            matches!(n, Note::Internal { text, .. }
                if text.ends_with("times out") || text.contains("ends: what it waited for came"))
        };
        let wait = t.notes.iter().position(ends);
        let event = t.notes.iter().position(|n| matches!(n, Note::Event(_)));
        assert!(wait.is_some(), "the wait's end is reported: {:?}", t.notes);
        assert!(wait < event, "before the event: {:?}", t.notes);
    }
    assert!(seen > 0, "some cycle ends the wait and handles an event");
}
