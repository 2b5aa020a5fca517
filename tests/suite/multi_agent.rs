//! Projects of several agents (`.mas2j`, `[[agent]]`): `verify` explores every
//! interleaving of their reasoning cycles; the seeded communication defects are found
//! with runs whose steps name their agents; bad project files are located.

use crate::common;
use common::{agent_steps, bdi_check, temp_dir, verify_json};

fn failing<'a>(r: &'a serde_json::Value, check: &str) -> Vec<&'a serde_json::Value> {
    r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == check && f["status"] == "fail")
        .collect()
}

#[test]
fn the_two_robots_pass_over_every_interleaving() {
    let (code, r, _) = verify_json("specs/two-robots", "two-robots");
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["verdict"], "pass");
    assert_eq!(r["stats"]["complete"], true);
    let find = |check: &str, id: &str| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["check"] == check && f["id"] == id)
            .unwrap_or_else(|| panic!("{check} {id}: {r:#}"))
            .clone()
    };
    for inv in [
        "one_place_each",
        "dishwasher_not_shared",
        "cup_held_or_in_one_place",
    ] {
        assert_eq!(
            find("invariant", &format!("invariant:{inv}"))["status"],
            "pass"
        );
    }
    let reach = find("property", "property:both_cups_loaded");
    assert_eq!(reach["status"], "pass");
    // The run that reaches it has both robots in it, and the message between them.
    let steps = agent_steps(&reach);
    assert!(steps
        .iter()
        .any(|s| s.starts_with("loader action put(loader,cup2)")));
    assert!(steps
        .iter()
        .any(|s| s == "fetcher internal .send(loader,achieve,load(cup1))"));
    assert!(steps
        .iter()
        .any(|s| s == "loader event +!load(cup1)[source(fetcher)]"));
    // Every interleaving: more states than either robot alone could reach in one order.
    assert!(r["stats"]["states"].as_u64().unwrap() > 1000, "{r:#}");
    for check in ["deadlock", "action-failure", "goal-failure"] {
        assert!(failing(&r, check).is_empty(), "{check}: {r:#}");
    }
}

#[test]
fn a_wait_for_an_event_that_came_already_is_a_deadlock() {
    let (code, r, _) = verify_json("tests/verify/mas-lost-wakeup", "lost-wakeup");
    assert_eq!(code, 1, "{r:#}");
    let d = failing(&r, "deadlock");
    assert_eq!(d.len(), 1, "{r:#}");
    assert!(d[0]["message"].as_str().unwrap().contains("`loader`"));
    let steps = agent_steps(d[0]);
    // The shortest run: the second request's plan is chosen while busy, the first
    // intention removes `busy` (its event passes), and only then does the wait begin.
    let at = |s: &str| {
        steps
            .iter()
            .position(|x| x == s)
            .unwrap_or_else(|| panic!("{s}: {steps:#?}"))
    };
    let removed = at("loader event -busy");
    let waits = at("loader internal .wait({-busy})");
    assert!(removed < waits, "{steps:#?}");
    assert_eq!(waits, steps.len() - 1, "the run ends where the wait starts");
}

#[test]
fn two_intentions_that_test_before_either_sets_busy_collide() {
    let (code, r, _) = verify_json("tests/verify/mas-race", "race");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "action-failure");
    assert_eq!(f.len(), 1, "{r:#}");
    assert!(f[0]["message"]
        .as_str()
        .unwrap()
        .starts_with("`openDoor(loader)` of agent `loader`"));
    let steps = agent_steps(f[0]);
    let plans: Vec<usize> = steps
        .iter()
        .enumerate()
        .filter(|(_, s)| *s == "loader plan +!stowAll")
        .map(|(i, _)| i)
        .collect();
    let sets: Vec<usize> = steps
        .iter()
        .enumerate()
        .filter(|(_, s)| *s == "loader belief +busy")
        .map(|(i, _)| i)
        .collect();
    // The last two choices of the plan both come before the last `+busy` pair.
    assert!(plans.len() >= 3 && sets.len() >= 3, "{steps:#?}");
    let (p, q) = (plans[plans.len() - 2], plans[plans.len() - 1]);
    assert!(
        p < sets[sets.len() - 2] && q < sets[sets.len() - 2],
        "{steps:#?}"
    );
    assert_eq!(failing(&r, "goal-failure").len(), 2, "{r:#}");
}

#[test]
fn instances_are_named_as_jason_names_them_and_see_their_sender() {
    let (code, r, _) = verify_json("tests/verify/mas-list", "mas-list");
    assert_eq!(code, 0, "{r:#}");
    let reach = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "property:all_answered")
        .unwrap();
    assert_eq!(reach["status"], "pass");
    let steps = agent_steps(reach);
    for k in 1..=3 {
        assert!(steps.contains(&format!("pinger{k} internal .send(ponger,achieve,ping)")));
        assert!(steps.contains(&format!("ponger event +!ping[source(pinger{k})]")));
        assert!(steps.contains(&format!("ponger action pong(pinger{k})")));
    }
    // An action no plan of one agent calls is still used by another.
    assert!(failing(&r, "unused-action").is_empty(), "{r:#}");
}

/// A project folder with these files.
fn project(name: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let d = temp_dir(name);
    for (f, text) in files {
        std::fs::write(d.join(f), text).unwrap();
    }
    d
}

const DOMAIN: &str = "(define (domain d) (:requirements :strips) (:predicates (p)) (:action a :parameters () :precondition () :effect (p)))";

fn verify_error(d: &std::path::Path) -> String {
    let o = bdi_check(&["verify", d.to_str().unwrap(), "--color", "never"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

#[test]
fn bad_project_files_are_refused_where_written() {
    let toml = "[agent]\nmas = \"p.mas2j\"\nactions = \"d.pddl\"\n";
    let syntax = project(
        "mas-syntax",
        &[
            ("bdi-check.toml", toml),
            ("d.pddl", DOMAIN),
            ("p.mas2j", "MAS p {\n  agents: a b\n}\n"),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&syntax);
    assert!(out.contains("p.mas2j:3:1"), "{out}");
    assert!(out.contains("expected `;`"), "{out}");
    let option = project(
        "mas-option",
        &[
            ("bdi-check.toml", toml),
            ("d.pddl", DOMAIN),
            ("p.mas2j", "MAS p { agents: a [intBels=newFocus]; }"),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&option);
    assert!(out.contains("`intBels=newFocus`"), "{out}");
    assert!(out.contains("p.mas2j:1:20"), "{out}");
    let missing = project(
        "mas-missing",
        &[
            ("bdi-check.toml", toml),
            ("d.pddl", DOMAIN),
            ("p.mas2j", "MAS p { agents: a; bob; }"),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&missing);
    assert!(
        out.contains("the source of agent `bob`, `bob.asl`, does not exist"),
        "{out}"
    );
    assert!(out.contains("p.mas2j:1:20"), "{out}");
    let no_actions = project(
        "mas-no-actions",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\n",
            ),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&no_actions);
    assert!(out.contains("missing key `actions` in [[agent]]"), "{out}");
    let twice = project(
        "mas-twice",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\ninstances = 2\n[[agent]]\nname = \"a1\"\nplans = \"a.asl\"\n",
            ),
            ("d.pddl", DOMAIN),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&twice);
    assert!(out.contains("two agents are named `a1`"), "{out}");
}

#[test]
fn messages_follow_jason_where_one_agent_runs_alone() {
    // A receiver nobody is named after: `.send` fails as `LocalAgArch.sendMsg` does.
    let d = project(
        "send-unknown",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[agent]]\nname = \"b\"\nplans = \"b.asl\"\n",
            ),
            ("d.pddl", DOMAIN),
            ("a.asl", "!g.\n+!g <- .send(c, achieve, h).\n"),
            ("b.asl", "+!h <- a.\n"),
        ],
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "send-unknown-report");
    assert_eq!(code, 1, "{r:#}");
    let g = failing(&r, "goal-failure");
    assert_eq!(g.len(), 1, "{r:#}");
    assert!(
        g[0]["message"]
            .as_str()
            .unwrap()
            .contains("receiver_not_found"),
        "{r:#}"
    );
}

#[test]
fn counterexamples_replay_until_the_defect_is_fixed() {
    for case in ["mas-lost-wakeup", "mas-race"] {
        // A copy, to fix afterwards.
        let d = temp_dir(&format!("{case}-fix"));
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/verify")
            .join(case);
        for e in std::fs::read_dir(&src).unwrap().flatten() {
            std::fs::copy(e.path(), d.join(e.file_name())).unwrap();
        }
        let (code, r, file) = verify_json(d.to_str().unwrap(), &format!("{case}-report"));
        assert_eq!(code, 1, "{r:#}");
        let failed = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["status"] == "fail" && f["severity"] == "error")
            .filter(|f| f["suppressed"].is_null())
            .count();
        assert!(failed >= 1);
        let o = bdi_check(&["replay", file.to_str().unwrap()]);
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        assert_eq!(
            o.status.code(),
            Some(1),
            "{out}{}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(
            out.matches("still reaches its violation").count(),
            failed,
            "{out}"
        );
        // The loader of specs/two-robots has neither defect.
        std::fs::copy(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/two-robots/loader.asl"),
            d.join("loader.asl"),
        )
        .unwrap();
        let o = bdi_check(&["replay", file.to_str().unwrap()]);
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        assert_eq!(o.status.code(), Some(0), "{out}");
        assert_eq!(
            out.matches("no longer reaches its violation").count(),
            failed,
            "{out}"
        );
    }
}

