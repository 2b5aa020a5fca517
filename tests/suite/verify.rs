//! `bdi-check verify` and `replay` as users run them: seeded dynamic defects are found with
//! counterexamples that replay, the kitchen passes, the paper's gap is found, and the
//! exploration counts equal counts derived by hand.

use std::path::Path;

use crate::common;
use common::{bdi_check, report_json, steps, temp_dir, verify_json};

fn failing<'a>(report: &'a serde_json::Value, check: &str) -> Vec<&'a serde_json::Value> {
    report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == check && f["status"] == "fail")
        .collect()
}

fn replay_code(report: &Path, finding: Option<&str>) -> i32 {
    let mut args = vec!["replay", report.to_str().unwrap()];
    if let Some(id) = finding {
        args.extend(["--finding", id]);
    }
    let o = bdi_check(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.is_empty()
            || err.starts_with("note: the project changed")
            || o.status.code() == Some(2),
        "{err}"
    );
    o.status.code().unwrap()
}

#[test]
fn the_kitchen_passes_with_a_complete_search() {
    let (code, r, _) = verify_json("specs/kitchen", "kitchen");
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["verdict"], "pass");
    assert_eq!(r["stats"]["complete"], true);
    assert_eq!(r["stats"]["initial_states"], 100);
    assert!(r["stats"]["states"].as_u64().unwrap() > 1000);
    // Every dynamic check ran and held; lint's warnings that no run reaches are notes.
    for f in r["findings"].as_array().unwrap() {
        let failing = f["status"] == "fail" && f["severity"] != "note";
        assert!(!failing, "{f:#}");
    }
    for check in [
        "invariant",
        "deadlock",
        "action-failure",
        "goal-failure",
        "livelock",
        "request-not-completed",
    ] {
        assert!(
            r["findings"]
                .as_array()
                .unwrap()
                .iter()
                .any(|f| f["check"] == check && f["status"] == "pass"),
            "{check}"
        );
    }
    // The reachable property comes with its witness run.
    let witness = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "property:robot_puts_both_cups_away")
        .unwrap();
    assert!(steps(witness)
        .iter()
        .any(|t| t == "action navigateTo(cupboard)"));
}

#[test]
fn the_papers_gap_is_a_goal_failure_that_replays() {
    let (code, r, file) = verify_json("specs/paper", "paper");
    assert_eq!(code, 1);
    let f = failing(&r, "goal-failure");
    assert_eq!(f.len(), 1, "{r:#}");
    let f = f[0];
    assert_eq!(f["location"]["file"], "specs/paper/paper.asl");
    assert_eq!(f["location"]["line"], 12);
    let c = &f["counterexample"];
    let initial: Vec<&str> = c["initial"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert!(initial.contains(&"dishwasherDoor(open)"), "{initial:?}");
    assert_eq!(c["requests"], serde_json::json!(["storeCup(cup1)"]));
    let steps = steps(f);
    assert_eq!(steps[0], "request !storeCup(cup1)");
    assert!(steps.iter().any(|s| s == "event +!openDishwasherIfNeed"));
    assert!(steps
        .last()
        .unwrap()
        .contains("+!openDishwasherIfNeed fails: no applicable plan"));
    assert_eq!(replay_code(&file, None), 1);
    assert_eq!(replay_code(&file, Some(f["id"].as_str().unwrap())), 1);
}

#[test]
fn fixing_the_paper_makes_replay_pass() {
    let dir = temp_dir("paper-fixed");
    for name in ["paper.asl", "kitchen.pddl", "bdi-check.toml"] {
        std::fs::copy(Path::new("specs/paper").join(name), dir.join(name)).unwrap();
    }
    let project = dir.to_str().unwrap().to_string();
    let (code, r, file) = verify_json(&project, "paper-fixed-report");
    assert_eq!(code, 1);
    assert_eq!(replay_code(&file, None), 1);
    let gap = failing(&r, "goal-failure")[0]["id"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(replay_code(&file, Some(&gap)), 1);
    // The fix: a plan for the open door.
    let mut asl = std::fs::read_to_string(dir.join("paper.asl")).unwrap();
    asl.push_str("\n+!openDishwasherIfNeed : dishwasherDoor(open).\n");
    std::fs::write(dir.join("paper.asl"), asl).unwrap();
    assert_eq!(replay_code(&file, Some(&gap)), 0);
    // What is left is the paper's Algorithm 1 at adoption, which the fix does not change.
    let (code, r, _) = verify_json(&project, "paper-fixed-after");
    assert_eq!(code, 1, "{r:#}");
    let left: Vec<&str> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["status"] == "fail" && f["severity"] == "error")
        .map(|f| f["check"].as_str().unwrap())
        .collect();
    assert_eq!(left, ["demand-adoption"], "{r:#}");
}

/// (project, check that must fail, file:line it must point at (or "" for the manifest))
const SEEDED: &[(&str, &str, &str)] = &[
    (
        "tests/verify/invariant",
        "invariant",
        "tests/verify/invariant/bdi-check.toml:9",
    ),
    (
        "tests/verify/action_failure",
        "action-failure",
        "tests/verify/action_failure/agent.asl:2",
    ),
    (
        "tests/verify/goal_failure",
        "goal-failure",
        "tests/verify/goal_failure/agent.asl:2",
    ),
    (
        "tests/verify/failing_failure_plan",
        "goal-failure",
        "tests/verify/failing_failure_plan/agent.asl:4",
    ),
    ("tests/verify/livelock", "livelock", ""),
    ("tests/verify/livelock", "request-not-completed", ""),
    (
        "tests/verify/eventually",
        "property",
        "tests/verify/eventually/bdi-check.toml:11",
    ),
];

#[test]
fn each_seeded_defect_is_found_with_a_counterexample_that_replays() {
    for (i, (project, check, place)) in SEEDED.iter().enumerate() {
        let (code, r, file) = verify_json(project, &format!("seeded-{i}"));
        assert_eq!(code, 1, "{project}: {r:#}");
        let found = failing(&r, check);
        assert_eq!(found.len(), 1, "{project}: {check} in {r:#}");
        let f = found[0];
        if !place.is_empty() {
            let at = format!(
                "{}:{}",
                f["location"]["file"].as_str().unwrap(),
                f["location"]["line"]
            );
            assert_eq!(&at, place, "{project}: {f:#}");
        }
        // A run may be empty: an `eventually` property fails where nothing is asked (the
        // user may stop asking at any point).
        assert!(
            f["counterexample"]["steps"].is_array()
                && (check == &"property"
                    || !f["counterexample"]["steps"].as_array().unwrap().is_empty()),
            "{f:#}"
        );
        assert_eq!(
            replay_code(&file, Some(f["id"].as_str().unwrap())),
            1,
            "{project}: {check} does not replay"
        );
    }
}

#[test]
fn liveness_counterexamples_are_lassos() {
    let (_, r, _) = verify_json("tests/verify/livelock", "lasso");
    let f = failing(&r, "livelock")[0];
    let c = &f["counterexample"];
    let start = c["loop_start"].as_u64().expect("a loop start") as usize;
    let steps = steps(f);
    assert!(start < steps.len());
    // The loop walks to the dishwasher and back, forever.
    let looped = &steps[start..];
    assert!(
        looped.iter().any(|s| s == "action navigateTo(dishwasher)"),
        "{looped:?}"
    );
    assert!(
        looped.iter().any(|s| s == "action navigateTo(table)"),
        "{looped:?}"
    );
}

#[test]
fn a_handled_failure_is_not_a_goal_failure_but_its_coverage_gap_is_reached() {
    let (code, r, _) = verify_json("tests/verify/handled_failure", "handled");
    assert!(failing(&r, "goal-failure").is_empty(), "{r:#}");
    // SPEC §3: lint's coverage gap for +!open is reached by a run, so it is an error, even
    // though -!load handles the failure.
    let gap: Vec<_> = failing(&r, "coverage-gap")
        .into_iter()
        .filter(|f| f["severity"] == "error")
        .collect();
    assert_eq!(gap.len(), 1, "{r:#}");
    assert_eq!(gap[0]["location"]["line"], 4);
    assert!(steps(gap[0]).iter().any(|s| s == "event +!open"));
    assert_eq!(code, 1);
    // Its message says how to accept it on purpose; an unhandled gap's does not.
    assert!(
        gap[0]["message"].as_str().unwrap().contains("[[allow]]"),
        "{r:#}"
    );
    let (_, r, _) = verify_json("tests/verify/goal_failure", "unhandled");
    for f in failing(&r, "coverage-gap") {
        if f["severity"] == "error" {
            assert!(
                !f["message"].as_str().unwrap().contains("[[allow]]"),
                "{f:#}"
            );
        }
    }
}

#[test]
fn lint_warnings_no_run_reaches_become_notes() {
    let (_, r, _) = verify_json("specs/paper", "paper-notes");
    let notes: Vec<_> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == "precondition" && f["status"] == "fail")
        .collect();
    assert!(!notes.is_empty());
    for n in notes {
        assert_eq!(n["severity"], "note", "{n:#}");
        assert!(n["message"]
            .as_str()
            .unwrap()
            .ends_with("but no run reaches it"));
    }
    // The paper's coverage gap is reached, with the run that reaches it.
    let gaps = failing(&r, "coverage-gap");
    let reached: Vec<_> = gaps.iter().filter(|f| f["severity"] == "error").collect();
    assert_eq!(reached.len(), 1, "{gaps:#?}");
    assert_eq!(reached[0]["location"]["line"], 19);
}

