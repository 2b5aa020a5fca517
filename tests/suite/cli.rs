//! The command line as a user meets it: exit codes, human and JSON output.

use std::path::Path;
use std::process::Output;

use crate::common;
use common::bdi_check;

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn parse_summarises_a_valid_file_and_exits_0() {
    let o = bdi_check(&["parse", "tests/asl/valid/kitchen_story.asl"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("tests/asl/valid/kitchen_story.asl: "), "{out}");
    assert!(out.contains("plans by trigger"), "{out}");
    assert!(out.contains("+!storeCup(C)"), "{out}");
    assert!(out.ends_with("parsed 1 file: no errors\n"), "{out}");
    assert!(stderr(&o).is_empty());
}

#[test]
fn parse_reports_every_error_with_location_and_exits_2() {
    let o = bdi_check(&["parse", "tests/asl/invalid/three_errors.asl"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    for loc in [
        "three_errors.asl:7:1: error[syntax]",
        "three_errors.asl:8:21: error[syntax]",
        "three_errors.asl:9:2: error[syntax]",
    ] {
        assert!(err.contains(loc), "missing {loc} in\n{err}");
    }
    // The excerpt shows the offending line with a caret.
    assert!(err.contains("+!wash(C) <- rinse(C; dry(C)."), "{err}");
    assert!(stdout(&o).contains("3 errors"), "{}", stdout(&o));
}

#[test]
fn parse_json_outlines_plans_with_locations() {
    let o = bdi_check(&["parse", "--format", "json", "specs/paper/paper.asl"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("valid JSON");
    assert_eq!(v["tool"]["name"], "bdi-check");
    assert_eq!(v["verdict"], "pass");
    let plans = v["files"][0]["plans"].as_array().expect("plans");
    assert_eq!(plans.len(), 2);
    assert_eq!(plans[0]["trigger"], "+!storeCup(C)");
    assert_eq!(plans[0]["context"], "used(C)");
    let body: Vec<&str> = plans[0]["body"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    assert_eq!(
        body,
        [
            "!openDishwasherIfNeed",
            "navigateTo(table)",
            "pickUp(C)",
            "navigateTo(dishwasher)",
            "putDown(C)"
        ]
    );
    assert_eq!(
        plans[1]["context"],
        "not dishwasherDoor(open) & holding(none)"
    );
    assert_eq!(plans[0]["location"]["file"], "specs/paper/paper.asl");
    assert_eq!(plans[0]["location"]["line"], 11);
    assert_eq!(plans[0]["location"]["column"], 1);
}

#[test]
fn parse_json_turns_errors_into_input_findings() {
    let o = bdi_check(&[
        "parse",
        "--format",
        "json",
        "tests/asl/invalid/missing_dot.asl",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("valid JSON");
    assert_eq!(v["verdict"], "error");
    let f = &v["findings"][0];
    assert_eq!(f["check"], "input");
    assert_eq!(f["severity"], "error");
    assert_eq!(f["location"]["file"], "tests/asl/invalid/missing_dot.asl");
    assert!(f["location"]["line"].as_u64().unwrap() >= 1);
    // JSON goes to stdout only; nothing else on stderr.
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}

#[test]
fn missing_file_is_bad_input_not_a_panic() {
    let o = bdi_check(&["parse", "no/such/file.asl"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains("no/such/file.asl"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn usage_errors_exit_2_and_help_exits_0() {
    assert_eq!(bdi_check(&["parse"]).status.code(), Some(2));
    assert_eq!(bdi_check(&["no-such-command"]).status.code(), Some(2));
    let help = bdi_check(&["--help"]);
    assert_eq!(help.status.code(), Some(0));
    assert!(stdout(&help).contains("parse"));
}

#[test]
fn quiet_prints_the_verdict_line_only_and_output_writes_a_file() {
    let o = bdi_check(&["parse", "-q", "specs/paper/paper.asl"]);
    assert_eq!(stdout(&o), "parsed 1 file: no errors\n");
    let dir = common::temp_dir("cli");
    let file = dir.join("report.json");
    let o = bdi_check(&[
        "parse",
        "--format",
        "json",
        "-o",
        file.to_str().unwrap(),
        "specs/paper/paper.asl",
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(stdout(&o).is_empty());
    let written = std::fs::read_to_string(&file).unwrap();
    assert!(written.contains("\"command\": \"parse\""));
    std::fs::remove_dir_all(&dir).ok();
    assert!(Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("specs/paper/paper.asl")
        .exists());
}

#[test]
fn parse_a_manifest_prints_the_grounded_domain() {
    let o = bdi_check(&["parse", "specs/kitchen/bdi-check.toml"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    // 3 locations x robotAt, 3 items x holding, 2 cups x 3 locations x cupAt, 2 x used,
    // 2 door states, 3 x dirty; 7 schemas over 3 locations or 2 cups; 5 x 5 x 2 x 2 states.
    let header = out.lines().next().unwrap();
    assert_eq!(
        header,
        "specs/kitchen/bdi-check.toml: 8 objects, 19 ground atoms, 19 ground actions, 100 initial states"
    );
    let o = bdi_check(&["parse", "--format", "json", "specs/kitchen/bdi-check.toml"]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let p = &v["files"][0];
    assert_eq!(p["kind"], "project");
    assert_eq!(p["atoms"].as_array().unwrap().len(), 19);
    assert_eq!(p["actions"].as_array().unwrap().len(), 19);
    assert_eq!(p["initial"]["count"], 100);
    let states = p["initial"]["states"].as_array().unwrap();
    assert_eq!(states.len(), 100);
    // Every initial state holds the facts and places each cup once.
    for s in states {
        let atoms: Vec<&str> = s
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap())
            .collect();
        assert!(atoms.contains(&"robotAt(table)") && atoms.contains(&"holding(none)"));
        for cup in ["cup1", "cup2"] {
            assert_eq!(
                atoms
                    .iter()
                    .filter(|a| a.starts_with(&format!("cupAt({cup},")))
                    .count(),
                1
            );
        }
    }
}

#[test]
fn parse_a_broken_project_locates_the_error_in_the_manifest() {
    let o = bdi_check(&["parse", "tests/project/unknown_type/bdi-check.toml"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.starts_with(
            "tests/project/unknown_type/bdi-check.toml:7:1: error[input]: `mug` is not a type"
        ),
        "{err}"
    );
    let o = bdi_check(&[
        "parse",
        "specs/paper/kitchen.pddl",
        "specs/paper/bdi-check.toml",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("parsed 2 files: no errors"));
}

#[test]
fn includes_look_along_the_source_path() {
    // Jason's `aslSourcePath`: beside the including file first, then each folder given.
    let agent = "tests/jason/47-include-source-path/agent.asl";
    let o = bdi_check(&["parse", agent]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("cannot include `common.asl`: no such file"),
        "{err}"
    );
    assert!(err.contains("source_path"), "{err}");
    let o = bdi_check(&[
        "parse",
        agent,
        "-I",
        "tests/jason/47-include-source-path/lib",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // The manifest's `[agent] source_path` does the same for a project.
    let o = bdi_check(&["parse", "tests/jason/47-include-source-path/bdi-check.toml"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn an_include_of_a_device_is_refused_not_read() {
    let dir = common::temp_dir("include-device");
    let agent = dir.join("a.asl");
    std::fs::write(&agent, "{ include(\"/dev/zero\") }\n+!g <- true.\n").unwrap();
    let o = bdi_check(&["parse", agent.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("cannot include `/dev/zero`: not a regular file"),
        "{err}"
    );
}

#[test]
fn a_timeout_must_be_a_number_of_seconds() {
    for bad in ["-1", "inf", "-inf", "NaN", "soon"] {
        let arg = format!("--timeout={bad}");
        let o = bdi_check(&["verify", "specs/paper", &arg]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
    }
}

#[test]
fn a_manifest_naming_a_device_says_so() {
    let dir = common::temp_dir("manifest-device");
    std::fs::write(
        dir.join("bdi-check.toml"),
        "[agent]\nplans = \"/dev/zero\"\nactions = \"x.pddl\"\n",
    )
    .unwrap();
    let o = bdi_check(&["parse", dir.join("bdi-check.toml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("`/dev/zero` is not a regular file"), "{err}");
}

#[test]
fn a_test_goal_on_an_undefined_predicate_is_a_lint_warning() {
    // Jason just fails `?nowhere(P)`: the project loads, and lint says it always fails.
    let o = bdi_check(&[
        "lint",
        "tests/jason/21-test-goal-undefined",
        "--format",
        "json",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let f: Vec<_> = r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == "undefined-predicate" && f["status"] == "fail")
        .collect();
    assert!(!f.is_empty(), "{r:#}");
    assert!(f.iter().all(|f| f["severity"] == "warning"));
    assert!(f[0]["message"].as_str().unwrap().contains("`nowhere/1`"));
}

#[test]
fn a_jason_jar_include_is_looked_for_along_the_source_path() {
    let dir = common::temp_dir("jason-jar");
    std::fs::create_dir_all(dir.join("res/inc")).unwrap();
    std::fs::write(dir.join("res/inc/lib.asl"), "+!g <- true.\n").unwrap();
    let agent = dir.join("a.asl");
    std::fs::write(&agent, "{ include(\"$jasonJar/inc/lib.asl\") }\n").unwrap();
    let a = agent.to_str().unwrap();
    let o = bdi_check(&["parse", a]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("a file of Jason's jar"));
    let res = dir.join("res");
    let o = bdi_check(&["parse", a, "-I", res.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_byte_order_mark_is_accepted_in_every_input() {
    // Editors on Windows may save UTF-8 with a BOM; the manifest always accepted one.
    let d = common::temp_dir("bom");
    let bom = "\u{feff}";
    let kitchen = Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
    for f in ["kitchen.asl", "kitchen.pddl", "bdi-check.toml"] {
        let text = std::fs::read_to_string(kitchen.join(f)).unwrap();
        std::fs::write(d.join(f), format!("{bom}{text}")).unwrap();
    }
    for f in ["kitchen.asl", "kitchen.pddl", "bdi-check.toml"] {
        let o = bdi_check(&["parse", d.join(f).to_str().unwrap()]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{f}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn replay_of_a_broken_report_names_the_place_once() {
    let d = common::temp_dir("replay-broken");
    let full = d.join("full.json");
    let o = bdi_check(&[
        "verify",
        "specs/paper",
        "--format",
        "json",
        "-o",
        full.to_str().unwrap(),
    ]);
    assert!(o.status.code().is_some());
    let text = std::fs::read_to_string(&full).unwrap();
    let trunc = d.join("trunc.json");
    std::fs::write(&trunc, &text[..text.len() / 2]).unwrap();
    let o = bdi_check(&["replay", trunc.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    let first = err.lines().next().unwrap_or("");
    assert_eq!(first.matches("error[").count(), 1, "{err}");
    // `file:line:column: error[...]`, the place given once.
    let place = first.split(": error[").next().unwrap();
    assert!(place.ends_with(|c: char| c.is_ascii_digit()), "{first}");
    assert_eq!(place.matches(':').count(), 2, "{first}");
    // A report of a project that no longer loads: the project's own diagnostics, as is.
    let moved = d.join("moved.json");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut v = v;
    v["project"] = serde_json::json!(d.join("gone").to_str().unwrap());
    std::fs::write(&moved, v.to_string()).unwrap();
    let o = bdi_check(&["replay", moved.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(
        err.lines().next().unwrap_or("").matches("error[").count(),
        1,
        "{err}"
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn what_a_run_leaves_out_is_said() {
    // A scenario beyond `[requests] max` runs, with a warning that verify does not cover it.
    let d = common::temp_dir("beyond-max");
    let sc = d.join("two.toml");
    std::fs::write(
        &sc,
        "initial = [\"robotAt(table)\", \"holding(none)\", \"cupAt(cup1,table)\"]\nrequests = [\"storeCup(cup1)\", \"storeCup(cup1)\"]\n",
    )
    .unwrap();
    let o = bdi_check(&["explain", "specs/paper", "--scenario", sc.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.contains("more than `[requests] max` (1)"), "{err}");
    let o = bdi_check(&[
        "explain",
        "specs/paper",
        "--scenario",
        sc.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(
        v["warnings"][0]
            .as_str()
            .unwrap()
            .contains("`verify` does not cover"),
        "{v:#}"
    );
    // An empty state graph says why.
    let o = bdi_check(&["graph", "specs/kitchen", "--states", "--max-states", "0"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stderr).contains("the state graph is empty"));
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn an_input_larger_than_bdi_check_reads_is_refused_where_it_is_named() {
    let d = common::temp_dir("huge-input");
    // A sparse file: no disk is used, nothing of it is read.
    let huge = d.join("huge.asl");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(bdi_check::syntax::source::MAX_INPUT_BYTES + 1)
        .unwrap();
    let agent = d.join("agent.asl");
    std::fs::write(&agent, "{ include(\"huge.asl\") }\n+!go <- ping.\n").unwrap();
    for (file, at) in [(&huge, "huge.asl:1:1"), (&agent, "agent.asl:1:")] {
        let o = bdi_check(&["parse", file.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("more than bdi-check reads (64 MiB)"), "{err}");
        assert!(err.contains(at), "{err}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn an_agent_given_as_the_project_is_named_for_what_it_is() {
    let o = bdi_check(&["verify", "specs/kitchen/kitchen.asl"]);
    assert_eq!(o.status.code(), Some(2));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("`specs/kitchen/kitchen.asl` is not a project: PROJECT is a folder holding a `bdi-check.toml`"),
        "{out}"
    );
    assert!(!out.contains("TOML"), "{out}");
}

#[test]
fn quiet_still_shows_bad_input() {
    let o = bdi_check(&["verify", "tests/project/unknown_type", "-q"]);
    assert_eq!(o.status.code(), Some(2));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("`mug` is not a type of the PDDL domain"),
        "{out}"
    );
}

#[test]
fn verify_denies_warnings_as_lint_does() {
    // The counter's coverage gap is a warning no run settles (the search is cut short).
    let o = bdi_check(&["verify", "tests/verify/counter_beyond", "-q"]);
    assert_eq!(o.status.code(), Some(3));
    let o = bdi_check(&[
        "verify",
        "tests/verify/counter_beyond",
        "-q",
        "--deny",
        "warnings",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let o = bdi_check(&["verify", "specs/kitchen", "-q", "--deny", "warnings"]);
    assert_eq!(o.status.code(), Some(0));
}

#[test]
fn colour_follows_the_flag_and_the_environment() {
    let run = |args: &[&str], env: &[(&str, &str)]| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_bdi-check"));
        c.args(args).current_dir(env!("CARGO_MANIFEST_DIR"));
        c.env_remove("NO_COLOR")
            .env_remove("CLICOLOR_FORCE")
            .env_remove("CLICOLOR");
        for (k, v) in env {
            c.env(k, v);
        }
        let o = c.output().expect("runs");
        String::from_utf8_lossy(&o.stdout).contains('\u{1b}')
    };
    let paper = ["verify", "specs/paper"];
    assert!(run(&[&paper[..], &["--color", "always"]].concat(), &[]));
    assert!(!run(&[&paper[..], &["--color", "never"]].concat(), &[]));
    // Not a terminal: no colour, unless forced; `NO_COLOR` wins.
    assert!(!run(&paper, &[]));
    assert!(run(&paper, &[("CLICOLOR_FORCE", "1")]));
    assert!(!run(&paper, &[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")]));
    // A report written to a file never holds escapes.
    let dir = common::temp_dir("colour").join("report.txt");
    let f = dir.to_str().unwrap();
    run(&[&paper[..], &["--color", "always", "-o", f]].concat(), &[]);
    assert!(!std::fs::read_to_string(&dir).unwrap().contains('\u{1b}'));
}

#[test]
fn the_catalogues_scenarios_paste_into_a_scenario_file() {
    let o = bdi_check(&["explain", "specs/paper"]);
    assert_eq!(o.status.code(), Some(0));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.trim() == "scenario:")
        .expect("a scenario");
    let sentence = lines[at - 1].trim().trim_matches('"').to_string();
    let file = common::temp_dir("pasted").join("scenario.toml");
    let toml = format!("{}\n{}\n", lines[at + 1].trim(), lines[at + 2].trim());
    std::fs::write(&file, toml).unwrap();
    let o = bdi_check(&[
        "explain",
        "specs/paper",
        "--scenario",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains(&sentence), "{}", stdout(&o));
    // `-q`: the count per user only.
    let q = stdout(&bdi_check(&["explain", "specs/paper", "-q"]));
    assert_eq!(q.lines().count(), 1, "{q}");
    assert!(q.contains("distinct explanations"), "{q}");
}

#[test]
fn the_reported_time_is_the_whole_runs_with_one_figure_per_phase() {
    let o = bdi_check(&["verify", "specs/kitchen", "--format", "json"]);
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let stats = &r["stats"];
    let phases = stats["phases"].as_array().expect("phases");
    let names: Vec<&str> = phases.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "lint",
            "search",
            "ltl search",
            "ltl product",
            "explanation:newcomer",
            "explanation:owner"
        ]
    );
    assert_eq!(phases[1]["states"], stats["states"]);
    assert!(phases[2]["states"].as_u64().unwrap() > 0);
    // Each phase is part of the run; those that ran one after the other take no longer
    // than it together. The products ran beside the searches after them, and say so.
    let total = stats["seconds"].as_f64().unwrap();
    let alone = |p: &&serde_json::Value| p.get("beside").is_none();
    let sum: f64 = phases
        .iter()
        .filter(alone)
        .map(|p| p["seconds"].as_f64().unwrap())
        .sum();
    assert!(total >= sum, "{stats:#}");
    assert!(
        phases
            .iter()
            .all(|p| p["seconds"].as_f64().unwrap() <= total),
        "{stats:#}"
    );
    let beside: Vec<&str> = phases[3]["beside"]
        .as_array()
        .expect("the products ran beside the searches")
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    assert_eq!(
        beside,
        ["ltl search", "explanation:newcomer", "explanation:owner"]
    );
    // The users' searches ran beside each other.
    for (i, other) in [(4, "explanation:owner"), (5, "explanation:newcomer")] {
        assert_eq!(phases[i]["beside"], serde_json::json!([other]), "{stats:#}");
    }
    assert_eq!(phases.iter().filter(alone).count(), phases.len() - 3);
    let o = bdi_check(&["verify", "specs/kitchen", "-v", "--color", "never"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.lines().any(|l| l.starts_with("phases: lint ")
            && l.contains("search ")
            && l.contains("beside ltl search and explanation:newcomer and explanation:owner")
            && l.contains("explanation:owner ")),
        "{out}"
    );
}

#[test]
fn the_progress_display_names_every_phase_in_turn() {
    let mut seen: Vec<String> = Vec::new();
    let run = bdi_check::commands::verify::run(
        Path::new("specs/kitchen"),
        &Default::default(),
        &Default::default(),
        |phase, _, _, _| {
            if seen.last().map(String::as_str) != Some(phase) {
                seen.push(phase.to_string());
            }
        },
    );
    assert!(run.report.stats.is_some());
    assert_eq!(
        seen,
        [
            "lint",
            "search",
            "ltl search",
            "explanation:newcomer, explanation:owner"
        ]
    );
}
