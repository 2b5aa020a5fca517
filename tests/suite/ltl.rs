//! `ltl` properties and the BDI modalities (SPEC §1): a seeded defect per operator and
//! modality, found with a run that replays; LTL agreeing with `always` and `eventually`
//! where both can say the same; refusals with their place.

use crate::common;
use common::{bdi_check, phase_names, replay_finding as replay, temp_dir, verify_json};
use std::path::{Path, PathBuf};

/// A copy of the project `base` with `extra` appended to its manifest (relative paths to
/// the crate's specs made absolute).
fn project_with(tag: &str, base: &str, extra: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = temp_dir(tag);
    for e in std::fs::read_dir(root.join(base)).unwrap().flatten() {
        let to = dir.join(e.file_name());
        if e.path().is_file() {
            std::fs::copy(e.path(), &to).unwrap();
        }
    }
    let manifest = dir.join("bdi-check.toml");
    let text = std::fs::read_to_string(&manifest).unwrap();
    let specs = format!("\"{}/specs/", root.display());
    let text = text.replace("\"../../../specs/", &specs);
    std::fs::write(&manifest, format!("{text}\n{extra}")).unwrap();
    dir
}

fn property(name: &str, key: &str, formula: &str) -> String {
    format!("[[property]]\nname = \"{name}\"\n{key} = \"{formula}\"\n")
}

fn finding<'r>(r: &'r serde_json::Value, id: &str) -> &'r serde_json::Value {
    r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["id"] == id)
        .unwrap_or_else(|| panic!("no {id} in {r:#}"))
}

/// Each operator and modality: a formula this agent satisfies, or one it violates.
const CASES: &[(&str, &str, bool)] = &[
    ("always", "[] .count(robotAt(_), 1)", true),
    ("always", "[] robotAt(table)", false),
    ("eventually", "<> not dirty(table)", false),
    ("leads-to", "requested(wipeTable) ~> not dirty(table)", true),
    ("leads-to", "requested(rest) ~> not dirty(table)", false),
    (
        "until",
        "dirty(table) U (did(wipe(table)) | [] dirty(table))",
        true,
    ),
    ("until", "dirty(table) U did(wipe(table))", false),
    ("weak-until", "dirty(table) W did(wipe(table))", true),
    ("weak-until", "robotAt(table) W did(wipe(table))", false),
    (
        "release",
        "did(wipe(table)) R (dirty(table) | did(wipe(table)))",
        true,
    ),
    ("release", "did(wipe(table)) R dirty(table)", false),
    ("next", "X robotAt(table)", true),
    (
        "next",
        "[] (did(navigateTo(table)) -> X robotAt(cupboard))",
        false,
    ),
    (
        "iff",
        "[] (believes(dirty(table)) <-> holds(dirty(table)))",
        true,
    ),
    (
        "iff",
        "[] (robotAt(cupboard) <-> did(navigateTo(cupboard)))",
        false,
    ),
    (
        "implies",
        "[] (requested(rest) -> <> did(wipe(table)))",
        false,
    ),
    ("and", "<> requested(wipeTable) & <> requested(rest)", false),
    (
        "or",
        "[] (dirty(table) | did(wipe(table)) | not intends(wipeTable))",
        true,
    ),
    ("not", "not <> did(navigateTo(cupboard))", false),
    (
        "intends",
        "[] (intends(wipeTable) -> requested(wipeTable))",
        true,
    ),
    ("intends", "<> intends(rest)", false),
    ("desires", "[] not desires(rest)", false),
    ("did", "[] not did(wipe(table))", false),
    ("requested", "[] not requested(wipeTable)", false),
    (
        "agent",
        "[] (believes(agent, dirty(table)) -> holds(dirty(table)))",
        true,
    ),
];