#[test]
fn formulas_name_an_agent_for_its_beliefs() {
    let d = temp_dir("mas-namespaces");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verify/mas-lost-wakeup");
    for e in std::fs::read_dir(&src).unwrap().flatten() {
        std::fs::copy(e.path(), d.join(e.file_name())).unwrap();
    }
    let base = std::fs::read_to_string(d.join("bdi-check.toml")).unwrap();
    let with = |extra: &str| {
        std::fs::write(d.join("bdi-check.toml"), format!("{base}\n{extra}\n")).unwrap();
    };
    with(
        r#"[[property]]
name = "loader_gets_busy"
reachable = "loader::busy"

[[property]]
name = "fetcher_never_busy"
always = "not fetcher::busy"

[[property]]
name = "loader_lags"
always = "loader::at(loader, L) | not at(loader, L)""#,
    );
    let (code, r, file) = verify_json(d.to_str().unwrap(), "mas-namespaces-report");
    assert_eq!(code, 1, "{r:#}");
    let status = |id: &str| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == id)
            .map(|f| f["status"].as_str().unwrap().to_string())
            .unwrap_or_else(|| panic!("{id}: {r:#}"))
    };
    assert_eq!(status("property:loader_gets_busy"), "pass");
    assert_eq!(status("property:fetcher_never_busy"), "pass");
    // An agent believes where it is only from its next sense on: right after it moves,
    // the world has changed and its belief has not.
    assert_eq!(status("property:loader_lags"), "fail");
    let (rc, out) = common::replay_finding(&file, "property:loader_lags");
    assert_eq!(rc, 1, "{out}");
    // A mental note without its agent, and a namespace no agent has, are bad input.
    with("[[property]]\nname = \"p\"\nreachable = \"busy\"");
    let out = verify_error(&d);
    assert!(
        out.contains(
            "`busy` is a mental note: in a project of several agents, name whose (`agent::busy`)"
        ),
        "{out}"
    );
    with("[[property]]\nname = \"p\"\nreachable = \"robot3::busy\"");
    let out = verify_error(&d);
    assert!(
        out.contains("a namespace in a formula names an agent: one of `fetcher`, `loader`"),
        "{out}"
    );
    // In a project of one agent, a namespace is refused, not read as the belief itself.
    let one = project(
        "one-agent-namespace",
        &[
            (
                "bdi-check.toml",
                "[agent]\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[property]]\nname = \"p\"\nreachable = \"a::p\"\n",
            ),
            ("d.pddl", DOMAIN),
            ("a.asl", "!g.\n+!g <- a.\n"),
        ],
    );
    let out = verify_error(&one);
    assert!(
        out.contains("a namespace in a formula names an agent, and this project has one"),
        "{out}"
    );
}

#[test]
fn parse_reads_a_jason_project_and_its_agents() {
    let o = bdi_check(&["parse", "specs/two-robots/two-robots.mas2j"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(
        out.contains("fetcher.asl") && out.contains("loader.asl"),
        "{out}"
    );
    let d = project("parse-mas", &[("p.mas2j", "MAS p { agents: a #0; }")]);
    let o = bdi_check(&[
        "parse",
        d.join("p.mas2j").to_str().unwrap(),
        "--color",
        "never",
    ]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned() + &String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("p.mas2j:1:20") && err.contains("from 1 to 64 instances"),
        "{err}"
    );
}

#[test]
fn lint_findings_are_settled_against_the_runs() {
    let of = |r: &serde_json::Value, check: &str| -> Vec<serde_json::Value> {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["check"] == check)
            .cloned()
            .collect()
    };
    // Reached: the race's failing precondition is an error with the run that fails it.
    let (_, r, _) = verify_json("tests/verify/mas-race", "settle-race");
    let pre: Vec<_> = of(&r, "precondition")
        .into_iter()
        .filter(|f| f["severity"] == "error")
        .collect();
    assert_eq!(pre.len(), 1, "{r:#}");
    assert!(pre[0]["message"]
        .as_str()
        .unwrap()
        .ends_with("— and a run reaches it"));
    assert!(!agent_steps(&pre[0]).is_empty());
    // Never reached, every state explored: the two robots' lint warnings are notes.
    let (_, r, _) = verify_json("specs/two-robots", "settle-robots");
    for check in ["precondition", "coverage-gap", "action-breaks-invariant"] {
        for f in of(&r, check).iter().filter(|f| f["status"] == "fail") {
            assert_eq!(f["severity"], "note", "{f:#}");
        }
    }
    // Undecided by lint (source annotations), decided by a run that adopts the plan.
    let (code, r, _) = verify_json("tests/jason-mas/tell", "settle-tell");
    assert_eq!(code, 0, "{r:#}");
    let dead = of(&r, "dead-plan");
    assert!(dead.iter().all(|f| f["status"] == "pass"), "{r:#}");
    assert!(dead
        .iter()
        .any(|f| f["message"].as_str().unwrap().ends_with("a run adopts it")));
}

/// A collector and `n` workers: each worker takes four cycles of its own (adopt the plan,
/// three mental notes), then tells the collector it is done. `extra` goes into the
/// manifest, `step` is the worker's third step.
/// Every project of several agents among the verify cases (`tests/verify/mas-*`).
fn seeded_projects() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verify");
    let mut out: Vec<std::path::PathBuf> = std::fs::read_dir(&root)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("mas-"))
        })
        .collect();
    out.sort();
    out
}

fn workers(tag: &str, n: usize, step: &str, extra: &str) -> std::path::PathBuf {
    project(
        tag,
        &[
            (
                "bdi-check.toml",
                &format!(
                    "[[agent]]\nname = \"collector\"\nplans = \"collector.asl\"\nactions = \"d.pddl\"\n\n[[agent]]\nname = \"worker\"\nplans = \"worker.asl\"\ninstances = {n}\n{extra}"
                ),
            ),
            ("d.pddl", DOMAIN),
            (
                "worker.asl",
                &format!("!work.\n+!work <- +step1; +step2; {step}; .send(collector, tell, done).\n"),
            ),
            ("collector.asl", "+done[source(A)] <- .print(A).\n"),
        ],
    )
}

/// Each failing and passing finding as `check id status severity`, sorted.
fn verdicts(r: &serde_json::Value) -> Vec<String> {
    let mut v: Vec<String> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            format!(
                "{} {} {} {}",
                f["check"], f["id"], f["status"], f["severity"]
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn partial_order_reduction_keeps_every_finding_and_its_runs_replay() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs: Vec<std::path::PathBuf> = vec![root.join("specs/two-robots")];
    dirs.extend(seeded_projects());
    let local = [
        workers("por-pass", 3, "+step3", ""),
        // Visible: the collector's belief is in an invariant.
        workers(
            "por-invariant",
            3,
            "+step3",
            "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
        ),
        // A goal failure in a step of each worker's own.
        workers("por-goal", 2, "?step4", ""),
    ];
    dirs.extend(local.iter().cloned());
    for (i, d) in dirs.iter().enumerate() {
        let tag = format!("por-{i}");
        let (code, reduced, file) = verify_json(d.to_str().unwrap(), &tag);
        let (full_code, full, _) = common::report_json(
            &["verify", d.to_str().unwrap(), "--no-partial-order"],
            &format!("{tag}-full"),
        );
        let at = d.display();
        assert_eq!(code, full_code, "{at}");
        assert_eq!(verdicts(&reduced), verdicts(&full), "{at}");
        let states = |r: &serde_json::Value| r["stats"]["states"].as_u64().unwrap();
        assert!(states(&reduced) <= states(&full), "{at}");
        if code == 0 && local.contains(d) {
            assert!(states(&reduced) < states(&full), "{at}: nothing reduced");
        }
        // A violation found is searched again over every interleaving, for the shortest
        // runs.
        if code == 1 {
            assert_eq!(reduced["findings"], full["findings"], "{at}");
        }
        if code == 1 {
            let failed = reduced["findings"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|f| f["status"] == "fail" && f["severity"] == "error")
                .filter(|f| f["suppressed"].is_null())
                .count();
            let o = bdi_check(&["replay", file.to_str().unwrap()]);
            let out = String::from_utf8_lossy(&o.stdout).into_owned();
            assert_eq!(o.status.code(), Some(1), "{at}: {out}");
            assert_eq!(
                out.matches("still reaches its violation").count(),
                failed,
                "{at}: {out}"
            );
        }
    }
}

#[test]
fn partial_order_reduction_finds_what_the_full_search_finds() {
    use bdi_check::check::{explore::Limits, system::verify_system, VerifyOptions};
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = seeded_projects();
    dirs.extend([
        workers(
            "por-lib-invariant",
            3,
            "+step3",
            "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
        ),
        workers("por-lib-goal", 3, "?step4", ""),
    ]);
    let limits = Limits {
        max_states: 1_000_000,
        max_depth: 10_000,
        timeout: None,
    };
    for d in &dirs {
        let projects = bdi_check::model::project::load_system(d).expect("the project loads");
        let run = |partial_order| {
            let opts = VerifyOptions {
                threads: 2,
                partial_order,
                ..VerifyOptions::default()
            };
            verify_system(&projects, limits, &opts, |_, _, _, _| {}, Vec::new()).expect("verifies")
        };
        let (reduced, full) = (run(true), run(false));
        let key = |v: &bdi_check::check::Verification| {
            let mut k: Vec<String> = v
                .findings
                .iter()
                .map(|f| format!("{} {} {:?} {:?}", f.check, f.id, f.status, f.severity))
                .collect();
            k.sort();
            k
        };
        assert_eq!(key(&reduced), key(&full), "{}", d.display());
        assert!(reduced.stats.complete && full.stats.complete);
        assert_eq!(full.reduced_states, 0);
        if !d.starts_with(root) {
            assert!(reduced.stats.states < full.stats.states, "{}", d.display());
        }
        // Every violation comes with a run: the reduced search's runs are real ones, if
        // not always the shortest.
        for f in &reduced.findings {
            if f.status == bdi_check::findings::Status::Fail && f.counterexample.is_some() {
                let g = full
                    .findings
                    .iter()
                    .find(|g| g.check == f.check && g.id == f.id)
                    .expect("the full search has it");
                let len = |x: &bdi_check::findings::Finding| {
                    x.counterexample.as_ref().map_or(0, |c| c.steps.len())
                };
                assert!(len(f) >= len(g), "{}: {}", d.display(), f.id);
            }
        }
    }
}

#[test]
fn a_reduced_run_stands_with_a_warning_when_the_full_search_is_cut_short() {
    let d = workers(
        "por-bounded",
        3,
        "+step3",
        "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
    );
    // The reduced search needs 47 states, every interleaving 236 (without symmetry over
    // the workers, which would merge most of them).
    let (code, r, _) = common::report_json(
        &[
            "verify",
            d.to_str().unwrap(),
            "--max-states",
            "100",
            "--no-symmetry",
        ],
        "por-bounded-report",
    );
    assert_eq!(code, 1, "{r:#}");
    assert_eq!(failing(&r, "invariant").len(), 1, "{r:#}");
    assert_eq!(r["stats"]["states"], 47, "{r:#}");
    let warned = r["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w.as_str().unwrap().contains("longer than the shortest"));
    assert!(warned, "{r:#}");
    // Unbounded, the full search's shortest run stands, without the warning.
    let (_, full, _) = common::report_json(
        &["verify", d.to_str().unwrap(), "--no-symmetry"],
        "por-unbounded",
    );
    assert_eq!(full["stats"]["states"], 236, "{full:#}");
    assert!(full.get("warnings").is_none(), "{full:#}");
}

/// Runs a project of several agents round-robin (one cycle of each agent in turn, as the
/// Jason lab's driver does) for `rounds` rounds; returns what the agents printed
/// (`agent: text`), the final state, and the system's agent names.
fn round_robin(
    d: &std::path::Path,
    rounds: usize,
) -> (Vec<String>, bdi_check::semantics::SystemState) {
    use bdi_check::semantics::{Note, System};
    let agents = bdi_check::model::project::load_system(d)
        .unwrap_or_else(|e| panic!("{}: {:?}", d.display(), e.diagnostics));
    let system = System::new(&agents).expect("the system");
    let names = system.names().to_vec();
    let start = system.initial_states().remove(0);
    let schedule: Vec<usize> = (0..rounds).flat_map(|_| 0..names.len()).collect();
    let steps = bdi_check::check::system::run_schedule(&system, start.clone(), &[], &schedule, &[]);
    let mut state = start;
    let mut printed = Vec::new();
    for st in &steps {
        // Follow the run to its end state (a cycle that shows nothing may still post a
        // subgoal; one in which the agent had nothing to do changes nothing).
        let k = st.agent as usize;
        let outcomes = if system.enabled(&state, k) {
            system.cycle_of(&state, k)
        } else {
            Vec::new()
        };
        if let Some((_, next)) = outcomes.into_iter().find(|(s, _)| s.notes == st.notes) {
            state = next;
        } else {
            assert!(st.notes.is_empty(), "no step {:?} of {k}", st.notes);
        }
        for n in &st.notes {
            if let Note::Printed(t) = n {
                printed.push(format!("{}: {t}", names[st.agent as usize]));
            }
        }
    }
    (printed, state)
}

/// A project of two agents, `a` (first, with the domain's action `a`) and `b`.
fn two_agents(name: &str, a: &str, b: &str) -> std::path::PathBuf {
    project(
        name,
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[agent]]\nname = \"b\"\nplans = \"b.asl\"\n[objects]\nobject = [\"k1\", \"k2\", \"yes\", \"no\"]\n",
            ),
            ("d.pddl", DOMAIN),
            ("a.asl", a),
            ("b.asl", b),
        ],
    )
}

