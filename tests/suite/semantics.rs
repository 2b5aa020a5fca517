//! Facts of the reasoning cycle that the recorded Jason runs (tests/suite/jason.rs) cannot show:
//! what the search may cache (`is_local`, `is_ordered`) and what a transition reports, on
//! one-plan libraries written for each construct.

use crate::common;

use bdi_check::model::project::{load_project, Project};
use bdi_check::semantics::{Note, Semantics, State};
use common::temp_dir;
use std::collections::{HashMap, HashSet, VecDeque};

const DOMAIN: &str = "(define (domain d) (:types thing)
  (:predicates (p ?x - thing))
  (:action act :parameters (?x - thing) :precondition (and) :effect (p ?x))
  (:action ping :parameters () :precondition (and) :effect (and))
  (:action two :parameters (?x ?y - thing) :precondition (and) :effect (and (p ?x) (p ?y))))
";

/// The project of `asl` over things `a` and `b`, requesting `go` once.
fn project(tag: &str, asl: &str) -> Project {
    project_with(tag, asl, &["a", "b"], "go").unwrap_or_else(|e| panic!("{asl}: {e}"))
}

/// The project of `asl` over `things`, requesting `goal` once, or what loading says.
fn project_with(tag: &str, asl: &str, things: &[&str], goal: &str) -> Result<Project, String> {
    let d = temp_dir(&format!("semantics-{tag}"));
    std::fs::write(d.join("agent.asl"), asl).unwrap();
    std::fs::write(d.join("domain.pddl"), DOMAIN).unwrap();
    let things: Vec<String> = things.iter().map(|t| format!("{t:?}")).collect();
    std::fs::write(
        d.join("bdi-check.toml"),
        format!(
            "[agent]\nplans = \"agent.asl\"\nactions = \"domain.pddl\"\n\n\
             [objects]\nthing = [{}]\n\n[initial]\nvary = []\n\n\
             [requests]\ngoals = [{goal:?}]\nmax = 1\n",
            things.join(", ")
        ),
    )
    .unwrap();
    let p = load_project(&d).map_err(|e| format!("{:?}", e.diagnostics));
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
        ("@g[atomic] +!go <- act(a).", false),
        ("@g[breakpoint] +!go <- act(a).", true),
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

#[test]
fn requests_ground_to_at_most_64_instances() {
    // A state keeps the requests made as the bits of a u64.
    let asl = "+!go(X) <- act(X).\n";
    let names: Vec<String> = (0..65).map(|i| format!("t{i}")).collect();
    let names: Vec<&str> = names.iter().map(|n| n.as_str()).collect();
    let p = project_with("requests-64", asl, &names[..64], "go(X)").expect("the project");
    let sem = Semantics::new(&p).expect("64 requests");
    assert_eq!(sem.requests.len(), 64);
    let p = project_with("requests-65", asl, &names, "go(X)").expect("the project");
    let e = Semantics::new(&p).err().expect("65 requests are refused");
    assert!(
        format!("{e:?}").contains("65 ground instances; at most 64"),
        "{e:?}"
    );
}

/// Every note of every reachable transition.
fn all_notes(sem: &Semantics) -> Vec<Note> {
    transitions(sem)
        .into_iter()
        .flat_map(|(_, t)| t.notes)
        .collect()
}

#[test]
fn only_the_contexts_up_to_the_first_applicable_plan_are_evaluated() {
    // Without a custom selectOption, Jason goes from SelEv to FindOp
    // (TransitionSystem.applySelEv, applyFindOp): it stops at the first applicable plan,
    // so a later context that would throw is never evaluated.
    let p = project(
        "find-op",
        "+!go : .count(p(_), N) & N < 1 <- ping.\n+!go : .count(p(_), N) & X = 1 div N <- ping.\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let notes = all_notes(&sem);
    assert!(
        notes
            .iter()
            .any(|n| matches!(n, Note::Plan { plan: 0, .. })),
        "{notes:?}"
    );
    assert!(
        !notes.iter().any(|n| matches!(n, Note::Beyond { .. })),
        "{notes:?}"
    );
}

#[test]
fn a_belief_event_without_an_applicable_plan_is_dropped() {
    // Jason discards it (TransitionSystem.applyRelApplPl: only goal events fail).
    let p = project("belief-event", "+!go <- act(a).\n+p(X) : p(b) <- ping.\n");
    let sem = Semantics::new(&p).expect("the semantics");
    let notes = all_notes(&sem);
    assert!(
        notes
            .iter()
            .any(|n| matches!(n, Note::Event(t) if t.to_string().starts_with("+p(a)"))),
        "{notes:?}"
    );
    assert!(
        !notes
            .iter()
            .any(|n| matches!(n, Note::GoalFailed { .. } | Note::NoApplicablePlan(_))),
        "{notes:?}"
    );
}

#[test]
fn a_failure_plan_goes_on_top_of_the_plan_that_failed() {
    // Jason pushes the -!g plan on the intention as it is (TransitionSystem.applyAddIM on
    // the failure event): the +!g plan stays below it, whatever TRO does for goal additions.
    let p = project(
        "failure-depth",
        "+!go <- !g; ping.\n+!g <- !h.\n-!g <- ping.\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let mut depths: Vec<(u32, u16)> = all_notes(&sem)
        .into_iter()
        .filter_map(|n| match n {
            Note::Plan { plan, depth, .. } => Some((plan, depth)),
            _ => None,
        })
        .collect();
    depths.sort();
    depths.dedup();
    assert_eq!(depths, [(0, 0), (1, 1), (2, 2)]);
}

#[test]
fn rules_that_call_each_other_too_deep_are_refused_not_false() {
    // A context that calls 256 rules deep is answered; one deeper leaves the model with
    // its reason (Jason recurses on its Java stack), never a silent "no answer".
    for (n, refused) in [(255, false), (256, true)] {
        // c0 :- c1. ... c{n-1} :- c{n}. c{n} :- 1 == 1. A query of c0 calls c{n} n + 1 deep.
        let mut asl: String = (0..n).map(|i| format!("c{i} :- c{}.\n", i + 1)).collect();
        asl.push_str(&format!("c{n} :- 1 == 1.\n+!go : c0 <- ping.\n"));
        let p = project(&format!("rule-depth-{n}"), &asl);
        let sem = Semantics::new(&p).expect("the semantics");
        let notes = all_notes(&sem);
        let beyond = notes.iter().find_map(|n| match n {
            Note::Beyond { reason, .. } => Some(reason.clone()),
            _ => None,
        });
        let adopted = notes
            .iter()
            .any(|n| matches!(n, Note::Plan { plan: 0, .. }));
        assert_eq!(adopted, !refused, "c0 to c{n}: {notes:?}");
        assert_eq!(
            beyond.is_some_and(|r| r.contains("more than 256 deep")),
            refused,
            "c0 to c{n}: {notes:?}"
        );
    }
}

#[test]
fn a_failed_constraint_fails_the_plan_with_error_constraint_failed() {
    // Jason's constraint step: generateGoalDeletion with createBasicErrorAnnots(
    // "constraint_failed", ...), so a -!g plan for that error is the one chosen.
    let p = project(
        "constraint-failed",
        "+!go <- .count(p(_), N); N == 1.\n\
         -!go[error(ia_failed)] <- act(b).\n\
         -!go[error(constraint_failed)] <- act(a).\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let plans: HashSet<u32> = all_notes(&sem)
        .into_iter()
        .filter_map(|n| match n {
            Note::Plan { plan, .. } => Some(plan),
            _ => None,
        })
        .collect();
    assert_eq!(plans, HashSet::from([0, 2]));
}

#[test]
fn a_belief_step_is_reported_with_its_own_sign() {
    let p = project("belief-signs", "+!go <- +q(a); -q(a); -+q(b).\n");
    let sem = Semantics::new(&p).expect("the semantics");
    let texts: Vec<String> = all_notes(&sem)
        .into_iter()
        .filter_map(|n| match n {
            Note::Belief { text, .. } => Some(text),
            _ => None,
        })
        .collect();
    assert_eq!(texts, ["+q(a)", "-q(a)", "-+q(b)"]);
}

#[test]
fn a_step_whose_arithmetic_leaves_the_model_is_named_as_written() {
    let p = project(
        "beyond-step",
        "+!go <- .count(p(_), N); act(a);\n    X = 1 div N.\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let beyond: Vec<(String, String)> = all_notes(&sem)
        .into_iter()
        .filter_map(|n| match n {
            Note::Beyond { text, reason, .. } => Some((text, reason)),
            _ => None,
        })
        .collect();
    assert_eq!(beyond.len(), 1, "{beyond:?}");
    assert_eq!(beyond[0].0, "X = 1 div N");
    assert!(beyond[0].1.contains("division by zero"), "{beyond:?}");
}

#[test]
fn fail_goal_is_refused_exactly_where_it_would_drop_a_bottom_goal() {
    // Jason 3 throws inside .fail_goal when it empties an intention (Intention.dropGoal,
    // then findEventForFailure peeks at it): refused. Elsewhere it is followed.
    let cases = [
        ("+!go <- .fail_goal(go).\n", true),
        ("+!go <- !!side; .fail_goal(side).\n+!side <- ping.\n", true),
        ("+!go <- !g.\n+!g <- .fail_goal(g).\n-!g <- ping.\n", false),
        (
            "+!go <- act(a).\n+p(X) <- .fail_goal(p(X)); ping.\n+!p(X) <- ping.\n",
            false,
        ),
    ];
    for (i, (asl, refused)) in cases.into_iter().enumerate() {
        let p = project(&format!("fail-goal-bottom-{i}"), asl);
        let sem = Semantics::new(&p).expect("the semantics");
        let notes = all_notes(&sem);
        let beyond = notes
            .iter()
            .any(|n| matches!(n, Note::Beyond { reason, .. } if reason.contains("bottom goal")));
        assert_eq!(beyond, refused, "{asl}{notes:?}");
    }
}

/// Whether some reachable state has `n` waits, all woken (resumed at the next cycle).
fn all_woken(sem: &Semantics, n: usize) -> bool {
    transitions(sem)
        .iter()
        .any(|(_, t)| t.next.waiting.len() == n && t.next.waiting.iter().all(|w| w.woken))
}

#[test]
fn one_action_s_percepts_wake_each_wait_they_match_in_turn() {
    // Each added event is told to the waits not woken yet (WaitEvent.eventAdded): the
    // second percept of `two` finds the first wait woken already, and wakes the other.
    let p = project(
        "wake-in-turn",
        "+!go <- !!wa; !!wb; ping; ping; two(a, b).\n\
         +!wa <- .wait({+p(a)}); ping.\n+!wb <- .wait({+p(b)}); ping.\n",
    );
    assert!(all_woken(&Semantics::new(&p).expect("the semantics"), 2));
}

#[test]
fn an_event_wait_is_woken_by_its_own_operator_and_kind_only() {
    // The events are `+!p(a)` and `+p(a)`: a wait for `-p(a)` matches their literal but
    // neither's operator and kind; a wait for `+!p(a)` is woken.
    for (i, wait) in ["{-p(a)}", "{+!p(a)}"].into_iter().enumerate() {
        let asl = format!(
            "+!go <- !!w; ping; ping; !!p(a); act(a).\n+!w <- .wait({wait}); ping.\n\
             +!p(X) <- ping.\n"
        );
        let p = project(&format!("wake-kind-{i}"), &asl);
        let sem = Semantics::new(&p).expect("the semantics");
        let woken = all_woken(&sem, 1);
        assert_eq!(woken, i == 1, "{wait}");
    }
}

#[test]
fn a_condition_wait_sees_the_beliefs_between_one_action_s_percepts() {
    // Jason adds each percept's event right after its belief changes: after the first of
    // `two`'s percepts, one p holds.
    let p = project(
        "wake-between",
        "+!go <- !!w; ping; ping; two(a, b).\n+!w <- .wait(.count(p(_), 1)); ping.\n",
    );
    assert!(all_woken(&Semantics::new(&p).expect("the semantics"), 1));
}

#[test]
fn random_has_one_outcome_per_element_or_declared_value() {
    // stdlib `random`: an element of its list, or (`.random(X)`) a number, here each value
    // of `[bounds] random`; any other step has one outcome.
    let d = temp_dir("semantics-random");
    std::fs::write(
        d.join("agent.asl"),
        "+!go <- .random([a, b], X); act(X); .random(R); .print(R); ping.\n",
    )
    .unwrap();
    std::fs::write(d.join("domain.pddl"), DOMAIN).unwrap();
    std::fs::write(
        d.join("bdi-check.toml"),
        "[agent]\nplans = \"agent.asl\"\nactions = \"domain.pddl\"\n\n\
         [objects]\nthing = [\"a\", \"b\"]\n\n[initial]\nvary = []\n\n\
         [requests]\ngoals = [\"go\"]\nmax = 1\n\n[bounds]\nrandom = [0.25, 0.75, 0.5]\n",
    )
    .unwrap();
    let p = load_project(&d).unwrap_or_else(|e| panic!("{:?}", e.diagnostics));
    let _ = std::fs::remove_dir_all(&d);
    let sem = Semantics::new(&p).expect("the semantics");
    let (mut acted, mut printed) = (HashSet::new(), HashSet::new());
    // How many successors each state has (once per state).
    let mut outcomes = std::collections::HashMap::new();
    for (from, t) in transitions(&sem) {
        outcomes
            .entry(from.clone())
            .or_insert_with(|| sem.successors(&from).len());
        for n in t.notes {
            match n {
                Note::Action { text, .. } => {
                    acted.insert(text);
                }
                Note::Printed(p) => {
                    printed.insert(p);
                }
                _ => {}
            }
        }
    }
    let want = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<HashSet<_>>();
    assert_eq!(acted, want(&["act(a)", "act(b)", "ping"]));
    assert_eq!(printed, want(&["0.25", "0.75", "0.5"]));
    // One state draws from the list (two outcomes), two draw a number (three each); every
    // other step, `.print` included, has one.
    let mut counts: Vec<usize> = outcomes.into_values().filter(|&n| n > 1).collect();
    counts.sort();
    assert_eq!(counts, [2, 3, 3]);
}

#[test]
fn print_shows_an_unbound_variable_as_no_value() {
    // stdlib println: a variable with no value prints as itself and `<no-value>`.
    let p = project("print-var", "+!go <- .print(\"x \", X); ping.\n");
    let sem = Semantics::new(&p).expect("the semantics");
    let printed: Vec<String> = all_notes(&sem)
        .into_iter()
        .filter_map(|n| match n {
            Note::Printed(s) => Some(s),
            _ => None,
        })
        .collect();
    assert_eq!(printed.len(), 1, "{printed:?}");
    assert!(
        printed[0].starts_with("x ") && printed[0].ends_with("<no-value>"),
        "{printed:?}"
    );
}

#[test]
fn an_intention_deeper_than_the_bound_fails_its_goal() {
    // `!r` before a step is no tail call: each one adds a plan to the stack.
    let p = project("deep-stack", "+!go <- !r.\n+!r <- !r; ping.\n");
    let sem = Semantics::new(&p).expect("the semantics");
    let failed = all_notes(&sem).into_iter().any(
        |n| matches!(n, Note::GoalFailed { reason, .. } if reason.contains("would hold more than")),
    );
    assert!(failed);
}

#[test]
fn rules_called_one_after_another_do_not_add_up_to_a_deep_call() {
    // The depth bound is of nested calls: 333 calls of rules in one context, each ended
    // before the next, are at most 3 deep.
    let ten = |r: &str| [r; 10].join(" & ");
    let asl = format!(
        "t :- 1 == 1.\nt10 :- {}.\nt100 :- {}.\n+!go : t100 & t100 & t100 <- ping.\n",
        ten("t"),
        ten("t10")
    );
    let p = project("rule-siblings", &asl);
    let sem = Semantics::new(&p).expect("the semantics");
    let notes = all_notes(&sem);
    assert!(
        notes
            .iter()
            .any(|n| matches!(n, Note::Plan { plan: 0, .. })),
        "{notes:?}"
    );
}

#[test]
fn intend_counts_goals_not_the_belief_plans_on_the_stack() {
    // stdlib intend: an intention's achievement goals; the +q(a) plan a belief update
    // pushed on the same intention (sameFocus) is not the goal q(a).
    let p = project(
        "intend-belief-frame",
        "+!go <- +q(a); ping.\n+q(X) <- if (.intend(q(X))) { act(a) } else { act(b) }.\n\
         +!q(X) <- ping.\n",
    );
    let acted: HashSet<String> = all_notes(&Semantics::new(&p).expect("the semantics"))
        .into_iter()
        .filter_map(|n| match n {
            Note::Action { text, .. } => Some(text),
            _ => None,
        })
        .collect();
    assert_eq!(
        acted,
        HashSet::from(["act(b)".to_string(), "ping".to_string()])
    );
}

#[test]
fn at_most_three_timers_fire_before_one_cycle() {
    // Four `.wait(5)` at once: a cycle may follow any one, two or three of them firing
    // (in every order), never four.
    let p = project(
        "timers",
        "+!go <- !!w; !!w; !!w; .wait(5); ping.\n+!w <- .wait(5); ping.\n",
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let mut most = 0;
    for (_, t) in transitions(&sem) {
        let fired = t
            .notes
            .iter()
            .filter(
                |n| matches!(n, Note::Internal { text, .. } if text.ends_with("its time is up")),
            )
            .count();
        most = most.max(fired);
    }
    assert_eq!(most, 3);
}

#[test]
fn states_that_differ_only_in_their_waits_have_different_fingerprints() {
    // The search keeps a state by its fingerprint: a wait woken or not is another state.
    let p = project("wait-hash", "+!go <- .wait({+p(a)}, 5); ping.\n");
    let sem = Semantics::new(&p).expect("the semantics");
    let asleep = transitions(&sem)
        .into_iter()
        .map(|(_, t)| t.next)
        .find(|s| !s.waiting.is_empty())
        .expect("a state with a wait");
    let mut woken = asleep.clone();
    woken.waiting[0].woken = !woken.waiting[0].woken;
    let fingerprint = bdi_check::check::explore::fingerprint::<State>;
    assert_ne!(fingerprint(&asleep), fingerprint(&woken));
}

#[test]
fn a_subgoal_s_variables_are_apart_from_its_plan_s() {
    // `!g(X, Y)` and `+!g(Y, X)`: the plan's X is the caller's Y (Jason renames the plan
    // apart from the literal it unifies with), so the caller's X gets what the plan's Y does.
    let p = project(
        "subgoal-apart",
        "+!go <- !g(X, Y); act(X); act(Y).\n+!g(Y, X) <- X = a; Y = b.\n",
    );
    let acted: Vec<String> = all_notes(&Semantics::new(&p).expect("the semantics"))
        .into_iter()
        .filter_map(|n| match n {
            Note::Action { text, .. } => Some(text),
            _ => None,
        })
        .collect();
    assert_eq!(acted, ["act(b)", "act(a)"]);
}

/// Every transition of `sem`, by the state it leaves.
fn successors_of(sem: &Semantics) -> HashMap<State, Vec<bdi_check::semantics::Transition>> {
    let mut out: HashMap<State, Vec<_>> = HashMap::new();
    for (from, t) in transitions(sem) {
        out.entry(from).or_default().push(t);
    }
    out
}

/// What runs after an action `start` on any run, until the action `stop`: the actions
/// (`action act(a)`) and the events handled (`event +!g`).
fn between(sem: &Semantics, start: &str, stop: &str) -> HashSet<String> {
    let succ = successors_of(sem);
    let mut stack: Vec<State> = succ
        .values()
        .flatten()
        .filter(|t| {
            t.notes
                .iter()
                .any(|n| matches!(n, Note::Action { text, .. } if text == start))
        })
        .map(|t| t.next.clone())
        .collect();
    assert!(!stack.is_empty(), "some run runs {start}");
    let mut seen = HashSet::new();
    let mut out = HashSet::new();
    while let Some(s) = stack.pop() {
        if !seen.insert(s.clone()) {
            continue;
        }
        for t in succ.get(&s).into_iter().flatten() {
            let mut stopped = false;
            for n in &t.notes {
                match n {
                    Note::Action { text, .. } if text == stop => {
                        stopped = true;
                        break;
                    }
                    Note::Action { text, .. } => {
                        out.insert(format!("action {text}"));
                    }
                    Note::Event(e) => {
                        out.insert(format!("event {e}"));
                    }
                    _ => {}
                }
            }
            if !stopped {
                stack.push(t.next.clone());
            }
        }
    }
    out
}

/// Two intentions from the start: `!other`, and `!work` under `label`.
fn two_intentions(label: &str, work: &str) -> String {
    format!(
        "!other.\n!work.\n+!other <- ping; ping; ping; ping.\n{label}+!work <- {work}.\n\
         +!more <- two(a, b).\n+p(a) <- ping.\n+!go <- true.\n"
    )
}

#[test]
fn an_atomic_intention_runs_alone_until_it_ends() {
    // Once `@work[atomic]` is chosen, only its own steps run (its subgoal's plan
    // included), and no other event is handled, until it ends: Jason's atomic intention
    // (`Circumstance.AI`: `applySelEv` selects no event, `applySelInt` takes it first, and
    // its subgoal's event `AE` comes before the queue). `act(a)` makes `p(a)` true, whose
    // plan pings; `!other` pings too.
    let work = "act(a); !more; act(b)";
    let p = project("atomic-alone", &two_intentions("@work[atomic]\n", work));
    let sem = Semantics::new(&p).expect("the semantics");
    assert_eq!(
        between(&sem, "act(a)", "act(b)"),
        HashSet::from(["event +!more".to_string(), "action two(a,b)".to_string()])
    );
    // Without the label, the other intention and the percept's plan come in between.
    let p = project("atomic-not", &two_intentions("@work\n", work));
    let sem = Semantics::new(&p).expect("the semantics");
    let seen = between(&sem, "act(a)", "act(b)");
    assert!(seen.contains("action ping"), "{seen:?}");
    assert!(seen.contains("event +p(a)[source(percept)]"), "{seen:?}");
}

#[test]
fn an_atomic_intention_that_waits_holds_up_the_whole_agent() {
    // In `.wait`, the atomic intention is suspended and still Jason's `AI`: no event is
    // handled and no other intention runs (`isAtomicIntentionSuspended`), the agent sleeps
    // (`canSleep`). Waiting for `+p(b)`, which nothing else can bring: no step at all.
    let work = "act(a); .wait({+p(b)}); act(b)";
    let p = project("atomic-waits", &two_intentions("@work[atomic]\n", work));
    let sem = Semantics::new(&p).expect("the semantics");
    let frozen: Vec<State> = successors_of(&sem)
        .into_values()
        .flatten()
        .map(|t| t.next)
        .filter(|s| !s.waiting.is_empty())
        .collect();
    assert!(!frozen.is_empty());
    for s in &frozen {
        assert!(!s.is_idle());
        assert!(sem.successors(s).is_empty(), "{s:?}");
    }
    assert!(frozen.iter().any(|s| !s.intentions.is_empty()));
    // Without the label, the other intention runs meanwhile.
    let p = project("atomic-waits-not", &two_intentions("@work\n", work));
    let sem = Semantics::new(&p).expect("the semantics");
    let pings = successors_of(&sem)
        .into_iter()
        .filter(|(s, _)| !s.waiting.is_empty())
        .flat_map(|(_, ts)| ts)
        .flat_map(|t| t.notes)
        .any(|n| matches!(n, Note::Action { text, .. } if text == "ping"));
    assert!(pings, "the other intention runs while `!work` waits");
    // A timer: the only step is the one in which it fires, and then `act(b)` comes next.
    let p = project(
        "atomic-timer",
        &two_intentions("@work[atomic]\n", "act(a); .wait(5); act(b)"),
    );
    let sem = Semantics::new(&p).expect("the semantics");
    assert_eq!(between(&sem, "act(a)", "act(b)"), HashSet::new());
}

#[test]
fn an_atomic_intention_left_atomic_while_it_fails_is_refused() {
    // Jason clears its atomic intention when an action fails (`applyProcAct`), not when a
    // `.wait` times out (`WaitEvent.resume`) nor when `.fail_goal` drops a goal of the
    // intention running it (`removeActionReQueue`): the intention then runs on from `AI`
    // while its failure event waits. Those steps are refused; without `[atomic]` they run.
    let cases = [".wait({+p(b)}, 5); ping", "!sub; ping"];
    let extra = "+!sub <- .fail_goal(sub); ping.\n-!sub <- ping.\n-!work <- ping.\n";
    for work in cases {
        for (label, refused) in [("@work[atomic]\n", true), ("@work\n", false)] {
            let asl = format!("{}{extra}", two_intentions(label, work));
            let p = project("atomic-refused", &asl);
            let beyond: Vec<String> = all_notes(&Semantics::new(&p).expect("the semantics"))
                .into_iter()
                .filter_map(|n| match n {
                    Note::Beyond { reason, .. } => Some(reason),
                    _ => None,
                })
                .collect();
            assert_eq!(!beyond.is_empty(), refused, "{asl}: {beyond:?}");
            assert!(
                beyond
                    .iter()
                    .all(|r| r.contains("in an atomic intention: Jason 3 leaves it")),
                "{beyond:?}"
            );
        }
    }
}

#[test]
fn a_running_atomic_intention_is_part_of_the_fingerprint() {
    // `State::atomic` (Jason's `AI` names the first intention) changes what the next
    // cycle does; states without it hash as they did before it existed.
    let p = project(
        "atomic-hash",
        &two_intentions("@work[atomic]\n", "act(a); !!more; act(b)"),
    );
    let sem = Semantics::new(&p).expect("the semantics");
    let running = successors_of(&sem)
        .into_values()
        .flatten()
        .map(|t| t.next)
        .find(|s| s.atomic)
        .expect("a state whose atomic intention runs");
    let mut plain = running.clone();
    plain.atomic = false;
    let fingerprint = bdi_check::check::explore::fingerprint::<State>;
    assert_ne!(fingerprint(&running), fingerprint(&plain));
}