#[test]
fn a_seeded_defect_per_operator_and_modality_is_found_and_replays() {
    for (i, (what, formula, holds)) in CASES.iter().enumerate() {
        let dir = project_with(
            &format!("ltl-case-{i}"),
            "tests/verify/ltl_table",
            &property("p", "ltl", formula),
        );
        let (code, r, file) = verify_json(dir.to_str().unwrap(), &format!("ltl-report-{i}"));
        let f = finding(&r, "property:p");
        let context = format!("{what}: {formula}: {f:#}");
        if *holds {
            assert_eq!(f["status"], "pass", "{context}");
            assert_eq!(code, 0, "{context}");
            continue;
        }
        assert_eq!(f["status"], "fail", "{context}");
        assert_eq!(code, 1, "{context}");
        assert!(f["counterexample"].is_object(), "{context}");
        let (rc, out) = replay(&file, "property:p");
        assert_eq!(rc, 1, "{context}: {out}");
        assert!(
            out.contains("still reaches its violation"),
            "{context}: {out}"
        );
    }
}

/// A run that loops for ever: the counterexample is a lasso whose loop replays.
#[test]
fn a_violation_on_a_loop_is_a_lasso_that_replays() {
    let dir = project_with(
        "ltl-lasso",
        "tests/verify/livelock",
        &property("rests", "ltl", "<> [] robotAt(table)"),
    );
    let (_, r, file) = verify_json(dir.to_str().unwrap(), "ltl-lasso-report");
    let f = finding(&r, "property:rests");
    assert_eq!(f["status"], "fail", "{f:#}");
    let c = &f["counterexample"];
    let steps = c["steps"].as_array().unwrap().len();
    let start = c["loop_start"].as_u64().unwrap_or_else(|| panic!("{f:#}")) as usize;
    assert!(start < steps, "{f:#}");
    assert_eq!(replay(&file, "property:rests").0, 1);
}

/// Where `always`/`eventually` and `ltl` can say the same, they say the same, and a
/// violated `always` has a run of the same length both ways (both are shortest).
#[test]
fn ltl_agrees_with_always_and_eventually() {
    let table = [
        property("a1", "always", "not robotAt(cupboard)"),
        property("a2", "always", ".count(robotAt(_), 1)"),
        property("e1", "eventually", "robotAt(table)"),
        property("e2", "eventually", "not dirty(table)"),
        property("e3", "eventually", "robotAt(cupboard) | not dirty(table)"),
    ]
    .concat();
    let projects = [
        ("specs/kitchen", String::new()),
        ("tests/verify/invariant", String::new()),
        ("tests/verify/eventually", String::new()),
        ("tests/verify/ltl_table", table),
    ];
    let mut compared = 0;
    for (k, (base, own)) in projects.iter().enumerate() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(root.join(base).join("bdi-check.toml")).unwrap();
        let text = format!("{text}\n{own}");
        let m: toml::Value = toml::from_str(&text).unwrap();
        let mut twins = String::new();
        let mut pairs = Vec::new();
        let props = m.get("property").and_then(|p| p.as_array()).cloned();
        for p in props.unwrap_or_default() {
            let name = p["name"].as_str().unwrap();
            for (key, op) in [("always", "[]"), ("eventually", "<>")] {
                if let Some(f) = p.get(key).and_then(|f| f.as_str()) {
                    let twin = format!("{name}_ltl");
                    twins.push_str(&property(&twin, "ltl", &format!("{op} ({f})")));
                    pairs.push((name.to_string(), twin, key));
                }
            }
        }
        // The invariants too, as `always` and as `[]`.
        if let Some(inv) = m.get("invariants").and_then(|i| i.as_table()) {
            for (name, f) in inv {
                let f = f.as_str().unwrap();
                twins.push_str(&property(&format!("{name}_always"), "always", f));
                twins.push_str(&property(
                    &format!("{name}_ltl"),
                    "ltl",
                    &format!("[] ({f})"),
                ));
                pairs.push((format!("{name}_always"), format!("{name}_ltl"), "always"));
            }
        }
        let dir = project_with(&format!("ltl-twin-{k}"), base, &format!("{own}{twins}"));
        let (_, r, _) = verify_json(
            &format!("{}", dir.display()),
            &format!("ltl-twin-report-{k}"),
        );
        for (a, b, key) in pairs {
            let fa = finding(&r, &format!("property:{a}"));
            let fb = finding(&r, &format!("property:{b}"));
            assert_eq!(fa["status"], fb["status"], "{base}: {fa:#} {fb:#}");
            if key == "always" && fa["status"] == "fail" {
                let len =
                    |f: &serde_json::Value| f["counterexample"]["steps"].as_array().unwrap().len();
                assert_eq!(len(fa), len(fb), "{base}: {fa:#} {fb:#}");
            }
            compared += 1;
        }
    }
    assert!(compared >= 12, "{compared}");
}