#[test]
fn asks_are_answered_as_jasons_plans_for_messages_answer_them() {
    // From a belief: the answer carries the receiver's source.
    let d = two_agents(
        "ask-belief",
        "!g.\n+!g <- .send(b, askOne, price(X), A); .print(A); .send(b, askOne, price(Y), price(Y)); .print(Y).\n",
        "price(k1).\n",
    );
    let (printed, _) = round_robin(&d, 12);
    assert_eq!(printed, ["a: price(k1)[source(b)]", "a: k1"]);
    // From a `+?` plan, and `false` when nothing answers (`untell`).
    let d = two_agents(
        "ask-test-goal",
        "!g.\n+!g <- .send(b, askOne, q(X), A); .print(A); .send(b, askOne, r(Y), B); .print(B).\n",
        "+?q(k2).\n",
    );
    let (printed, _) = round_robin(&d, 20);
    assert_eq!(printed, ["a: q(k2)[source(b)]", "a: false"]);
    // An answer that does not unify with the fourth argument fails the goal (`ask_failed`).
    let d = two_agents(
        "ask-failed",
        "!g.\n+!g <- .send(b, askOne, q(X), q(X)); .print(X).\n-!g[error(E)] <- .print(E).\n",
        "\n",
    );
    let (printed, _) = round_robin(&d, 20);
    assert_eq!(printed, ["a: ask_failed"]);
    // askAll: every belief, in the receiver's belief-base order.
    let d = two_agents(
        "ask-all",
        "!g.\n+!g <- .send(b, askAll, item(X), L); .print(L); .send(b, askAll, none(X), N); .print(N).\n",
        "item(k1).\nitem(k2).\n",
    );
    let (printed, _) = round_robin(&d, 20);
    assert_eq!(
        printed,
        ["a: [item(k1)[source(b)],item(k2)[source(b)]]", "a: []"]
    );
    // Without an answer variable, the answer is told: a belief of the asker.
    let d = two_agents(
        "ask-async",
        "!g.\n+!g <- .send(b, askOne, price(X)).\n+price(P)[source(b)] <- .print(P).\n",
        "price(k2).\n",
    );
    let (printed, _) = round_robin(&d, 12);
    assert_eq!(printed, ["a: k2"]);
}

#[test]
fn an_ask_nobody_answers_times_out_or_waits_for_ever() {
    // No applicable `+?` plan: Jason's plans for messages print a communication error and
    // send nothing.
    let d = two_agents(
        "ask-timeout",
        "!g.\n+!g <- .send(b, askOne, q(X), A, 100); .print(A).\n",
        "+?q(k1) : p.\n",
    );
    let (printed, state) = round_robin(&d, 20);
    // The timer fires once no agent has anything else to do (the lab's clock).
    assert_eq!(
        printed,
        [
            "b: Communication error -- no_applicable: Found a goal for which there is no applicable plan: +?q(X)[source(a)]",
            "a: timeout"
        ]
    );
    assert!(state.agents[0].waiting.is_empty());
    let (code, r, _) = verify_json(d.to_str().unwrap(), "ask-timeout-report");
    assert_eq!(code, 0, "{r:#}");
    // Without a timeout, the asker waits for ever: a deadlock of that agent, at its `.send`.
    let d = two_agents(
        "ask-forever",
        "!g.\n+!g <- .send(b, askOne, q(X), A); .print(A).\n",
        "+?q(k1) : p.\n",
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "ask-forever-report");
    assert_eq!(code, 1, "{r:#}");
    let d = failing(&r, "deadlock");
    assert_eq!(d.len(), 1, "{r:#}");
    assert_eq!(d[0]["id"], "deadlock:a");
    assert_eq!(d[0]["location"]["line"], 2);
    assert!(
        d[0]["message"]
            .as_str()
            .unwrap()
            .contains("waits for the answer to `.send(b, askOne, q(X), A)`"),
        "{r:#}"
    );
}

#[test]
fn untell_and_unachieve_go_through_jasons_plans_for_messages() {
    // untell: the sender's source goes, and the belief with it when it had no other.
    let d = two_agents(
        "untell",
        "!g.\n+!g <- .send(b, tell, t(k1)); .send(b, tell, t(k2)); .send(b, untell, t(k1)); .send(b, untell, t(k2)).\n",
        "t(k2).\n+t(X)[source(a)] <- .print(\"+\", X).\n-t(X)[source(a)] <- .print(\"-\", X).\n",
    );
    let (printed, state) = round_robin(&d, 20);
    assert_eq!(printed, ["b: +k1", "b: +k2", "b: -k1", "b: -k2"]);
    // t(k2) stays, of b's own; t(k1) is gone.
    let p = &bdi_check::model::project::load_system(&d).unwrap()[1];
    let believed: Vec<String> = state.agents[1]
        .beliefs
        .iter()
        .map(|a| p.atoms.display(a, &p.universe))
        .collect();
    assert_eq!(believed, ["t(k2)"]);
    assert!(state.agents[1].told.is_empty());
    // unachieve: the goal is dropped before its plan ends.
    let d = two_agents(
        "unachieve",
        "!g.\n+!g <- .send(b, achieve, long); .send(b, unachieve, long).\n",
        "+!long <- .print(1); .print(2); .print(3); .print(4); .print(5).\n",
    );
    let (printed, state) = round_robin(&d, 20);
    assert!(!printed.is_empty() && printed.len() < 5, "{printed:?}");
    assert!(state.agents[1].intentions.is_empty());
}

