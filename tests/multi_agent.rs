//! Projects of several agents (`.mas2j`, `[[agent]]`): `verify` explores every
//! interleaving of their reasoning cycles; the seeded communication defects are found
//! with runs whose steps name their agents; bad project files are located.

mod common;
use common::{bdi_check, temp_dir, verify_json};

fn failing<'a>(r: &'a serde_json::Value, check: &str) -> Vec<&'a serde_json::Value> {
    r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == check && f["status"] == "fail")
        .collect()
}

/// A counterexample's steps as `agent kind text`.
fn agent_steps(f: &serde_json::Value) -> Vec<String> {
    f["counterexample"]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            format!(
                "{} {} {}",
                s["agent"].as_str().unwrap(),
                s["kind"].as_str().unwrap(),
                s["text"].as_str().unwrap()
            )
        })
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
    let o = bdi_check(&[
        "replay",
        file.to_str().unwrap(),
        "--finding",
        "property:loader_lags",
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
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
    for case in ["mas-lost-wakeup", "mas-race", "mas-list"] {
        dirs.push(root.join("tests/verify").join(case));
    }
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
    let dirs = [
        root.join("tests/verify/mas-lost-wakeup"),
        root.join("tests/verify/mas-race"),
        workers(
            "por-lib-invariant",
            3,
            "+step3",
            "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
        ),
        workers("por-lib-goal", 3, "?step4", ""),
    ];
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
            verify_system(&projects, limits, &opts, |_, _, _| {}, Vec::new()).expect("verifies")
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
fn multi_agent_projects() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs: Vec<std::path::PathBuf> = vec![root.join("specs/two-robots")];
    for case in ["mas-lost-wakeup", "mas-race", "mas-list"] {
        dirs.push(root.join("tests/verify").join(case));
    }
    for case in ["ping-pong", "send-errors", "tell", "two-robots"] {
        dirs.push(root.join("tests/jason-mas").join(case));
    }
    dirs.extend([
        workers("sym-pass", 3, "+step3", ""),
        workers(
            "sym-invariant",
            3,
            "+step3",
            "\n[invariants]\nnot_all_done = \"not collector::done\"\n",
        ),
        workers("sym-goal", 3, "?step4", ""),
        // Each pinger asks twice: the second `pong` of a pinger fails its precondition.
        ping_pong(
            "sym-action",
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping); .send(ponger, achieve, ping).\n",
            PONGER,
            "",
        ),
        // Each pinger waits for an answer that never comes.
        ping_pong(
            "sym-deadlock",
            3,
            "!start.\n+!start <- .send(ponger, achieve, ping); .wait({+never}).\n+!stop <- +never.\n",
            PONGER,
            "",
        ),
        // The ponger tells each pinger; each pinger tells the others it was answered.
        ping_pong(
            "sym-tell",
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
    for (i, d) in multi_agent_projects().iter().enumerate() {
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
                    .filter(|f| f["severity"] == "error")
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
            |_, _, _| {},
            Vec::new(),
        )
        .expect("verifies");
        assert_eq!(v.stats.states, classes.len(), "{}", d.display());
        assert!(classes.len() < states.len(), "{}", d.display());
    }
}