/// `.intend` and `.desire` in `always`, `eventually` and `reachable` (SPEC §1), with
/// Jason's meaning.
#[test]
fn intend_and_desire_work_in_state_properties() {
    let extra = [
        property(
            "busy_means_asked",
            "always",
            "not .intend(rest) | requested(rest)",
        ),
        property("never_intends_wiping", "always", "not .intend(wipeTable)"),
        property("wants_rest", "reachable", ".desire(rest) & robotAt(table)"),
        property("stops_wanting_rest", "eventually", "not .desire(rest)"),
    ]
    .concat();
    let dir = project_with("ltl-intend", "tests/verify/ltl_table", &extra);
    let (_, r, file) = verify_json(dir.to_str().unwrap(), "ltl-intend-report");
    assert_eq!(finding(&r, "property:busy_means_asked")["status"], "pass");
    let f = finding(&r, "property:never_intends_wiping");
    assert_eq!(f["status"], "fail", "{f:#}");
    assert_eq!(replay(&file, "property:never_intends_wiping").0, 1);
    let f = finding(&r, "property:wants_rest");
    assert_eq!(f["status"], "pass", "{f:#}");
    assert!(f["counterexample"].is_object(), "a witness run: {f:#}");
    assert_eq!(finding(&r, "property:stops_wanting_rest")["status"], "pass");
}