#[test]
fn an_ask_that_can_go_unanswered_is_found_and_replays_until_answered() {
    let d = temp_dir("mas-unanswered-fix");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verify/mas-unanswered");
    for e in std::fs::read_dir(&src).unwrap().flatten() {
        std::fs::copy(e.path(), d.join(e.file_name())).unwrap();
    }
    let (code, r, file) = verify_json(d.to_str().unwrap(), "mas-unanswered-report");
    assert_eq!(code, 1, "{r:#}");
    let dl = failing(&r, "deadlock");
    assert_eq!(dl.len(), 1, "{r:#}");
    assert_eq!(dl[0]["id"], "deadlock:fetcher");
    assert!(dl[0]["location"]["file"]
        .as_str()
        .unwrap()
        .ends_with("/fetcher.asl"));
    assert_eq!(dl[0]["location"]["line"], 10);
    let steps = agent_steps(dl[0]);
    // The question comes while the loader loads the first cup: no `+?free` plan applies,
    // Jason's plans for messages report it, and the loader goes on without answering.
    let at = |s: &str| {
        steps
            .iter()
            .position(|x| x.starts_with(s))
            .unwrap_or_else(|| panic!("{s}: {steps:#?}"))
    };
    let opened = at("loader action openDoor(loader)");
    let failed = at("loader event -!kqml_received(fetcher,askOne,free(A),samid0)");
    assert!(opened < failed, "{steps:#?}");
    assert!(steps[failed + 1].ends_with("@kqmlError"), "{steps:#?}");
    // The run ends in the loop the loader is left in.
    assert!(dl[0]["counterexample"]["loop_start"].is_u64(), "{r:#}");
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        out.contains("deadlock:fetcher: still reaches its violation"),
        "{out}"
    );
    // Answered in both cases, the question no longer waits.
    let loader = std::fs::read_to_string(d.join("loader.asl")).unwrap();
    std::fs::write(
        d.join("loader.asl"),
        loader.replace(
            "+?free(yes) : door(closed).",
            "+?free(yes) : door(closed).\n+?free(no) : door(open).",
        ),
    )
    .unwrap();
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(
        out.contains("deadlock:fetcher: no longer reaches its violation"),
        "{out}"
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "mas-unanswered-fixed");
    assert_eq!(code, 0, "{r:#}");
}

#[test]
fn a_tell_that_arrives_after_the_receiver_acted_is_found() {
    let (code, r, file) = verify_json("tests/verify/mas-late-tell", "mas-late-tell");
    assert_eq!(code, 1, "{r:#}");
    let inv = failing(&r, "invariant");
    assert_eq!(inv.len(), 1, "{r:#}");
    assert_eq!(inv[0]["id"], "invariant:counter_not_shared");
    let steps = agent_steps(inv[0]);
    let last = |s: &str| {
        steps
            .iter()
            .rposition(|x| x.starts_with(s))
            .unwrap_or_else(|| panic!("{s}: {steps:#?}"))
    };
    // The fetcher looked (no `atCounter`) and moved before the loader's tell was sent, and
    // the loader moved without waiting for it to be read.
    let fetcher_moved = last("fetcher action move(fetcher,counter)");
    let told = last("loader internal .send(fetcher,tell,atCounter)");
    let loader_moved = last("loader action move(loader,counter)");
    assert!(fetcher_moved < told && told < loader_moved, "{steps:#?}");
    assert_eq!(loader_moved, steps.len() - 1, "{steps:#?}");
    assert!(!steps
        .iter()
        .any(|s| s.starts_with("fetcher event message from loader")));
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        out.contains("invariant:counter_not_shared: still reaches its violation"),
        "{out}"
    );
}

/// A ping-pong of one ponger and `n` pingers (`pinger1` ... `pingerN`, objects of the PDDL
/// model too): each pinger asks the ponger to `pong` it. `pinger` and `ponger` are their
/// plans, `extra` goes into the manifest.
fn ping_pong(tag: &str, n: usize, pinger: &str, ponger: &str, extra: &str) -> std::path::PathBuf {
    let names: Vec<String> = (1..=n).map(|i| format!("\"pinger{i}\"")).collect();
    let all: Vec<String> = (1..=n).map(|i| format!("ponged(pinger{i})")).collect();
    project(
        tag,
        &[
            (
                "bdi-check.toml",
                &format!(
                    "[[agent]]\nname = \"ponger\"\nplans = \"ponger.asl\"\nactions = \"ping.pddl\"\n\n[[agent]]\nname = \"pinger\"\nplans = \"pinger.asl\"\ninstances = {n}\n\n[objects]\nagent = [\"ponger\", {}]\n\n[invariants]\nno_pong_for_the_ponger = \"not ponged(ponger)\"\n\n[[property]]\nname = \"all_answered\"\nreachable = \"{}\"\n{extra}",
                    names.join(", "),
                    all.join(" & ")
                ),
            ),
            (
                "ping.pddl",
                "(define (domain ping) (:requirements :strips :typing) (:types agent) (:predicates (ponged ?a - agent)) (:action pong :parameters (?a - agent) :precondition (not (ponged ?a)) :effect (ponged ?a)))",
            ),
            ("pinger.asl", pinger),
            ("ponger.asl", ponger),
        ],
    )
}

const PINGER: &str = "!start.\n+!start <- .send(ponger, achieve, ping).\n";
const PONGER: &str = "+!ping[source(A)] <- pong(A).\n";

/// A finding as `check id status severity message steps`, with the names of instances
/// (`pinger2`, `worker3`) written as their agent's (`pinger#`): symmetry may show another
/// instance's run of the same length, as its message says.
fn masked(r: &serde_json::Value) -> Vec<String> {
    let mut v: Vec<String> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let steps = f["counterexample"]["steps"]
                .as_array()
                .map_or(0, |s| s.len());
            let mut m = f["message"].as_str().unwrap_or("").to_string();
            for agent in ["pinger", "worker", "recv", "teller"] {
                for k in (1..=9).rev() {
                    m = m.replace(&format!("{agent}{k}"), &format!("{agent}#"));
                }
            }
            // A condition that holds says in how many states.
            if let Some(at) = m.find(" holds in all ") {
                m.truncate(at);
            }
            format!(
                "{} {} {} {} {m} {steps}",
                f["check"], f["id"], f["status"], f["severity"]
            )
        })
        .collect();
    v.sort();
    v
}

/// Every project of several agents the tests know: the repository's, and generated ones
/// with instances that pass, break an invariant, fail goals and actions, and deadlock.
/// `tag` sets the generated projects' folders apart (tests run side by side).
fn multi_agent_projects(tag: &str) -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs: Vec<std::path::PathBuf> = vec![root.join("specs/two-robots")];
    for case in ["mas-lost-wakeup", "mas-race", "mas-list"] {
        dirs.push(root.join("tests/verify").join(case));
    }
    for case in [
        "ping-pong",
        "send-errors",
        "tell",
        "two-robots",
        "tell-how",
        "tell-how-sources",
    ] {
        dirs.push(root.join("tests/jason-mas").join(case));
    }
    dirs.extend([
        workers(&format!("{tag}-sym-pass"), 3, "+step3", ""),
        workers(
            &format!("{tag}-sym-invariant"),
            3,
            "+step3",
            "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
        ),
        workers(&format!("{tag}-sym-goal"), 3, "?step4", ""),
        // Each pinger asks twice: the second `pong` of a pinger fails its precondition.
        ping_pong(
            &format!("{tag}-sym-action"),
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping); .send(ponger, achieve, ping).\n",
            PONGER,
            "",
        ),
        // Each pinger waits for an answer that never comes.
        ping_pong(
            &format!("{tag}-sym-deadlock"),
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping); .wait({+never}).\n+!stop <- +never.\n",
            PONGER,
            "",
        ),
        // The ponger serves the first pinger only: the others wait for ever, which ones
        // depending on the run (so the search must follow each pinger's identity).
        ping_pong(
            &format!("{tag}-sym-first-served"),
            3,
            "!start.\n+!start <- .my_name(Me); .send(ponger, achieve, ping); .wait(ponged(Me)).\n",
            "+!ping[source(A)] : not served <- +served; pong(A).\n+!ping[source(A)] : served.\n",
            "",
        ),
        // The ponger serves two pingers: the third waits for ever, one of the three
        // depending on the run; the two served go on (each asks twice).
        ping_pong(
            &format!("{tag}-sym-two-served"),
            3,
            "!start.\n+!start <- .my_name(Me); .send(ponger, achieve, ping); .wait(ponged(Me)); .send(ponger, achieve, bye).\n",
            "count(0).\n+!ping[source(A)] : count(N) & N < 2 <- -+count(N + 1); pong(A).\n+!ping[source(A)] : count(2).\n+!bye.\n",
            "\n[bounds]\nnumbers = [0, 2]\n",
        ),
        // Every pinger is answered in the end: checked on the reduced graph, which has no
        // loop.
        ping_pong(
            &format!("{tag}-sym-eventually"),
            3,
            PINGER,
            PONGER,
            "\n[[property]]\nname = \"each_answered\"\neventually = \"ponged(pinger1) & ponged(pinger2) & ponged(pinger3)\"\n",
        ),
        // Each pinger looks for its pong every 100 ms, for ever when the ponger serves
        // only the first: loops, so the checks of runs that go on for ever search every
        // interleaving again.
        ping_pong(
            &format!("{tag}-sym-polling"),
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping); !look.\n+!look : .my_name(Me) & not ponged(Me) <- .wait(100); !look.\n+!look.\n",
            "+!ping[source(A)] : not served <- +served; pong(A).\n+!ping[source(A)] : served.\n",
            "\n[[property]]\nname = \"each_answered\"\neventually = \"ponged(pinger1) & ponged(pinger2) & ponged(pinger3)\"\n",
        ),
        // The ponger tells each pinger; each pinger tells the others it was answered.
        ping_pong(
            &format!("{tag}-sym-tell"),
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping).\n+answered[source(ponger)] <- .my_name(Me); .broadcast(tell, heard(Me)).\n",
            "+!ping[source(A)] <- pong(A); .send(A, tell, answered).\n",
            "",
        ),
    ]);
    dirs
}