#[test]
fn exploration_counts_equal_a_count_by_hand() {
    // Two initial states (door open or closed). From each: idle -> (request) -> event
    // queued -> (cycle: plan chosen, navigateTo(dishwasher) sent, the intention waits for
    // its feedback) -> (cycle: feedback, back in the queue, navigateTo(table) sent) ->
    // (cycle: feedback, intention done) -> idle with the request made: 5 states and 4
    // transitions each.
    let (code, r, _) = verify_json("tests/verify/tiny", "tiny");
    assert_eq!(code, 0, "{r:#}");
    let s = &r["stats"];
    assert_eq!(s["initial_states"], 2);
    assert_eq!(s["states"], 10);
    assert_eq!(s["transitions"], 8);
    assert_eq!(s["depth"], 4);
}

#[test]
fn bounds_give_incomplete_never_pass() {
    let o = bdi_check(&["verify", "specs/kitchen", "--max-states", "500", "-q"]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("verdict: incomplete"));
    let o = bdi_check(&[
        "verify",
        "specs/kitchen",
        "--max-depth",
        "3",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(3));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(r["verdict"], "incomplete");
    assert_eq!(r["stats"]["complete"], false);
    // A violation found within the bound is still a failure.
    let o = bdi_check(&["verify", "specs/paper", "--max-states", "12", "-q"]);
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn scenarios_are_written_one_per_counterexample() {
    let dir = temp_dir("scenarios");
    let o = bdi_check(&[
        "verify",
        "specs/paper",
        "-q",
        "--scenarios",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    // The reached coverage gap, the goal failure and the owner's demand-adoption run;
    // unreached warnings get none.
    assert_eq!(files.len(), 3, "{files:?}");
    for file in &files {
        let mut map = bdi_check::syntax::SourceMap::new();
        let sc =
            bdi_check::syntax::manifest::load_scenario(file, &mut map).expect("a valid scenario");
        assert_eq!(sc.requests.len(), 1);
        let door = if file.to_string_lossy().contains("demand-adoption") {
            "dishwasherDoor(closed)"
        } else {
            "dishwasherDoor(open)"
        };
        assert!(sc.initial.iter().any(|f| f.text == door), "{file:?}");
    }
}

#[test]
fn bad_input_exits_2() {
    assert_eq!(
        bdi_check(&["verify", "no/such/project"]).status.code(),
        Some(2)
    );
    let o = bdi_check(&["verify", "tests/project/unknown_type", "--format", "json"]);
    assert_eq!(o.status.code(), Some(2));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(r["verdict"], "error");
    assert_eq!(r["findings"][0]["check"], "input");
    let bad = temp_dir("bad-report").join("r.json");
    std::fs::write(&bad, "{ not json").unwrap();
    assert_eq!(replay_code(&bad, None), 2);
}

#[test]
fn graph_draws_the_goal_plan_tree_and_the_state_graph() {
    let o = bdi_check(&["graph", "specs/paper", "--plans"]);
    assert_eq!(o.status.code(), Some(0));
    let dot = String::from_utf8_lossy(&o.stdout);
    assert!(dot.starts_with("digraph plans {"), "{dot}");
    assert!(
        dot.contains("label = \"+!openDishwasherIfNeed/0\""),
        "{dot}"
    );
    assert!(
        dot.contains(": not dishwasherDoor(open) & holding(none)"),
        "{dot}"
    );
    assert_eq!(dot.matches(" -> ").count(), 3, "{dot}");
    assert!(!dot.contains("added at run time"), "{dot}");
    // A plan that `.add_plan` adds is drawn as such.
    let o = bdi_check(&["graph", "tests/jason/44-add-remove-plan", "--plans"]);
    let dot = String::from_utf8_lossy(&o.stdout);
    assert_eq!(dot.matches("(added at run time)").count(), 1, "{dot}");
    assert!(dot.contains("@extra"), "{dot}");
    // The paper's state graph is small enough to draw whole: 14 states, 12 transitions,
    // its two initial states double-bordered, the state whose step fails filled red with
    // the failing step red, every transition labelled.
    let o = bdi_check(&["graph", "specs/paper", "--states"]);
    let dot = String::from_utf8_lossy(&o.stdout).to_string();
    assert_eq!(dot.matches("[ label = \"s").count(), 14, "{dot}");
    assert_eq!(dot.matches(" -> ").count(), 12, "{dot}");
    assert!(dot.contains("navigateTo(dishwasher)"));
    assert_eq!(dot.matches("peripheries=2").count(), 2, "{dot}");
    assert_eq!(dot.matches("fillcolor=\"#f4cccc\"").count(), 1, "{dot}");
    assert_eq!(dot.matches("color=red, fontcolor=red").count(), 1, "{dot}");
    assert!(
        !dot.contains("label = \"\""),
        "an unlabelled transition: {dot}"
    );
    // The kitchen's is not, and the tool says so: it draws the states nearest one initial
    // state, not a strip of initial states.
    let o = bdi_check(&["graph", "specs/kitchen", "--states"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stderr).contains("too many to draw"));
    let dot = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(dot.matches("[ label = \"s").count() <= 200, "{dot}");
    assert_eq!(dot.matches("peripheries=2").count(), 1, "{dot}");
    // A large graph with failures: the runs to the failing states, each a path from an
    // initial state.
    let dir = kitchen_any("graph-kitchen-any");
    let o = bdi_check(&["graph", dir.to_str().unwrap(), "--states"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("drawing the runs to the first"), "{err}");
    let dot = String::from_utf8_lossy(&o.stdout).to_string();
    let (mut initial, mut failing, mut edges) = (Vec::new(), Vec::new(), Vec::new());
    for line in dot.lines().map(str::trim) {
        let id = line.split(' ').next().unwrap_or("").to_string();
        if line.contains(" -> ") {
            let to = line
                .split(" -> ")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap();
            edges.push((id.clone(), to.to_string()));
        } else if line.contains("peripheries=2") {
            initial.push(id.clone());
        }
        if line.contains("fillcolor=\"#f4cccc\"") {
            failing.push(id);
        }
    }
    assert!(!failing.is_empty(), "{dot}");
    let mut reached: std::collections::BTreeSet<String> = initial.into_iter().collect();
    loop {
        let before = reached.len();
        for (a, b) in &edges {
            if reached.contains(a) {
                reached.insert(b.clone());
            }
        }
        if reached.len() == before {
            break;
        }
    }
    assert!(failing.iter().all(|f| reached.contains(f)), "{dot}");
    // One of --plans and --states is required.
    assert_eq!(bdi_check(&["graph", "specs/paper"]).status.code(), Some(2));
}

/// A copy of the kitchen whose requests may arrive at any time, not only when it is idle.
fn kitchen_any(tag: &str) -> std::path::PathBuf {
    let dir = temp_dir(tag);
    for name in ["kitchen.asl", "kitchen.pddl", "bdi-check.toml"] {
        std::fs::copy(Path::new("specs/kitchen").join(name), dir.join(name)).unwrap();
    }
    let manifest = std::fs::read_to_string(dir.join("bdi-check.toml")).unwrap();
    std::fs::write(
        dir.join("bdi-check.toml"),
        manifest.replace("arrival = \"idle\"", "arrival = \"any\""),
    )
    .unwrap();
    dir
}

#[test]
fn concurrent_requests_interleave_and_interfere_in_the_kitchen() {
    let dir = kitchen_any("kitchen-any");
    let (code, r, file) = verify_json(dir.to_str().unwrap(), "kitchen-any-report");
    assert_eq!(code, 1);
    let failures = failing(&r, "action-failure");
    assert!(!failures.is_empty());
    // Each counterexample needs two requests in flight at once (with one at a time, the
    // kitchen passes: see `the_kitchen_passes_with_a_complete_search`).
    for f in &failures {
        let steps = steps(f);
        let requests = steps.iter().filter(|s| s.starts_with("request ")).count();
        assert_eq!(requests, 2, "{steps:#?}");
        assert!(steps.last().unwrap().contains(" fails: "), "{steps:#?}");
    }
    assert_eq!(replay_code(&file, None), 1);
}

#[test]
fn body_statements_and_internal_actions_behave_as_in_jason() {
    let (_, r, _) = verify_json("tests/verify/control", "control");
    let findings = r["findings"].as_array().unwrap();
    // Each property encodes one behaviour (see tests/verify/control/agent.asl): for over
    // every answer, if/elif/else, while, ?g, -+b, .succeed_goal, .fail_goal with -!g,
    // .findall/.length/.member, .intend (seeing the intention of the event being handled),
    // .drop_desire, and !!g.
    let props: Vec<_> = findings
        .iter()
        .filter(|f| f["check"] == "property")
        .collect();
    assert_eq!(props.len(), 15);
    for p in props {
        assert_eq!(p["status"], "pass", "{p:#}");
    }
    for check in ["goal-failure", "action-failure", "livelock", "deadlock"] {
        assert!(
            findings
                .iter()
                .any(|f| f["check"] == check && f["status"] == "pass"),
            "{check}"
        );
    }
    // The exploration decides everything, the static checks lint cannot encode
    // (arithmetic, lists) included: the search is complete, so the runs settle them.
    assert!(
        findings.iter().all(|f| f["status"] != "unknown"),
        "{findings:#?}"
    );
    assert_eq!(r["verdict"], "pass");
}

#[test]
fn a_timeout_is_incomplete_and_undecided_checks_say_how_far_they_hold() {
    // A zero-second limit is reached at the first check of the clock, after the initial
    // states: deterministic, whatever the machine's speed.
    let o = bdi_check(&["verify", "specs/kitchen", "--timeout", "0"]);
    assert_eq!(o.status.code(), Some(3));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("the time limit (`--timeout`) was reached"),
        "{out}"
    );
    assert!(
        out.contains("warning[invariant]: undecided: invariant `one_location`"),
        "{out}"
    );
    assert!(out.contains("as far as the search went"), "{out}");
    assert!(!out.contains("error[invariant]"), "{out}");
    assert!(
        out.lines()
            .last()
            .unwrap()
            .starts_with("verdict: incomplete"),
        "{out}"
    );
}

#[test]
fn every_spec_has_its_expected_outcome() {
    // What .github/workflows/verify.yml expects of the examples: the paper's plans and the
    // misleading-content example fail on purpose, every other project passes.
    let mut seen = Vec::new();
    for e in std::fs::read_dir("specs").unwrap().flatten() {
        if !e.path().join("bdi-check.toml").is_file() {
            continue;
        }
        let name = e.file_name().to_string_lossy().to_string();
        let o = bdi_check(&["verify", e.path().to_str().unwrap(), "-q"]);
        let want = if name == "paper" || name == "misleading-content" {
            1
        } else {
            0
        };
        assert_eq!(
            o.status.code(),
            Some(want),
            "{name}: {}",
            String::from_utf8_lossy(&o.stdout)
        );
        seen.push(name);
    }
    seen.sort();
    assert_eq!(
        seen,
        [
            "kitchen",
            "kitchen-explaining",
            "misleading-content",
            "paper",
            "two-robots",
            "two-robots-explaining"
        ]
    );
}

#[test]
fn an_invariant_that_is_not_inductive_is_settled_by_the_runs() {
    // lint: `putDown` can break `cup_placed` from some state that satisfies the invariants,
    // a warning. No run reaches such a state: a note, and the correct library passes.
    let (code, r, _) = verify_json("tests/verify/non_inductive", "non-inductive");
    assert_eq!(code, 0, "{r:#}");
    let f = failing(&r, "action-breaks-invariant");
    assert_eq!(f.len(), 1, "{f:#?}");
    assert_eq!(f[0]["severity"], "note");
    assert!(f[0]["message"]
        .as_str()
        .unwrap()
        .ends_with("yet it holds in every reachable state"));
    // A run that breaks the invariant makes it an error, with that run.
    let (code, r, _) = verify_json("tests/verify/invariant", "breaks-invariant");
    assert_eq!(code, 1);
    let f = failing(&r, "action-breaks-invariant");
    assert_eq!(f[0]["severity"], "error", "{f:#?}");
    assert!(f[0]["counterexample"].is_object());
}

#[test]
fn plan_checks_lint_cannot_decide_are_decided_by_the_runs() {
    // `N < 3` over `[bounds] numbers` is arithmetic lint does not model: its dead-plan and
    // coverage-gap checks of `+!tick` are undecided, and the runs decide them.
    let (_, r, _) = verify_json("tests/jason/38-counter", "undecided-by-runs");
    let findings = r["findings"].as_array().unwrap();
    let tick: Vec<_> = findings
        .iter()
        .filter(|f| f["message"].as_str().unwrap_or("").contains("+!tick"))
        .filter(|f| f["check"] == "dead-plan" || f["check"] == "coverage-gap")
        .collect();
    assert!(!tick.is_empty(), "{findings:#?}");
    for f in tick {
        assert_eq!(f["status"], "pass", "{f:#}");
    }
    assert!(findings
        .iter()
        .any(|f| f["message"] == "+!tick is applicable: a run adopts it"));
}

#[test]
fn a_plan_for_a_number_a_countdown_reaches_is_not_dead() {
    let (code, r, _) = verify_json("tests/verify/countdown", "countdown");
    assert_eq!(code, 0, "{r:#}");
    assert!(failing(&r, "dead-plan").is_empty());
}

#[test]
fn a_plan_for_a_list_argument_that_a_run_reaches_is_not_dead() {
    // Lint's events range over objects; `+!state([])` is reached by a subgoal, so lint
    // must leave it undecided (settled by the runs), never call it dead.
    let (code, r, _) = verify_json("tests/verify/list_trigger", "list_trigger");
    assert_eq!(code, 0, "{r:#}");
    assert!(failing(&r, "dead-plan").is_empty(), "{r:#}");
    let lint = std::process::Command::new(env!("CARGO_BIN_EXE_bdi-check"))
        .args(["lint", "tests/verify/list_trigger", "--format", "json"])
        .output()
        .expect("runs");
    let r: serde_json::Value = serde_json::from_slice(&lint.stdout).expect("JSON");
    assert!(failing(&r, "dead-plan").is_empty(), "{r:#}");
}

#[test]
fn a_wait_timer_may_end_before_what_it_waits_for() {
    // The model has no clock: `.wait(1000)` may end before `!prepare` is done, and the run
    // that shows it replays; waiting for the event itself is correct.
    let (code, r, file) = verify_json("tests/verify/wait_early", "wait_early");
    assert_eq!(code, 1, "{r:#}");
    let f: Vec<_> = failing(&r, "precondition")
        .into_iter()
        .filter(|f| f["severity"] == "error")
        .collect();
    assert_eq!(f.len(), 1, "{r:#}");
    assert_eq!(f[0]["location"]["line"], 5);
    let steps = steps(f[0]);
    assert!(
        steps
            .iter()
            .any(|s| s.contains(".wait(1000) ends: its time is up")),
        "{steps:?}"
    );
    assert!(failing(&r, "goal-failure")
        .iter()
        .all(|g| g["location"]["line"] != 10));
    let a = failing(&r, "action-failure");
    assert_eq!(a.len(), 1, "{r:#}");
    assert_eq!(replay_code(&file, Some(a[0]["id"].as_str().unwrap())), 1);
}

#[test]
fn an_atomic_plan_keeps_every_other_intention_out_until_it_ends() {
    // Borrowing the drill takes it out of its rack for three steps; an inspection needs it
    // in the rack. With `[atomic]` no interleaving of the two requests runs the inspection
    // in between (lint's precondition warning is settled: no run reaches it).
    let (code, r, _) = verify_json("tests/verify/atomic", "atomic");
    assert_eq!(code, 0, "{r:#}");
    assert!(failing(&r, "action-failure").is_empty(), "{r:#}");
    // The same plans without the label fail, and the run replays.
    let (code, r, file) = verify_json("tests/verify/atomic/interleaved.toml", "interleaved");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "action-failure");
    assert_eq!(f.len(), 1, "{r:#}");
    assert_eq!(
        f[0]["location"]["file"],
        "tests/verify/atomic/interleaved.asl"
    );
    assert_eq!(f[0]["location"]["line"], 5);
    let steps = steps(f[0]);
    let take = steps.iter().position(|s| s.contains("take(drill)"));
    let inspect = steps
        .iter()
        .position(|s| s.contains("inspect(drill) fails"));
    assert!(take.is_some() && take < inspect, "{steps:?}");
    assert_eq!(replay_code(&file, Some(f[0]["id"].as_str().unwrap())), 1);
}

#[test]
fn random_values_are_choices_of_the_search() {
    // Every value `[bounds] random` lists, and every element of `.random`'s list, is tried:
    // the runs that fail are found and replay.
    let (code, r, file) = verify_json("tests/verify/random", "random");
    assert_eq!(code, 1, "{r:#}");
    let failures = failing(&r, "action-failure");
    let line = |f: &&serde_json::Value| f["location"]["line"].as_u64().unwrap();
    let mut lines: Vec<u64> = failures.iter().map(line).collect();
    lines.sort();
    assert_eq!(lines, [8, 11], "{r:#}");
    for f in &failures {
        let s = steps(f);
        let want = if line(f) == 8 {
            ".random(0.1)"
        } else {
            ".random([a,b],b)"
        };
        assert!(s.iter().any(|x| x.contains(want)), "{s:?}");
        assert_eq!(replay_code(&file, Some(f["id"].as_str().unwrap())), 1);
    }
}

#[test]
fn a_counter_past_its_bound_makes_the_search_incomplete_not_failed() {
    // Jason would go on counting; the finite model cannot: that is a limit of the model
    // (exit 3, incomplete), never a goal failure of the agent.
    let (code, r, _) = verify_json("tests/verify/counter_beyond", "counter_beyond");
    assert_eq!(code, 3, "{r:#}");
    assert_eq!(r["verdict"], "incomplete");
    assert_eq!(r["stats"]["complete"], false);
    for check in ["goal-failure", "action-failure"] {
        assert!(
            r["findings"]
                .as_array()
                .unwrap()
                .iter()
                .all(|f| f["check"] != check || f["status"] != "fail"),
            "{r:#}"
        );
    }
}

#[test]
fn every_run_a_report_holds_replays_to_its_violation() {
    // Every error with a run, of every kind (static checks a run settled, dynamic checks,
    // explanation properties), replays to its violation on the unchanged project; a note
    // or an undecided warning has no run, and replaying it is refused, never called fixed.
    let projects = [
        "specs/paper",
        "specs/misleading-content",
        "tests/verify/goal_failure",
        "tests/verify/failing_failure_plan",
        "tests/verify/handled_failure",
        "tests/verify/invariant",
        "tests/verify/control",
        "tests/verify/livelock",
        "tests/verify/eventually",
        "tests/verify/wait_early",
        "tests/verify/random",
        "tests/verify/explain_untruthful",
    ];
    for dir in projects {
        let (_, r, file) = verify_json(dir, "replay_all");
        let runs: Vec<&serde_json::Value> = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| {
                f["status"] == "fail" && f["severity"] == "error" && !f["counterexample"].is_null()
            })
            .collect();
        let o = bdi_check(&["replay", file.to_str().unwrap()]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(out.lines().count(), runs.len(), "{dir}: {out}");
        assert!(
            out.lines()
                .all(|l| l.contains(": still reaches its violation")),
            "{dir}: {out}"
        );
        assert_eq!(o.status.code(), Some(i32::from(!runs.is_empty())), "{dir}");
        for f in r["findings"].as_array().unwrap() {
            if f["status"] == "fail" && f["severity"] == "note" && !f["counterexample"].is_null() {
                let id = f["id"].as_str().unwrap();
                let o = bdi_check(&["replay", file.to_str().unwrap(), "--finding", id]);
                assert_eq!(o.status.code(), Some(2), "{dir}: {id}");
                assert!(
                    String::from_utf8_lossy(&o.stderr).contains("has no run to replay"),
                    "{dir}: {id}"
                );
            }
        }
    }
}

#[test]
fn goal_failures_point_at_the_source_at_fault_and_ids_are_unique() {
    let (code, r, _) = verify_json("tests/verify/goal_places", "goal_places");
    assert_eq!(code, 1, "{r:#}");
    let mut places: Vec<(String, u64)> = failing(&r, "goal-failure")
        .iter()
        .map(|f| {
            let l = &f["location"];
            (
                l["file"]
                    .as_str()
                    .unwrap()
                    .rsplit('/')
                    .next()
                    .unwrap()
                    .to_string(),
                l["line"].as_u64().unwrap(),
            )
        })
        .collect();
    places.sort();
    assert_eq!(
        places,
        [
            ("agent.asl".to_string(), 3),
            ("agent.asl".to_string(), 4),
            ("bdi-check.toml".to_string(), 12)
        ],
        "{r:#}"
    );
    for dir in [
        "tests/verify/goal_places",
        "specs/kitchen-explaining",
        "tests/verify/control",
    ] {
        let (_, r, _) = verify_json(dir, "unique_ids");
        let ids: Vec<&str> = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["id"].as_str().unwrap())
            .collect();
        let set: std::collections::BTreeSet<&&str> = ids.iter().collect();
        assert_eq!(set.len(), ids.len(), "{dir}: {ids:?}");
    }
}

#[test]
fn replay_tells_a_changed_project_from_an_altered_report() {
    let dir = temp_dir("paper-integrity");
    for name in ["paper.asl", "kitchen.pddl", "bdi-check.toml"] {
        std::fs::copy(Path::new("specs/paper").join(name), dir.join(name)).unwrap();
    }
    let project = dir.to_str().unwrap().to_string();
    let (_, r, file) = verify_json(&project, "paper-integrity-report");
    assert_eq!(r["sources"].as_array().unwrap().len(), 3, "{r:#}");
    let text = std::fs::read_to_string(&file).unwrap();
    let run = |report: &str| {
        let f = dir.join("altered.json");
        std::fs::write(&f, report).unwrap();
        let o = bdi_check(&["replay", f.to_str().unwrap()]);
        (
            o.status.code().unwrap(),
            String::from_utf8_lossy(&o.stdout).into_owned(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    // Unaltered, on the unchanged project: every run replays, nothing to say.
    let (code, _, err) = run(&text);
    assert_eq!((code, err.as_str()), (1, ""));
    // A check bdi-check does not have.
    let (code, _, err) = run(&text.replacen(
        "\"check\": \"goal-failure\"",
        "\"check\": \"goal-fixed\"",
        1,
    ));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("which bdi-check does not have"), "{err}");
    // An initial state edited: on the unchanged project the run cannot be the one it gave.
    let (code, _, err) =
        run(&text.replace("\"dishwasherDoor(open)\"", "\"dishwasherDoor(closed)\""));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("does not match the project it was made from"),
        "{err}"
    );
    // A report that names no files: replayed, with a note that nothing is known.
    let mut bare: serde_json::Value = serde_json::from_str(&text).unwrap();
    bare.as_object_mut().unwrap().remove("sources");
    let (code, _, err) = run(&bare.to_string());
    assert_eq!(code, 1);
    assert!(
        err.contains("does not name the files it was made from"),
        "{err}"
    );
    // The project changed: said, and the runs replay against it as it is now.
    let mut asl = std::fs::read_to_string(dir.join("paper.asl")).unwrap();
    asl.push_str("\n+!openDishwasherIfNeed : dishwasherDoor(open).\n");
    std::fs::write(dir.join("paper.asl"), asl).unwrap();
    let (code, out, err) = run(&text);
    assert!(
        err.contains("the project changed since the report was made"),
        "{err}"
    );
    assert!(err.contains("paper.asl"), "{err}");
    assert!(out.contains("no longer reaches"), "{out}");
    assert_eq!(code, 1, "the paper's demand finding is left: {out}");
}

#[test]
fn the_human_report_puts_errors_first_and_notes_behind_v() {
    let o = bdi_check(&["verify", "specs/kitchen"]);
    assert_eq!(o.status.code(), Some(0));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(!out.contains("note["), "{out}");
    assert!(out.contains("notes not shown (`-v` shows them)"), "{out}");
    assert!(
        out.lines().last().unwrap().starts_with("verdict: pass"),
        "{out}"
    );
    let o = bdi_check(&["verify", "specs/paper", "-v"]);
    let out = String::from_utf8_lossy(&o.stdout);
    let first = |what: &str| out.find(what).unwrap_or_else(|| panic!("{what}: {out}"));
    assert!(first("error[") < first("note["), "{out}");
    // A note is not a run: it says so instead of showing a "counterexample".
    assert!(
        out.contains("a state where this holds, which no run reaches: "),
        "{out}"
    );
}

#[test]
fn a_new_users_agent_with_rules_a_counter_and_fail_verifies_with_no_false_error() {
    let (code, r, _) = verify_json("tests/verify/new_user", "new_user");
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["stats"]["complete"], true);
    // What lint could not decide, the complete search settles: the arithmetic step's
    // preconditions hold in every run, and the plan for a count above 2 is never adopted
    // (two rooms, one request each), which is said as a warning.
    let find = |check: &str| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["check"] == check && f["location"]["line"] == 5)
            .cloned()
    };
    let pre = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| {
            f["check"] == "precondition"
                && f["location"]["line"] == 5
                && f["location"]["column"] == 65
        })
        .expect("the arithmetic step's finding");
    assert_eq!(pre["status"], "pass", "{pre:#}");
    let dead = find("dead-plan");
    assert!(dead.is_none() || dead.unwrap()["status"] != "unknown");
    let report = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["check"] == "dead-plan" && f["location"]["line"] == 7)
        .expect("the plan for a count above 2");
    assert_eq!(report["severity"], "warning");
    assert!(report["message"]
        .as_str()
        .unwrap()
        .starts_with("no run adopts"));
}