/// What a property cannot say is refused with its place, exit 2.
#[test]
fn unsupported_and_malformed_formulas_are_refused_with_their_place() {
    let cases = [
        (
            "[] explained(owner, wipe(table))",
            "names a user of `[explanation.users]`",
        ),
        (
            "[] believes(robot, dirty(table))",
            "names an agent this project does not have",
        ),
        ("[] (dirty(table) -> )", "expected a state formula"),
        ("[] unknown(table)", "unknown predicate `unknown`"),
        ("<> believes(unknwn(table))", "is not a predicate"),
        ("[] .count(intends(rest), 1)", "a modality can be combined"),
    ];
    for (i, (formula, message)) in cases.iter().enumerate() {
        let dir = project_with(
            &format!("ltl-bad-{i}"),
            "tests/verify/ltl_table",
            &property("p", "ltl", formula),
        );
        let o = bdi_check(&["verify", dir.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(2), "{formula}: {out}{err}");
        let all = format!("{out}{err}");
        assert!(all.contains(message), "{formula}: {all}");
        assert!(all.contains("bdi-check.toml:"), "{formula}: {all}");
    }
}

/// The kitchen's properties hold; without the tasks' closing of the dishwasher door, the
/// owner's door property fails with a run that replays, and the others still hold.
#[test]
fn the_kitchen_closes_the_door_it_opens() {
    let (code, r, _) = verify_json("specs/kitchen", "ltl-kitchen");
    assert_eq!(code, 0, "{r:#}");
    let names = [
        "every_used_cup_is_stored",
        "door_closed_after_the_last_request",
        "no_cup_in_hand_while_wiping",
        "never_runs_with_the_door_open",
    ];
    for n in names {
        assert_eq!(
            finding(&r, &format!("property:{n}"))["status"],
            "pass",
            "{n}"
        );
    }
    let dir = project_with("ltl-kitchen-open", "specs/kitchen", "");
    let asl = dir.join("kitchen.asl");
    let text = std::fs::read_to_string(&asl).unwrap();
    let open = text.replace(";\n      !closeDishwasherIfNeed.", ".");
    assert_ne!(open, text);
    std::fs::write(&asl, open).unwrap();
    let (code, r, file) = verify_json(dir.to_str().unwrap(), "ltl-kitchen-open-report");
    assert_eq!(code, 1, "{r:#}");
    let f = finding(&r, "property:door_closed_after_the_last_request");
    assert_eq!(f["status"], "fail", "{f:#}");
    assert_eq!(
        replay(&file, "property:door_closed_after_the_last_request").0,
        1
    );
    for n in names.iter().filter(|n| !n.starts_with("door")) {
        assert_eq!(
            finding(&r, &format!("property:{n}"))["status"],
            "pass",
            "{n}"
        );
    }
}

/// A formula whose automaton would take unbounded time is undecided (exit 3), quickly,
/// never a pass.
#[test]
fn a_formula_too_long_to_translate_is_undecided() {
    let part = "(robotAt(table) | X dirty(table))";
    let formula = vec![part; 14].join(" U ");
    let dir = project_with(
        "ltl-too-long",
        "tests/verify/ltl_table",
        &property("p", "ltl", &formula),
    );
    let (code, r, _) = verify_json(dir.to_str().unwrap(), "ltl-too-long-report");
    let f = finding(&r, "property:p");
    assert_eq!(f["status"], "unknown", "{f:#}");
    assert!(f["message"].as_str().unwrap().contains("too long"), "{f:#}");
    assert_eq!(code, 3, "{r:#}");
}

/// `explained(user, a)` is decided on the user's explanation search: the newcomer is told
/// of every pick-up as it happens; the owner is told of one on a detour, a run that
/// replays (on the owner's search too: without the explanations it would not).
#[test]
fn explained_is_decided_on_the_users_explanation_search() {
    let extra = [
        property(
            "newcomer_told",
            "ltl",
            "[] (did(pickUp(C)) -> explained(newcomer, pickUp(C)))",
        ),
        property(
            "owner_never_told",
            "ltl",
            "[] not explained(owner, pickUp(C))",
        ),
    ]
    .concat();
    let dir = project_with("ltl-explained", "specs/kitchen", &extra);
    let (code, r, file) = verify_json(dir.to_str().unwrap(), "ltl-explained-report");
    assert_eq!(code, 1, "{r:#}");
    assert_eq!(finding(&r, "property:newcomer_told")["status"], "pass");
    let f = finding(&r, "property:owner_never_told");
    assert_eq!(f["status"], "fail", "{f:#}");
    let told = f["counterexample"]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .any(|s| s["kind"] == "explanation" && s["text"].as_str().unwrap().contains("pick up"));
    assert!(told, "the run shows the explanation: {f:#}");
    let (rc, out) = replay(&file, "property:owner_never_told");
    assert_eq!(rc, 1, "{out}");
    let phases = phase_names(&r);
    assert!(phases.contains(&"ltl search:owner"), "{phases:?}");
    // Two users in one property cannot be decided on one search.
    let two = property(
        "both",
        "ltl",
        "[] (explained(owner, pickUp(C)) -> explained(newcomer, pickUp(C)))",
    );
    let dir = project_with("ltl-explained-two", "specs/kitchen", &two);
    let o = bdi_check(&["verify", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let out = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(out.contains("may name one user"), "{out}");
}

/// Under symmetry (tests/verify/symmetric_order: three interchangeable cups), every run
/// property gets the verdict, message and run of the exact search, and each run replays:
/// a formula no renaming changes is decided on the reduced graph (where a loop may come
/// back to a renaming of its entry: the run goes round until the state itself comes back),
/// one that names cups on a graph reduced by the renamings that fix them. Which cup the
/// robot takes depends on its name (Jason's belief order), so an instance holding for
/// `cup1` says nothing of `cup2`: every instance is decided.
#[test]
fn run_properties_under_symmetry_agree_with_the_exact_search() {
    let renamed_alike = [
        property("rotation_stops", "ltl", "<> [] not intends(rotate)"),
        property("lets_go", "ltl", "[] <> holding(none)"),
        property("takes_a_cup", "ltl", "requested(grab) ~> not holding(none)"),
        property(
            "keeps_grabbing",
            "always",
            "not intends(grab) | .desire(grab)",
        ),
    ]
    .concat();
    let cup1 = [
        property("cup1_settles", "ltl", "<> [] not holding(cup1)"),
        property("cup1_taken", "reachable", "did(pickUp(cup1))"),
    ]
    .concat();
    let every = [
        property("holds_no_cup", "ltl", "[] (holding(C) -> C == none)"),
        property(
            "takes_cup3",
            "ltl",
            "[] (requested(grab) -> <> holding(cup3))",
        ),
        property(
            "takes_cup2",
            "ltl",
            "[] (requested(grab) -> <> holding(cup2))",
        ),
    ]
    .concat();
    let sets = [
        (renamed_alike.clone(), None),
        (
            format!("{renamed_alike}{cup1}"),
            Some("ltl search (cup1 fixed)"),
        ),
        (format!("{renamed_alike}{cup1}{every}"), Some("ltl search")),
    ];
    let mut failed = 0;
    for (k, (props, own)) in sets.iter().enumerate() {
        let dir = project_with(
            &format!("ltl-sym-{k}"),
            "tests/verify/symmetric_order",
            props,
        );
        let dir = dir.to_str().unwrap();
        let (_, sym, file) = verify_json(dir, &format!("ltl-sym-report-{k}"));
        let (_, exact, _) = common::report_json(
            &["verify", dir, "--no-symmetry"],
            &format!("ltl-sym-exact-{k}"),
        );
        let phases = phase_names(&sym);
        let searches: Vec<&&str> = phases
            .iter()
            .filter(|p| p.starts_with("ltl search"))
            .collect();
        assert_eq!(searches, own.iter().collect::<Vec<_>>(), "{phases:?}");
        let states = |r: &serde_json::Value| r["stats"]["states"].as_u64().unwrap();
        assert!(states(&sym) < states(&exact), "the reduction reduces");
        for e in exact["findings"].as_array().unwrap() {
            let id = e["id"].as_str().unwrap();
            if !id.starts_with("property:") {
                continue;
            }
            let s = finding(&sym, id);
            assert_eq!(s["status"], e["status"], "{s:#} {e:#}");
            // A passing `always` counts the states of the graph it was decided on.
            let said = |f: &serde_json::Value| {
                let m = f["message"].as_str().unwrap().to_string();
                match m.split_once(" holds in all ") {
                    Some((name, _)) => format!("{name} holds in all reached states"),
                    None => m,
                }
            };
            assert_eq!(said(s), said(e), "{s:#} {e:#}");
            let cx = |f: &serde_json::Value| {
                let c = &f["counterexample"];
                (c["steps"].as_array().map(Vec::len), c["loop_start"].clone())
            };
            assert_eq!(cx(s), cx(e), "{s:#} {e:#}");
            if s["status"] == "fail" && s["counterexample"].is_object() {
                let (rc, out) = replay(&file, id);
                assert_eq!(rc, 1, "{id}: {out}");
                assert!(out.contains("still reaches its violation"), "{id}: {out}");
                failed += 1;
            }
        }
    }
    // The rotation's loop is one round on the reduced graph and two in the real run.
    let dir = project_with(
        "ltl-sym-loop",
        "tests/verify/symmetric_order",
        &renamed_alike,
    );
    let (_, r, _) = verify_json(dir.to_str().unwrap(), "ltl-sym-loop-report");
    let f = finding(&r, "property:rotation_stops");
    assert!(
        f["message"].as_str().unwrap().contains("a loop of 8 steps"),
        "{f:#}"
    );
    let start = f["counterexample"]["loop_start"].as_u64().unwrap() as usize;
    let mut picked: Vec<String> = common::steps(f)[start..]
        .iter()
        .filter(|s| s.contains("pickUp"))
        .cloned()
        .collect();
    picked.sort();
    picked.dedup();
    assert_eq!(picked.len(), 2, "{f:#}");
    assert!(failed >= 8, "{failed}");
}

/// `graph --states` marks the states an `always` with a modality fails in, as it marks
/// those of a plain `always`, and says which it cannot mark (those reading steps).
#[test]
fn the_state_graph_marks_where_a_modal_always_fails() {
    let marked = |extra: &str, tag: &str| {
        let dir = project_with(tag, "tests/verify/ltl_table", extra);
        let o = bdi_check(&["graph", dir.to_str().unwrap(), "--states"]);
        assert_eq!(o.status.code(), Some(0));
        let dot = String::from_utf8_lossy(&o.stdout).into_owned();
        let note = String::from_utf8_lossy(&o.stderr).into_owned();
        (dot.matches("fillcolor=\"#f4cccc\"").count(), note)
    };
    let (none, _) = marked("", "graph-modal-none");
    assert_eq!(none, 0);
    let intends = property("never_wipes", "always", "not .intend(wipeTable)");
    let (some, note) = marked(&intends, "graph-modal-intend");
    assert!(some > 0, "{note}");
    assert!(note.is_empty(), "{note}");
    let did = property("no_wiping", "always", "not did(wipe(table))");
    let (_, note) = marked(&format!("{intends}{did}"), "graph-modal-did");
    assert!(note.contains("`no_wiping` fails are not marked"), "{note}");
}

/// On the agent's exact graph the products take the cores the users' searches free, a
/// property at a time, each on the thread of a search that ended: with both users, on one
/// thread or two, every property of the kitchen is decided once, with the same verdict
/// and message.
#[test]
fn beside_the_users_every_property_is_decided_once_on_any_number_of_threads() {
    let decided = |threads: &str| {
        let (code, r, _) = common::report_json(
            &[
                "verify",
                "specs/kitchen",
                "--no-symmetry",
                "--threads",
                threads,
            ],
            &format!("ltl-users-threads-{threads}"),
        );
        assert_eq!(code, 0, "{r:#}");
        let phases = phase_names(&r);
        for p in ["ltl product", "explanation:newcomer", "explanation:owner"] {
            assert!(phases.contains(&p), "{threads} threads: {phases:?}");
        }
        let mut props: Vec<(String, String, String)> = (r["findings"].as_array().unwrap())
            .iter()
            .filter(|f| f["id"].as_str().unwrap().starts_with("property:"))
            .map(|f| {
                let s = |k: &str| f[k].as_str().unwrap_or_default().to_string();
                (s("id"), s("status"), s("message"))
            })
            .collect();
        props.sort();
        props
    };
    let one = decided("1");
    let names: Vec<&str> = one.iter().map(|(id, _, _)| id.as_str()).collect();
    let manifest = std::fs::read_to_string("specs/kitchen/bdi-check.toml").unwrap();
    let declared = manifest.matches("[[property]]").count();
    assert_eq!(names.len(), declared, "one finding per property: {names:?}");
    let mut distinct = names.clone();
    distinct.dedup();
    assert_eq!(distinct, names, "each property once");
    assert_eq!(decided("2"), one);
    assert_eq!(decided("3"), one);
}