#[test]
fn symmetry_over_instances_keeps_every_finding_and_its_runs_replay() {
    for (i, d) in multi_agent_projects("same").iter().enumerate() {
        let at = d.display();
        let path = d.to_str().unwrap();
        for por in [&[][..], &["--no-partial-order"][..]] {
            let tag = format!("sym-{i}-{}", por.len());
            let mut args = vec!["verify", path];
            args.extend(por);
            let (code, sym, file) = common::report_json(&args, &tag);
            args.push("--no-symmetry");
            let (full_code, full, _) = common::report_json(&args, &format!("{tag}-full"));
            assert_eq!(code, full_code, "{at} {por:?}");
            assert_eq!(verdicts(&sym), verdicts(&full), "{at} {por:?}");
            assert_eq!(masked(&sym), masked(&full), "{at} {por:?}");
            let states = |r: &serde_json::Value| r["stats"]["states"].as_u64().unwrap();
            assert!(states(&sym) <= states(&full), "{at}");
            if code == 1 {
                let failed = sym["findings"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .filter(|f| f["status"] == "fail" && f["counterexample"].is_object())
                    .filter(|f| f["suppressed"].is_null())
                    .filter(|f| f["severity"] == "error")
                    // Lint's own witness is a state, not a run: replay leaves it out.
                    .filter(|f| {
                        let check = f["check"].as_str().unwrap();
                        let steps = f["counterexample"]["steps"].as_array().map_or(0, Vec::len);
                        !bdi_check::smt::lint::CHECKS.contains(&check) || steps > 0
                    })
                    .count();
                let o = bdi_check(&["replay", file.to_str().unwrap()]);
                let out = String::from_utf8_lossy(&o.stdout).into_owned();
                assert_eq!(o.status.code(), Some(1), "{at}: {out}");
                assert_eq!(
                    out.matches("still reaches its violation").count(),
                    failed,
                    "{at}: {out}"
                );
            }
            // Where instances are interchangeable, fewer states; where none are (or their
            // names are written in a plan), as many, and the report says why.
            let refused = sym["warnings"].as_array().is_some_and(|w| {
                w.iter().any(|w| {
                    w.as_str()
                        .unwrap()
                        .starts_with("symmetry over the instances")
                })
            });
            let instances = std::fs::read_to_string(d.join("bdi-check.toml"))
                .unwrap()
                .contains("instances")
                || d.ends_with("ping-pong");
            if instances && !refused {
                assert!(states(&sym) < states(&full), "{at}: nothing reduced");
            } else {
                assert_eq!(states(&sym), states(&full), "{at}");
            }
            assert_eq!(refused, d.ends_with("tell"), "{at}: {sym:#}");
            assert!(full.get("warnings").is_none(), "{at}: {full:#}");
        }
    }
    // The goal failure of each worker is reported for each, as the full search does.
    let (_, r, _) = verify_json(
        workers("sym-goal-each", 3, "?step4", "").to_str().unwrap(),
        "sym-goal-each-report",
    );
    let g = failing(&r, "goal-failure");
    assert_eq!(g.len(), 3, "{r:#}");
    for k in 1..=3 {
        assert!(
            g.iter().any(|f| {
                f["message"]
                    .as_str()
                    .unwrap()
                    .contains(&format!("of agent `worker{k}`"))
                    && agent_steps(f)
                        .iter()
                        .all(|s| s.starts_with(&format!("worker{k} ")))
            }),
            "worker{k}: {r:#}"
        );
    }
}

#[test]
fn symmetry_over_instances_reduces_a_ping_pong() {
    let d = ping_pong("sym-ping-pong-4", 4, PINGER, PONGER, "");
    let (code, sym, _) = verify_json(d.to_str().unwrap(), "sym-ping-pong-4-report");
    let (_, full, _) = common::report_json(
        &["verify", d.to_str().unwrap(), "--no-symmetry"],
        "sym-ping-pong-4-full",
    );
    assert_eq!(code, 0, "{sym:#}");
    let states = |r: &serde_json::Value| r["stats"]["states"].as_u64().unwrap();
    // 4! orders of the pingers: about a twentieth of the states.
    assert!(
        states(&sym) * 20 < states(&full),
        "{} states with symmetry, {} without",
        states(&sym),
        states(&full)
    );
    // The run to `all_answered` is a shortest one either way.
    let steps = |r: &serde_json::Value| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == "property:all_answered")
            .map(|f| f["counterexample"]["steps"].as_array().unwrap().len())
    };
    assert_eq!(steps(&sym), steps(&full));
}

#[test]
fn instances_something_tells_apart_get_no_symmetry_and_the_report_says_why() {
    let states = |r: &serde_json::Value| r["stats"]["states"].as_u64().unwrap();
    let warning = |r: &serde_json::Value| {
        r["warnings"]
            .as_array()
            .and_then(|w| w.first())
            .and_then(|w| w.as_str())
            .unwrap_or("")
            .to_string()
    };
    // A plan names an instance.
    let named = ping_pong(
        "sym-named",
        3,
        "!start.\n+!start <- .send(ponger, achieve, ping).\n+!hello <- .send(pinger1, tell, hi).\n",
        PONGER,
        "",
    );
    // A property that is not symmetric in the instances.
    let property = ping_pong(
        "sym-property",
        3,
        PINGER,
        PONGER,
        "\n[[property]]\nname = \"first\"\nreachable = \"ponged(pinger1) & not ponged(pinger2)\"\n",
    );
    // An invariant of one instance's beliefs.
    let invariant = ping_pong(
        "sym-invariant-one",
        3,
        PINGER,
        PONGER,
        "\n[[property]]\nname = \"mine\"\nalways = \"not pinger2::ponged(pinger3)\"\n",
    );
    // An initial state that renaming does not keep.
    let initial = ping_pong(
        "sym-initial",
        3,
        PINGER,
        PONGER,
        "\n[initial]\nfacts = [\"ponged(pinger1)\"]\n",
    );
    // A request that names an instance.
    let request = ping_pong(
        "sym-request",
        3,
        PINGER,
        "+!ping[source(A)] <- pong(A).\n+!ask(A) <- .print(A).\n",
        "\n[requests]\ngoals = [\"ask(pinger1)\"]\n",
    );
    for (d, why) in [
        (&named, "pinger.asl:3:18 names `pinger1`"),
        (&property, "`first` is not symmetric in them"),
        (&invariant, "`mine` is not symmetric in them"),
        (
            &initial,
            "renaming them turns an initial state of the environment into one that is not initial",
        ),
        (&request, "the request `ask(pinger1)` names `pinger1`"),
    ] {
        let (_, r, _) = verify_json(d.to_str().unwrap(), "sym-refused");
        let (_, full, _) = common::report_json(
            &["verify", d.to_str().unwrap(), "--no-symmetry"],
            "sym-refused-full",
        );
        let w = warning(&r);
        assert!(
            w.starts_with("symmetry over the instances `pinger1`, `pinger2`, `pinger3`"),
            "{w}"
        );
        assert!(w.contains(why), "{w}");
        assert_eq!(states(&r), states(&full), "{}", d.display());
        assert_eq!(verdicts(&r), verdicts(&full), "{}", d.display());
    }
    // The human report shows it too.
    let o = bdi_check(&["verify", named.to_str().unwrap(), "--color", "never"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("warning: symmetry over the instances"),
        "{out}"
    );
    // A symmetric property of every instance keeps the symmetry (tests/verify/mas-list).
    let (_, r, _) = verify_json("tests/verify/mas-list", "sym-symmetric-property");
    assert!(r.get("warnings").is_none(), "{r:#}");
}

#[test]
fn a_renaming_of_instances_that_changes_what_the_agents_do_is_announced() {
    // Each pinger reacts to every `ponged(A)` it perceives: when it perceives two at once,
    // Jason meets them in the hash order of their names, which renaming does not keep.
    let d = ping_pong(
        "sym-hash-order",
        3,
        "!start.\n+!start <- .send(ponger, achieve, ping).\n+ponged(A) <- .print(A).\n",
        PONGER,
        "",
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "sym-hash-order-report");
    assert_eq!(code, 0, "{r:#}");
    let w = r["warnings"][0].as_str().unwrap_or("");
    assert!(
        w.starts_with("symmetry reduction treats instances of one agent as interchangeable, but renaming pinger"),
        "{r:#}"
    );
    assert!(w.contains("`--no-symmetry` gives the exact verdict"), "{w}");
    let (_, full, _) = common::report_json(
        &["verify", d.to_str().unwrap(), "--no-symmetry"],
        "sym-hash-order-full",
    );
    assert!(full.get("warnings").is_none(), "{full:#}");
    assert_eq!(verdicts(&r), verdicts(&full));
    // Jason lists a belief's sources sorted by name: a test goal over two senders answers
    // the first name, whichever instance told it last.
    let d = project(
        "sym-sources",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"collector\"\nplans = \"collector.asl\"\nactions = \"d.pddl\"\n\n[[agent]]\nname = \"worker\"\nplans = \"worker.asl\"\ninstances = 2\n",
            ),
            ("d.pddl", DOMAIN),
            ("worker.asl", "!work.\n+!work <- .send(collector, tell, done).\n"),
            (
                "collector.asl",
                "+done[source(A)] <- ?done[source(B)]; .print(A, B).\n",
            ),
        ],
    );
    let (_, r, _) = verify_json(d.to_str().unwrap(), "sym-sources-report");
    let w = r["warnings"][0].as_str().unwrap_or("");
    assert!(
        w.contains(
            "but renaming worker1 -> worker2, worker2 -> worker1 changes what the agents do"
        ),
        "{r:#}"
    );
}

/// Every state of `system` reachable over every interleaving.
fn reachable(system: &bdi_check::semantics::System) -> Vec<bdi_check::semantics::SystemState> {
    let mut seen = std::collections::HashSet::new();
    let mut queue: Vec<_> = system.initial_states();
    let mut out = Vec::new();
    while let Some(s) = queue.pop() {
        if !seen.insert(s.clone()) {
            continue;
        }
        for (_, t) in system.successors(&s) {
            if !seen.contains(&t) {
                queue.push(t);
            }
        }
        out.push(s);
    }
    out
}