#[test]
fn trace_shows_the_state_after_each_step_of_every_run() {
    // `trace` replays the run the report holds and shows each transition's steps with the
    // whole state after it. Checked against the report: its steps are the counterexample's
    // (the checker's explanation steps aside), and each state's beliefs are the previous
    // ones changed exactly as the steps between them say.
    for dir in [
        "tests/verify/goal_failure",
        "tests/verify/wait_early",
        "tests/verify/livelock",
        "tests/verify/explain_untruthful",
    ] {
        let (_, r, file) = verify_json(dir, "trace");
        let runs = r["findings"].as_array().unwrap().iter().filter(|f| {
            f["status"] == "fail" && f["severity"] == "error" && !f["counterexample"].is_null()
        });
        let mut traced = 0;
        for f in runs {
            let id = f["id"].as_str().unwrap();
            let o = bdi_check(&[
                "trace",
                file.to_str().unwrap(),
                "--finding",
                id,
                "--format",
                "json",
            ]);
            assert_eq!(o.status.code(), Some(1), "{dir}: {id}");
            let t: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            assert_eq!(t["finding"], id);
            assert_eq!(t["reached"], true);
            let shown: Vec<(String, String)> = t["transitions"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|x| x["steps"].as_array().unwrap().iter())
                .map(|s| (s["kind"].to_string(), s["text"].to_string()))
                .collect();
            let recorded: Vec<(String, String)> = f["counterexample"]["steps"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|s| s["kind"] != "explanation")
                .map(|s| (s["kind"].to_string(), s["text"].to_string()))
                .collect();
            assert!(
                shown.len() >= recorded.len() && shown[..recorded.len()] == recorded[..],
                "{dir}: {id}:\n{shown:?}\n{recorded:?}"
            );
            let set = |v: &serde_json::Value| -> std::collections::BTreeSet<String> {
                v.as_array()
                    .unwrap()
                    .iter()
                    .map(|a| a.as_str().unwrap().to_string())
                    .collect()
            };
            let mut beliefs = set(&t["initial"]["beliefs"]);
            assert_eq!(beliefs, set(&f["counterexample"]["initial"]), "{dir}: {id}");
            for x in t["transitions"].as_array().unwrap() {
                for s in x["steps"].as_array().unwrap() {
                    for a in set(&s["removed"]) {
                        assert!(beliefs.remove(&a), "{dir}: {id}: {a} was not believed");
                    }
                    for a in set(&s["added"]) {
                        assert!(beliefs.insert(a.clone()), "{dir}: {id}: {a} was believed");
                    }
                }
                assert_eq!(beliefs, set(&x["state"]["beliefs"]), "{dir}: {id}: {x:#}");
            }
            if dir.ends_with("goal_failure") {
                // The intention's frame names the plan's bindings and the step it runs next.
                let frames: Vec<&serde_json::Value> = t["transitions"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .flat_map(|x| x["state"]["intentions"].as_array().unwrap())
                    .flat_map(|i| i["frames"].as_array().unwrap())
                    .collect();
                assert!(
                    frames.iter().any(|f| f["next"] == "pickUp(C)"
                        && f["bindings"][0] == "C = cup1"
                        && f["trigger"] == "+!load(cup1)"),
                    "{frames:#?}"
                );
            }
            if dir.ends_with("explain_untruthful") {
                // The user learns each novel pair as Algorithm 1 does: N only grows.
                let learned: Vec<usize> = t["transitions"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| {
                        x["state"]["expected"][0]["learned"]
                            .as_array()
                            .unwrap()
                            .len()
                    })
                    .collect();
                assert!(learned.windows(2).all(|w| w[0] <= w[1]), "{learned:?}");
                assert!(learned.last() > Some(&0), "{learned:?}");
            }
            let human = bdi_check(&["trace", file.to_str().unwrap(), "--finding", id]);
            let text = String::from_utf8_lossy(&human.stdout);
            assert!(text.contains("transition 1\n"), "{text}");
            assert!(text.contains("  intention 1 ("), "{text}");
            assert!(
                text.ends_with(&format!(
                    "{id}: still reaches its violation ({})\n",
                    t["outcome"].as_str().unwrap()
                )),
                "{text}"
            );
            traced += 1;
        }
        assert!(traced > 0, "{dir}: no run to trace");
        // Bad input: an unknown id, a finding without a run, a format trace has not.
        let o = bdi_check(&["trace", file.to_str().unwrap(), "--finding", "nope"]);
        assert_eq!(o.status.code(), Some(2), "{dir}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("has no finding `nope`"));
        if let Some(note) = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["severity"] == "note" && f["status"] == "fail")
        {
            let o = bdi_check(&[
                "trace",
                file.to_str().unwrap(),
                "--finding",
                note["id"].as_str().unwrap(),
            ]);
            assert_eq!(o.status.code(), Some(2), "{dir}");
            assert!(String::from_utf8_lossy(&o.stderr).contains("has no run to replay"));
        }
    }
    let (_, _, file) = verify_json("tests/verify/goal_failure", "trace_sarif");
    let o = bdi_check(&[
        "trace",
        file.to_str().unwrap(),
        "--finding",
        "x",
        "--format",
        "sarif",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

/// `simulate` with these arguments: its exit code, JSON report and the report's file.
fn simulate_json(
    project: &str,
    runs: u32,
    seed: u64,
    tag: &str,
) -> (i32, serde_json::Value, std::path::PathBuf) {
    let (runs, seed) = (runs.to_string(), seed.to_string());
    report_json(
        &["simulate", project, "--runs", &runs, "--seed", &seed],
        tag,
    )
}

/// The errors a report fails with, as `id`s.
fn failed_ids(r: &serde_json::Value) -> std::collections::BTreeSet<String> {
    r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["status"] == "fail" && f["severity"] == "error")
        .map(|f| f["id"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn simulate_finds_only_what_verify_finds_with_runs_that_replay_and_never_passes_early() {
    // Random runs find a subset of verify's errors (never a false one), each with a run
    // that replays; the same seed gives the same report; with runs to spare at every depth
    // the search is the exhaustive one and the report is verify's.
    for dir in [
        "tests/verify/goal_failure",
        "tests/verify/invariant",
        "tests/verify/action_failure",
        "tests/verify/livelock",
        "specs/paper",
    ] {
        let (_, full, _) = verify_json(dir, "simulate_full");
        let mut found = std::collections::BTreeSet::new();
        for seed in 0..4 {
            let (code, r, file) = simulate_json(dir, 1, seed, "simulate");
            let ids = failed_ids(&r);
            assert!(ids.is_subset(&failed_ids(&full)), "{dir}: {ids:?}");
            assert_eq!(code, if ids.is_empty() { 3 } else { 1 }, "{dir}: {r:#}");
            if !ids.is_empty() {
                let o = bdi_check(&["replay", file.to_str().unwrap()]);
                let out = String::from_utf8_lossy(&o.stdout);
                assert!(
                    out.lines().all(|l| l.contains("still reaches")),
                    "{dir}: {out}"
                );
            }
            let (_, again, _) = simulate_json(dir, 1, seed, "simulate_again");
            assert_eq!(r["findings"], again["findings"], "{dir}: seed {seed}");
            found.extend(ids);
        }
        assert!(!found.is_empty(), "{dir}: no seed found a defect");
        let (code, wide, _) = simulate_json(dir, 1_000_000, 0, "simulate_wide");
        assert_eq!(code, full_code(&full), "{dir}");
        assert_eq!(wide["findings"], full["findings"], "{dir}");
        assert_eq!(wide["stats"]["complete"], true, "{dir}");
    }
    // A correct library too large for the runs: no error, and incomplete rather than pass.
    let (code, r, _) = simulate_json("specs/kitchen", 5, 0, "simulate_kitchen");
    assert_eq!(code, 3, "{r:#}");
    assert_eq!(r["verdict"], "incomplete");
    assert!(failed_ids(&r).is_empty(), "{r:#}");
    assert!(r["stats"]["states"].as_u64().unwrap() < 12_006, "{r:#}");
    let (_, other, _) = simulate_json("specs/kitchen", 5, 1, "simulate_kitchen_seed");
    let visited = |r: &serde_json::Value| {
        (
            r["stats"]["states"].clone(),
            r["stats"]["transitions"].clone(),
        )
    };
    assert_ne!(
        visited(&r),
        visited(&other),
        "two seeds followed the same runs"
    );
}

fn full_code(r: &serde_json::Value) -> i32 {
    match r["verdict"].as_str().unwrap() {
        "pass" => 0,
        "fail" => 1,
        "incomplete" => 3,
        _ => 2,
    }
}

#[test]
fn allows_suppress_exactly_the_findings_they_name_and_say_so() {
    // tests/verify/allowed is goal_failure with its two errors accepted by `[[allow]]`:
    // the same findings, the two marked with their reasons, a pass, and the allow that
    // matches nothing reported.
    let (code, r, file) = verify_json("tests/verify/allowed", "allowed");
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["verdict"], "pass");
    let (_, plain, _) = verify_json("tests/verify/goal_failure", "allowed_plain");
    let shape = |r: &serde_json::Value| -> Vec<(String, String, String, String)> {
        let mut v: Vec<_> = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                let s = |k: &str| f[k].as_str().unwrap_or("").to_string();
                (s("check"), s("status"), s("severity"), s("message"))
            })
            .collect();
        v.sort();
        v
    };
    assert_eq!(shape(&r), shape(&plain));
    let suppressed: std::collections::BTreeSet<String> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| !f["suppressed"].is_null())
        .map(|f| f["id"].as_str().unwrap().replace("allowed", "goal_failure"))
        .collect();
    assert_eq!(suppressed, failed_ids(&plain), "{r:#}");
    let warnings = r["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].as_str().unwrap().contains("`deadlock`"),
        "{warnings:?}"
    );
    // A suppressed finding is replayed only when named.
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    // SARIF suppressions, JUnit skipped test cases.
    let sarif = bdi_check(&["verify", "tests/verify/allowed", "--format", "sarif"]);
    let s: serde_json::Value = serde_json::from_slice(&sarif.stdout).unwrap();
    let with_suppressions = s["runs"][0]["results"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|x| x["suppressions"][0]["kind"] == "external")
        .count();
    assert_eq!(with_suppressions, 2);
    let junit = bdi_check(&["verify", "tests/verify/allowed", "--format", "junit"]);
    let j = String::from_utf8_lossy(&junit.stdout);
    assert_eq!(
        j.matches("<skipped message=\"suppressed by [[allow]]")
            .count(),
        2,
        "{j}"
    );
    assert!(j.contains("failures=\"0\""), "{j}");
    // Human output says how many were suppressed.
    let human = bdi_check(&["verify", "tests/verify/allowed"]);
    let text = String::from_utf8_lossy(&human.stdout);
    assert!(text.contains("2 suppressed"), "{text}");
    assert!(
        text.contains("warning: the [[allow]] of `deadlock`"),
        "{text}"
    );
}

#[test]
fn bad_allows_are_bad_input_with_their_place() {
    let base = std::fs::read_to_string("tests/verify/goal_failure/bdi-check.toml").unwrap();
    for (allow, says) in [
        (
            "check = \"nope\"\nwhy = \"x\"",
            "`nope` is not a check bdi-check has",
        ),
        ("check = \"goal-failure\"", "missing"),
        ("check = \"goal-failure\"\nwhy = \" \"", "needs a reason"),
        (
            "check = \"goal-failure\"\nat = \"other.asl:2\"\nwhy = \"x\"",
            "`other.asl` is not a file of the project",
        ),
        (
            "check = \"goal-failure\"\nat = \"agent.asl:two\"\nwhy = \"x\"",
            "is not `file:line`",
        ),
        (
            "check = \"goal-failure\"\nwhy = \"x\"\nwhere = \"x\"",
            "where",
        ),
    ] {
        let dir = temp_dir("bad_allow");
        std::fs::copy("tests/verify/goal_failure/agent.asl", dir.join("agent.asl")).unwrap();
        let manifest = base.replace(
            "../../../specs",
            &format!("{}/specs", env!("CARGO_MANIFEST_DIR")),
        );
        std::fs::write(
            dir.join("bdi-check.toml"),
            format!("{manifest}\n[[allow]]\n{allow}\n"),
        )
        .unwrap();
        for cmd in ["verify", "lint"] {
            let o = bdi_check(&[cmd, dir.to_str().unwrap()]);
            let err = String::from_utf8_lossy(&o.stderr).to_string()
                + &String::from_utf8_lossy(&o.stdout);
            assert_eq!(o.status.code(), Some(2), "{cmd} {allow}: {err}");
            assert!(err.contains(says), "{cmd} {allow}: {err}");
            assert!(err.contains("bdi-check.toml:1"), "{cmd} {allow}: {err}");
        }
    }
}

#[test]
fn a_plan_overlap_a_run_reaches_is_an_error_with_that_run() {
    // lint warns that @runOpenDishwasher and @runClosedDishwasher may both apply; the search
    // reaches such a state with +!runDishwasher selected, so the warning becomes an error
    // whose run replays. The kitchen's other plan pairs are never applicable together.
    let (code, r, _) = verify_json("tests/lint/plan_overlap", "plan-overlap-reached");
    assert_eq!(code, 1, "{r:#}");
    let failing: Vec<&serde_json::Value> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == "plan-overlap" && f["status"] == "fail")
        .collect();
    assert_eq!(failing.len(), 1, "{failing:#?}");
    let f = failing[0];
    assert_eq!(f["severity"], "error");
    assert!(
        f["message"]
            .as_str()
            .unwrap()
            .ends_with("and a run reaches it"),
        "{f:#}"
    );
    // The run to the state where +!runDishwasher meets both plans (`replay` does not
    // replay a plan overlap yet: issue 14's closing note).
    let run = steps(f);
    assert!(run.iter().any(|s| s.contains("runDishwasher")), "{run:#?}");
    // The kitchen, whose two plans exclude each other, has no overlap any run reaches.
    let (code, r, _) = verify_json("specs/kitchen", "plan-overlap-none");
    assert_eq!(code, 0, "{r:#}");
    assert!(r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .all(|f| f["check"] != "plan-overlap" || f["status"] == "pass"));
}

#[test]
fn arithmetic_jason_throws_on_is_refused_where_it_happens() {
    // `5 div 0` throws in Jason (the circumstance is created anew) and `5 mod 0` is NaN:
    // neither is a run of the model, so the search stops there, says where and why, and
    // the verdict is incomplete, never a pass nor a made-up plan failure.
    let (code, r, _) = verify_json("tests/jason/82-belief-update-errors", "arith-beyond");
    assert_eq!(code, 3, "{r:#}");
    let warnings: Vec<&str> = r["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|w| w.as_str())
        .collect();
    let w = warnings
        .iter()
        .find(|w| w.starts_with("a run leaves the model"))
        .unwrap_or_else(|| panic!("{warnings:?}"));
    assert!(w.contains("agent.asl:"), "{w}");
    assert!(
        w.contains("integer division by zero") || w.contains("not a finite number"),
        "{w}"
    );
    assert!(r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .all(|f| f["check"] != "goal-failure" || f["status"] != "fail"));
}

#[test]
fn a_request_goal_may_have_at_most_sixty_four_ground_instances() {
    // Requests are tracked one bit each: 64 instances load, 65 are refused as bad input.
    for (n, want) in [(64usize, 3), (65, 2)] {
        let d = temp_dir(&format!("requests-{n}"));
        let names: Vec<String> = (0..n).map(|i| format!("\"t{i}\"")).collect();
        std::fs::write(d.join("agent.asl"), "+!go(X) <- act(X).\n").unwrap();
        std::fs::write(
            d.join("domain.pddl"),
            "(define (domain d) (:types thing) (:predicates (p ?x - thing))\n\
             (:action act :parameters (?x - thing) :precondition (and) :effect (p ?x)))\n",
        )
        .unwrap();
        std::fs::write(
            d.join("bdi-check.toml"),
            format!(
                "[agent]\nplans = \"agent.asl\"\nactions = \"domain.pddl\"\n\n\
                 [objects]\nthing = [{}]\n\n[initial]\nvary = []\n\n\
                 [requests]\ngoals = [\"go(X)\"]\nmax = 1\n",
                names.join(", ")
            ),
        )
        .unwrap();
        let o = bdi_check(&["verify", d.to_str().unwrap(), "--max-states", "5", "-q"]);
        let out = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(o.status.code(), Some(want), "{n} instances: {out}");
        if want == 2 {
            assert!(out.contains("65 ground instances; at most 64"), "{out}");
        }
        let _ = std::fs::remove_dir_all(&d);
    }
}