#[test]
fn renaming_instances_renames_every_successor_and_keeps_the_canonical_form() {
    use bdi_check::check::symmetry::Instances;
    use bdi_check::semantics::System;
    let fp = |s: &bdi_check::semantics::SystemState| bdi_check::check::explore::fingerprint(s);
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        ping_pong("eq-ping-pong", 3, PINGER, PONGER, ""),
        root.join("tests/jason-mas/send-errors"),
        workers("eq-workers", 3, "+step3", ""),
        workers("eq-goal", 3, "?step4", ""),
        ping_pong(
            "eq-tell",
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping).\n+answered[source(ponger)] <- .my_name(Me); .broadcast(tell, heard(Me)).\n",
            "+!ping[source(A)] <- pong(A); .send(A, tell, answered).\n",
            "",
        ),
    ];
    for d in &dirs {
        let projects = bdi_check::model::project::load_system(d).expect("the project loads");
        let system = System::new(&projects).expect("a system");
        let inst = Instances::new(&system, &[]);
        assert!(!inst.is_empty(), "{}", d.display());
        let gens = inst.generators();
        let members: Vec<u8> = (0..projects.len() as u8)
            .filter(|&k| gens.iter().any(|g| g[k as usize] != k))
            .collect();
        let every = inst.images(&members);
        let states = reachable(&system);
        let mut classes = std::collections::HashSet::new();
        for s in &states {
            // Successors of a renamed state are the renamed successors.
            for g in &gens {
                let mut renamed: Vec<u64> = system
                    .successors(s)
                    .iter()
                    .map(|(_, t)| fp(&inst.apply(t, g)))
                    .collect();
                let mut theirs: Vec<u64> = system
                    .successors(&inst.apply(s, g))
                    .iter()
                    .map(|(_, t)| fp(t))
                    .collect();
                renamed.sort_unstable();
                theirs.sort_unstable();
                assert_eq!(renamed, theirs, "{}: {}", d.display(), inst.show(g));
            }
            assert_eq!(inst.equivariance_violation(&system, s), None);
            // Every renaming of a state has its canonical form, a renaming of it.
            let (c, form) = inst.canonical(s);
            for p in &every {
                assert_eq!(inst.canonical(&inst.apply(s, p)).0, c, "{}", d.display());
            }
            let form = form.unwrap_or_else(|| s.clone());
            assert!(every.iter().any(|p| inst.apply(s, p) == form));
            // One class per orbit: the least fingerprint of every renaming.
            classes.insert(every.iter().map(|p| fp(&inst.apply(s, p))).min());
        }
        // The search stores exactly one state per class.
        let opts = bdi_check::check::VerifyOptions {
            threads: 1,
            partial_order: false,
            ..Default::default()
        };
        let limits = bdi_check::check::explore::Limits {
            max_states: 1_000_000,
            max_depth: 10_000,
            timeout: None,
        };
        let v = bdi_check::check::system::verify_system(
            &projects,
            limits,
            &opts,
            |_, _, _, _| {},
            Vec::new(),
        )
        .expect("verifies");
        assert_eq!(v.stats.states, classes.len(), "{}", d.display());
        assert!(classes.len() < states.len(), "{}", d.display());
    }
}

#[test]
fn the_agents_stuck_in_each_state_are_those_no_continuation_moves() {
    // The backward search over the explored graph (with symmetry: following each agent
    // through the renamings the states are stored under) against every state's
    // continuations, explored one by one.
    use bdi_check::check::system::{stuck_from, stuck_states};
    use bdi_check::semantics::System;
    let mut cases: Vec<std::path::PathBuf> = vec![
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verify/mas-unanswered"),
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verify/mas-lost-wakeup"),
    ];
    cases.extend(multi_agent_projects("stuck").into_iter().filter(|d| {
        let name = d.file_name().unwrap().to_string_lossy();
        name.contains("served") || name.contains("deadlock")
    }));
    assert!(cases.len() >= 5);
    let mut stuck_seen = 0;
    for d in &cases {
        let agents = bdi_check::model::project::load_system(d).unwrap();
        let system = System::new(&agents).unwrap();
        for (symmetry, por) in [(false, false), (true, false), (true, true)] {
            let states = stuck_states(&agents, symmetry, por).unwrap();
            for (s, stuck) in &states {
                for k in 0..system.names().len() {
                    let want = stuck_from(&system, s, k).expect("decided");
                    // Partial-order reduction may leave out the run that moves an agent
                    // from a state only where another of its states does: it only finds
                    // agents stuck that are.
                    if por {
                        assert!(stuck >> k & 1 == 0 || want, "{}: {k} in {s:?}", d.display());
                    } else {
                        assert_eq!(
                            stuck >> k & 1 == 1,
                            want,
                            "{} ({symmetry}): {k} in {s:?}",
                            d.display()
                        );
                    }
                    stuck_seen += usize::from(want);
                }
            }
        }
    }
    assert!(stuck_seen > 0);
}

#[test]
fn requests_go_to_the_agent_the_manifest_names() {
    let toml = |to: &str| {
        format!("[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[agent]]\nname = \"b\"\nplans = \"b.asl\"\n[requests]\ngoals = [\"go\"]\nto = \"{to}\"\n[[property]]\nname = \"done\"\nreachable = \"p\"\n")
    };
    let d = project(
        "requests-to",
        &[
            ("bdi-check.toml", &toml("b")),
            ("d.pddl", DOMAIN),
            ("a.asl", "+!go <- .print(wrong).\n"),
            ("b.asl", "+!go <- a.\n"),
        ],
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "requests-to-report");
    assert_eq!(code, 0, "{r:#}");
    let done = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "property:done")
        .unwrap();
    let steps = agent_steps(done);
    assert_eq!(steps[0], "b request !go", "{steps:#?}");
    assert!(steps.iter().all(|s| s.starts_with("b ")), "{steps:#?}");
    // A name no agent has is refused where written.
    std::fs::write(d.join("bdi-check.toml"), toml("c")).unwrap();
    let out = verify_error(&d);
    assert!(out.contains("no agent is named `c`"), "{out}");
    assert!(out.contains("bdi-check.toml:10:6"), "{out}");
}

#[test]
fn runs_that_go_on_for_ever_are_fair_to_every_agent() {
    let with_property = |d: &std::path::Path| {
        let toml = d.join("bdi-check.toml");
        let text = std::fs::read_to_string(&toml).unwrap();
        std::fs::write(
            &toml,
            format!("{text}[[property]]\nname = \"marked\"\neventually = \"p\"\n"),
        )
        .unwrap();
    };
    let poll = "!wait.\n+!wait : not go <- .wait(100); !wait.\n+!wait : go <- a.\n";
    // `a` looks for `go` every 100 ms until `b` tells it: `b` can always do so, and is not
    // left out for ever, so `a` does not run for ever, and `p` comes.
    let d = two_agents("fair-poll", poll, "!tell.\n+!tell <- .send(a, tell, go).\n");
    with_property(&d);
    let (code, r, _) = verify_json(d.to_str().unwrap(), "fair-poll-report");
    assert_eq!(code, 0, "{r:#}");
    for id in ["livelock:a", "livelock:b", "property:marked"] {
        let f = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == id)
            .unwrap_or_else(|| panic!("{id}: {r:#}"));
        assert_eq!(f["status"], "pass", "{id}: {r:#}");
    }
    // `b` never tells it: `a` looks for ever, and `p` never comes.
    let d = two_agents("unfair-poll", poll, "+!tell <- .send(a, tell, go).\n");
    with_property(&d);
    let (code, r, file) = verify_json(d.to_str().unwrap(), "unfair-poll-report");
    assert_eq!(code, 1, "{r:#}");
    let ids: Vec<&str> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["status"] == "fail" && f["severity"] == "error")
        .filter(|f| f["suppressed"].is_null())
        .map(|f| f["id"].as_str().unwrap())
        .collect();
    assert_eq!(ids, ["livelock:a", "property:marked"], "{r:#}");
    for f in failing(&r, "livelock") {
        let c = &f["counterexample"];
        let at = c["loop_start"].as_u64().expect("a loop") as usize;
        let steps = agent_steps(f);
        assert!(
            steps[at..].iter().any(|s| s.contains("its time is up")),
            "{steps:#?}"
        );
    }
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(
        out.matches("still reaches its violation").count(),
        2,
        "{out}"
    );
    // A request pending for ever: its intention polls.
    let d = project(
        "pending-request",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[agent]]\nname = \"b\"\nplans = \"b.asl\"\n[requests]\ngoals = [\"job\"]\n",
            ),
            ("d.pddl", DOMAIN),
            ("a.asl", "+!job <- !wait.\n+!wait : not go <- .wait(100); !wait.\n+!wait : go <- a.\n"),
            ("b.asl", "+!tell <- .send(a, tell, go).\n"),
        ],
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "pending-request-report");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "request-not-completed");
    assert_eq!(f.len(), 1, "{r:#}");
    assert_eq!(f[0]["id"], "request-not-completed:job");
    // A run that ends without `p`.
    let d = two_agents("ends-unmarked", "!g.\n+!g <- .print(done).\n", "\n");
    with_property(&d);
    let (code, r, file) = verify_json(d.to_str().unwrap(), "ends-unmarked-report");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "property");
    assert_eq!(f.len(), 1, "{r:#}");
    assert!(f[0]["message"]
        .as_str()
        .unwrap()
        .contains("on a run that ends"));
    assert!(f[0]["counterexample"]["loop_start"].is_null());
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}

#[test]
fn an_action_with_an_agent_parameter_is_done_by_the_agent_that_calls_it() {
    let domain = "(define (domain rooms) (:requirements :strips :typing) (:types robot place)\n  (:constants hall lab - place)\n  (:predicates (at ?r - robot ?p - place))\n  (:action go :parameters (?agent - robot ?to - place) :precondition (not (at ?agent ?to)) :effect (at ?agent ?to)))\n";
    let toml = "[[agent]]\nname = \"r\"\nplans = \"r.asl\"\nactions = \"d.pddl\"\ninstances = 2\n[objects]\nrobot = [\"r1\", \"r2\"]\n[[property]]\nname = \"both_in_the_lab\"\nreachable = \"at(r1, lab) & at(r2, lab)\"\n";
    let d = project(
        "agent-parameter",
        &[
            ("bdi-check.toml", toml),
            ("d.pddl", domain),
            ("r.asl", "!g.\n+!g <- go(lab).\n"),
        ],
    );
    let (code, r, _) = verify_json(d.to_str().unwrap(), "agent-parameter-report");
    assert_eq!(code, 0, "{r:#}");
    let reach = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "property:both_in_the_lab")
        .unwrap();
    let steps = agent_steps(reach);
    assert!(
        steps.contains(&"r1 action go(lab)".to_string()),
        "{steps:#?}"
    );
    assert!(
        steps.contains(&"r2 action go(lab)".to_string()),
        "{steps:#?}"
    );
    // The agent does not write itself.
    std::fs::write(d.join("r.asl"), "!g.\n+!g <- go(r1, lab).\n").unwrap();
    let out = verify_error(&d);
    assert!(
        out.contains("the action `go` takes 1 argument, but 2 are given"),
        "{out}"
    );
    assert!(
        out.contains("its `?agent` parameter is the agent that does it"),
        "{out}"
    );
    // An agent that is no robot cannot do it.
    std::fs::write(d.join("r.asl"), "!g.\n+!g <- go(lab).\n").unwrap();
    std::fs::write(
        d.join("bdi-check.toml"),
        toml.replace("robot = [\"r1\", \"r2\"]", "robot = [\"r1\", \"r9\"]")
            .replace("at(r2, lab)", "at(r9, lab)"),
    )
    .unwrap();
    let out = verify_error(&d);
    assert!(
        out.contains("the agent `r2` is no object of type `robot`"),
        "{out}"
    );
}

#[test]
fn a_run_where_a_property_never_holds_never_passes_through_it() {
    // Two ways into the same loop: the shorter one makes `p` true on the way; the run shown
    // must be the other.
    let domain = "(define (domain d) (:requirements :strips) (:predicates (p)) (:action on :parameters () :precondition () :effect (p)) (:action off :parameters () :precondition () :effect (not (p))))";
    let d = project(
        "eventually-prefix",
        &[
            (
                "bdi-check.toml",
                "[[agent]]\nname = \"a\"\nplans = \"a.asl\"\nactions = \"d.pddl\"\n[[agent]]\nname = \"b\"\nplans = \"b.asl\"\n[[property]]\nname = \"marked\"\neventually = \"p\"\n",
            ),
            ("d.pddl", domain),
            (
                "a.asl",
                "!g.\n+!g <- .random([yes, no], X); !act(X).\n+!act(yes) <- on; off; !!poll.\n+!act(no) <- .print(1); .print(2); .print(3); .print(4); .print(5); .print(6); !!poll.\n+!poll <- .wait(100); !poll.\n",
            ),
            ("b.asl", "\n"),
        ],
    );
    std::fs::write(
        d.join("bdi-check.toml"),
        std::fs::read_to_string(d.join("bdi-check.toml")).unwrap()
            + "[objects]\nobject = [\"yes\", \"no\"]\n[[allow]]\ncheck = \"livelock\"\nwhy = \"a polls for ever\"\n",
    )
    .unwrap();
    let (code, r, file) = verify_json(d.to_str().unwrap(), "eventually-prefix-report");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "property");
    assert_eq!(f.len(), 1, "{r:#}");
    let steps = agent_steps(f[0]);
    assert!(!steps.iter().any(|s| s.contains("action on")), "{steps:#?}");
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        out.contains("property:marked: still reaches its violation"),
        "{out}"
    );
}

#[test]
fn random_runs_of_several_agents_find_what_they_reach_and_never_pass() {
    // `simulate`: the race of `tests/verify/mas-race` on random runs, found and replayed;
    // what the runs cannot decide is undecided.
    let (code, r, file) = common::report_json(
        &[
            "simulate",
            "tests/verify/mas-race",
            "--runs",
            "20",
            "--seed",
            "1",
        ],
        "simulate-race",
    );
    assert_eq!(code, 1, "{r:#}");
    assert!(!failing(&r, "action-failure").is_empty(), "{r:#}");
    assert_eq!(r["stats"]["complete"], false);
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(!out.contains("no longer reaches"), "{out}");
    // On the two robots, nothing fails and nothing passes for sure: incomplete.
    let (code, r, _) = common::report_json(
        &["simulate", "specs/two-robots", "--runs", "5", "--seed", "7"],
        "simulate-two-robots",
    );
    assert_eq!(code, 3, "{r:#}");
    assert_eq!(r["verdict"], "incomplete");
    // Shards are refused.
    let o = bdi_check(&["verify", "specs/two-robots", "--shard", "1/2"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn the_state_graph_of_several_agents_names_the_agent_of_every_transition() {
    let o = bdi_check(&["graph", "tests/verify/mas-lost-wakeup", "--states"]);
    assert_eq!(o.status.code(), Some(0));
    let dot = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(dot.starts_with("// the state graph has"), "{dot}");
    assert!(dot.contains("digraph states"));
    // Transitions of both agents, and the stuck states the deadlock ends in, drawn.
    assert!(dot.contains("label = \"fetcher: "), "{dot}");
    assert!(dot.contains("label = \"loader: "), "{dot}");
    assert!(
        dot.contains("loader: 0 events, 1 intentions, 0 messages\", style=filled"),
        "{dot}"
    );
    // One agent's plans, not several.
    let o = bdi_check(&["graph", "specs/two-robots", "--plans"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn plans_told_untold_and_asked_go_through_jasons_plans_for_messages() {
    // A second plan with a label the library holds is refused (`PlanLibrary.add` throws,
    // the plan for messages fails); the first stays and is used.
    let d = two_agents(
        "tell-how-label",
        "!g.\n+!g <- .send(b, tellHow, \"@h +!hi <- .print(one).\"); .send(b, tellHow, {@h +!hi <- .print(two)}); .wait(100); .send(b, achieve, hi).\n",
        "\n",
    );
    let (printed, _) = round_robin(&d, 30);
    assert_eq!(
        printed,
        ["b: Communication error -- internal_action", "b: one"]
    );
    // untellHow takes the sender's source away, and the plan with it.
    let d = two_agents(
        "untell-how",
        "!g.\n+!g <- .send(b, tellHow, \"@h +!hi <- .print(one).\"); .wait(100); .send(b, achieve, hi); .wait(100); .send(b, untellHow, h); .wait(100); .send(b, achieve, hi).\n",
        "-!hi <- .print(gone).\n",
    );
    let (printed, _) = round_robin(&d, 40);
    assert_eq!(printed, ["b: one", "b: gone"]);
    // askHow: the answer is told back and joins the asker's library, the receiver's
    // plans in its order; asked again, the answers are new copies (their variables are
    // anonymous), whose labels are taken.
    let d = two_agents(
        "ask-how",
        "!g.\n+!g <- .send(b, askHow, {+!tip(_)}); .wait(100); !tip(k1); !tip(k2); .send(b, askHow, \"+!tip(X)\").\n",
        "@t1 +!tip(X) : X == k1 <- .print(first, X).\n@t2 +!tip(X) <- .print(second, X).\n",
    );
    let (printed, state) = round_robin(&d, 40);
    assert_eq!(
        printed,
        [
            "a: firstk1",
            "a: secondk2",
            "a: Communication error -- internal_action"
        ]
    );
    let library = state.agents[0].library.as_ref().expect("a's plans changed");
    assert_eq!(library.len(), 3, "a's own +!g and the two told plans");
    // A plan told by a plan the sender adds is told too.
    let d = two_agents(
        "tell-how-added",
        "!g.
+!g <- .add_plan({+!later <- .send(b, tellHow, \"+!x <- .print(x).\")}); !later; .wait(100); .send(b, achieve, x).
",
        "\n",
    );
    let (printed, _) = round_robin(&d, 30);
    assert_eq!(printed, ["b: x"]);
}

#[test]
fn know_how_that_is_not_written_out_is_refused_where_written() {
    let cases = [
        (
            "tell-how-var",
            "!g.\n+!g <- .plan_label(P, h); .send(b, tellHow, P).\n",
            "\n",
            "a.asl:2:45",
            "`tellHow` of a plan held in a variable",
        ),
        (
            "tell-how-syntax",
            "!g.\n+!g <- .send(b, tellHow, \"+!hi <- .print(.\").\n",
            "\n",
            "a.asl:2:",
            "error",
        ),
        (
            "ask-how-sync",
            "!g.\n+!g <- .send(b, askHow, {+!hi}, Plans).\n",
            "@h +!hi.\n",
            "a.asl:2:33",
            "an `askHow` that waits for its answer",
        ),
        (
            "ask-how-unlabelled",
            "!g.\n+!g <- .send(b, askHow, {+!hi}).\n",
            "+!hi <- .print(hi).\n",
            "a.asl:2:25",
            "`askHow` of unlabelled plans",
        ),
        (
            "untell-how-var",
            "!g.\n+!g <- .send(b, untellHow, L).\n",
            "\n",
            "a.asl:2:28",
            "`untellHow` needs a plan's label",
        ),
        (
            "ask-how-changing",
            "!g.\n+!g <- .send(b, tellHow, \"@h2 +!hi <- .print(two).\"); .send(b, askHow, {+!hi}).\n",
            "@h1 +!hi <- .print(one).\n",
            "a.asl:2:",
            "`askHow` of plans the receiver may add or remove",
        ),
        (
            "signal",
            "!g.\n+!g <- .send(b, signal, hi).\n",
            "\n",
            "a.asl:2:17",
            "the performative `signal`",
        ),
    ];
    for (name, a, b, at, what) in cases {
        let d = two_agents(name, a, b);
        let out = verify_error(&d);
        assert!(out.contains(at), "{name}: {out}");
        assert!(out.contains(what), "{name}: {out}");
    }
}

#[test]
fn plans_that_can_never_be_in_the_library_together_are_no_overlap() {
    // Two senders tell one plan (a string and a plan term, equal as Jason's `Plan.equals`
    // sees them): the receiver holds it once, so lint must not call the two copies
    // overlapping; a second plan under a label the library holds is never added either.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = root.join("tests/jason-mas/tell-how-sources");
    let (_, r, _) = verify_json(d.to_str().unwrap(), "never-together");
    let overlaps: Vec<_> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == "plan-overlap" && f["status"] == "fail")
        .collect();
    assert!(overlaps.is_empty(), "{overlaps:#?}");
    let d = two_agents(
        "never-together-label",
        "!g.\n+!g <- .send(b, tellHow, \"@h +!hi <- .print(one).\"); .send(b, tellHow, {@h +!hi <- .print(two)}).\n",
        "\n",
    );
    let (_, r, _) = verify_json(d.to_str().unwrap(), "never-together-label");
    assert!(
        !r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f["check"] == "plan-overlap" && f["status"] == "fail"),
        "{r:#}"
    );
}

#[test]
fn without_fairness_among_agents_a_loop_may_leave_one_out() {
    // The fair poll of `runs_that_go_on_for_ever_are_fair_to_every_agent`: `b` can always
    // tell `a` to stop. With `fairness = ["intentions"]` the runs where `b` never moves
    // count too: `a` polls for ever there, and the loop replays (it need not move `b`).
    let poll = "!wait.\n+!wait : not go <- .wait(100); !wait.\n+!wait : go <- a.\n";
    let d = two_agents(
        "unfair-allowed",
        poll,
        "!tell.\n+!tell <- .send(a, tell, go).\n",
    );
    let toml = d.join("bdi-check.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    std::fs::write(
        &toml,
        format!("{text}[bounds]\nfairness = [\"intentions\"]\n"),
    )
    .unwrap();
    let (code, r, file) = verify_json(d.to_str().unwrap(), "unfair-allowed-report");
    assert_eq!(code, 1, "{r:#}");
    let f = failing(&r, "livelock");
    assert_eq!(f.len(), 1, "{r:#}");
    assert_eq!(f[0]["id"], "livelock:a", "{r:#}");
    let (rc, out) = common::replay_finding(&file, "livelock:a");
    assert_eq!(rc, 1, "{out}");
    // And the fairness the passing checks assumed is said.
    let b = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "livelock:b")
        .unwrap();
    assert!(
        b["message"].as_str().unwrap().contains("not to the agents"),
        "{b:#}"
    );
    // `intentions` cannot be left out: the cycle's selection is Jason's round-robin.
    std::fs::write(&toml, format!("{text}[bounds]\nfairness = [\"agents\"]\n")).unwrap();
    let o = bdi_check(&["verify", d.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("must list \"intentions\""), "{err}");
    assert!(err.contains("bdi-check.toml:"), "{err}");
}

#[test]
fn ltl_among_agents_names_them_and_assumes_the_fairness_the_manifest_says() {
    // The fair poll: `b` can always tell `a` to stop polling, and then `a` does `a`.
    let poll = "!wait.\n+!wait : not go <- .wait(100); !wait.\n+!wait : go <- a.\n";
    let d = two_agents("ltl-poll", poll, "!tell.\n+!tell <- .send(a, tell, go).\n");
    let toml = d.join("bdi-check.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    let props = "[[property]]\nname = \"acts\"\nltl = \"<> did(a, a)\"\n\
                 [[property]]\nname = \"told_first\"\nltl = \"[] (did(a, a) -> believes(a, go))\"\n\
                 [[property]]\nname = \"b_never_acts\"\nltl = \"[] not did(b, a) & <> p\"\n";
    std::fs::write(&toml, format!("{text}{props}")).unwrap();
    let (code, r, _) = verify_json(d.to_str().unwrap(), "ltl-poll-report");
    assert_eq!(code, 0, "{r:#}");
    for id in [
        "property:acts",
        "property:told_first",
        "property:b_never_acts",
    ] {
        let f = r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == id)
            .unwrap();
        assert_eq!(f["status"], "pass", "{f:#}");
        assert!(
            f["message"]
                .as_str()
                .unwrap()
                .contains("fair to the agents"),
            "{f:#}"
        );
    }
    // Without fairness of agents, `b` may never move: `a` polls for ever, a lasso that
    // replays (and it need not move `b`).
    std::fs::write(
        &toml,
        format!("{text}[bounds]\nfairness = [\"intentions\"]\n{props}"),
    )
    .unwrap();
    let (code, r, file) = verify_json(d.to_str().unwrap(), "ltl-unfair-poll-report");
    assert_eq!(code, 1, "{r:#}");
    let acts = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == "property:acts")
        .unwrap();
    assert_eq!(acts["status"], "fail", "{acts:#}");
    assert!(acts["counterexample"]["loop_start"].is_u64(), "{acts:#}");
    let (rc, out) = common::replay_finding(&file, "property:acts");
    assert_eq!(rc, 1, "{out}");
    // A modality names its agent among several.
    std::fs::write(
        &toml,
        format!("{text}[[property]]\nname = \"whose\"\nltl = \"<> believes(go)\"\n"),
    )
    .unwrap();
    let err = verify_error(&d);
    assert!(err.contains("must name its agent"), "{err}");
    assert!(err.contains("bdi-check.toml:"), "{err}");
}

#[test]
fn explained_among_agents_assumes_the_fairness_the_manifest_says() {
    // The fair poll, watched by a newcomer: `a` acts once `b` tells it to, and the action
    // is explained. Fair to the agents, every run gets there; without that fairness, `b`
    // may never move and `a` polls for ever, unexplained (a lasso that replays).
    let poll = "!wait.\n+!wait : not go <- .wait(100); !wait.\n+!wait : go <- a.\n";
    let d = two_agents(
        "ltl-explained-poll",
        poll,
        "!tell.\n+!tell <- .send(a, tell, go).\n",
    );
    let toml = d.join("bdi-check.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    let rest = "[[property]]\nname = \"told_of_a\"\nltl = \"<> explained(newcomer, a)\"\n\
                [explanation]\nrobot = \"a\"\n[explanation.users.newcomer]\nexpected = []\n";
    std::fs::write(&toml, format!("{text}{rest}")).unwrap();
    let told = |r: &serde_json::Value| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == "property:told_of_a")
            .unwrap_or_else(|| panic!("{r:#}"))
            .clone()
    };
    let (_, r, _) = verify_json(d.to_str().unwrap(), "ltl-explained-poll-report");
    let f = told(&r);
    assert_eq!(f["status"], "pass", "{f:#}");
    // The user's search decides it: the interleavings themselves read no proposition.
    let phases = common::phase_names(&r);
    assert!(phases.contains(&"ltl search:newcomer"), "{phases:?}");
    assert!(!phases.contains(&"ltl product"), "{phases:?}");
    assert!(
        f["message"]
            .as_str()
            .unwrap()
            .contains("fair to the agents"),
        "{f:#}"
    );
    std::fs::write(
        &toml,
        format!("{text}[bounds]\nfairness = [\"intentions\"]\n{rest}"),
    )
    .unwrap();
    let (_, r, file) = verify_json(d.to_str().unwrap(), "ltl-explained-unfair-report");
    let f = told(&r);
    assert_eq!(f["status"], "fail", "{f:#}");
    assert!(f["counterexample"]["loop_start"].is_u64(), "{f:#}");
    let (rc, out) = common::replay_finding(&file, "property:told_of_a");
    assert_eq!(rc, 1, "{out}");
}

#[test]
fn explained_among_agents_is_decided_on_the_users_search_of_every_interleaving() {
    // specs/two-robots-explaining: the owner watches the fetcher; carrying a cup to the
    // counter and putting it there surprise them, picking it up does not.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = common::temp_dir("ltl-explained-among");
    let src = root.join("specs/two-robots-explaining");
    for e in std::fs::read_dir(&src).unwrap().flatten() {
        std::fs::copy(e.path(), d.join(e.file_name())).unwrap();
    }
    let toml = d.join("bdi-check.toml");
    let text = std::fs::read_to_string(&toml).unwrap().replace(
        "\"../two-robots/",
        &format!("\"{}/", root.join("specs/two-robots").display()),
    );
    let props = "[[property]]\nname = \"told_of_puts\"\nltl = \"[] (did(fetcher, put(fetcher, C)) -> explained(owner, put(fetcher, C)))\"\n\
                 [[property]]\nname = \"never_told_of_picks\"\nltl = \"[] not explained(owner, pick(fetcher, C))\"\n\
                 [[property]]\nname = \"never_told_of_puts\"\nltl = \"[] not explained(owner, put(fetcher, C))\"\n";
    let text = text.replacen(
        "\n[explanation]\n",
        &format!("\n{props}\n[explanation]\n"),
        1,
    );
    std::fs::write(&toml, text).unwrap();
    let (code, r, file) = verify_json(d.to_str().unwrap(), "ltl-explained-among-report");
    assert_eq!(code, 1, "{r:#}");
    let status = |id: &str| {
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["id"] == id)
            .unwrap_or_else(|| panic!("{id}: {r:#}"))["status"]
            .clone()
    };
    assert_eq!(status("property:told_of_puts"), "pass");
    assert_eq!(status("property:never_told_of_picks"), "pass");
    assert_eq!(status("property:never_told_of_puts"), "fail");
    let (rc, out) = common::replay_finding(&file, "property:never_told_of_puts");
    assert_eq!(rc, 1, "{out}");
}
