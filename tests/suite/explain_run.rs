//! `bdi-check explain` as users run it: the paper's scenario gives the paper's explanation,
//! and the catalogue lists what the robot can say, each with a scenario that produces it.

use std::process::Output;

use crate::common;
use common::bdi_check;

fn json(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("JSON")
}

fn strings(v: &serde_json::Value) -> Vec<&str> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect()
}

#[test]
fn the_papers_scenario_gives_the_papers_explanation() {
    let o = bdi_check(&[
        "explain",
        "specs/paper",
        "--scenario",
        "tests/scenarios/paper_door_closed.toml",
        "--user",
        "owner",
        "--format",
        "json",
    ]);
    let r = json(&o);
    let first = &r["explanations"][0];
    assert_eq!(first["user"], "owner");
    assert_eq!(first["action"], "navigateTo(dishwasher)");
    assert_eq!(first["after"], "!storeCup(cup1)");
    // The paper's content: Γ from storeUsedCup and openDishwasherIfNeed, and the actions up
    // to openDoor(dishwasher), the first that changes Γ.
    assert_eq!(
        strings(&first["context"]),
        ["used(cup1)", "not dishwasherDoor(open)", "holding(none)"]
    );
    assert_eq!(
        strings(&first["actions"]),
        ["navigateTo(dishwasher)", "openDoor(dishwasher)"]
    );
    assert_eq!(
        first["text"],
        "I go to the dishwasher because cup1 is used, the dishwasher door is not open and my hands are free: I want to open the dishwasher."
    );
    // The owner expects !storeCup(C) -> navigateTo(table), not navigateTo(dishwasher); the
    // explanation stands right before the action in the trace.
    let steps = r["trace"]["steps"].as_array().unwrap();
    let i = steps
        .iter()
        .position(|s| s["kind"] == "explanation")
        .unwrap();
    assert_eq!(steps[i + 1]["text"], "navigateTo(dishwasher)");
    assert_eq!(r["trace"]["outcome"], "done");
}

#[test]
fn a_newcomer_is_surprised_by_every_first_step_and_learns() {
    let o = bdi_check(&[
        "explain",
        "specs/kitchen",
        "--scenario",
        "tests/scenarios/paper_door_closed.toml",
        "--user",
        "newcomer",
        "--format",
        "json",
    ]);
    let r = json(&o);
    let actions: Vec<&str> = r["explanations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["action"].as_str().unwrap())
        .collect();
    // Every pair is new to the newcomer: each of the eight actions is explained once (the
    // last two close the door the robot opened).
    assert_eq!(
        actions,
        [
            "navigateTo(dishwasher)",
            "openDoor(dishwasher)",
            "navigateTo(table)",
            "pickUp(cup1)",
            "navigateTo(dishwasher)",
            "putDown(cup1)",
            "navigateTo(dishwasher)",
            "closeDoor(dishwasher)"
        ]
    );
    // The owner, who knows the routine, is only told about the detour.
    let o = bdi_check(&[
        "explain",
        "specs/kitchen",
        "--scenario",
        "tests/scenarios/paper_door_closed.toml",
        "--user",
        "owner",
        "--format",
        "json",
    ]);
    let owner = json(&o)["explanations"].as_array().unwrap().len();
    assert!(owner < actions.len(), "{owner}");
}

#[test]
fn the_catalogue_lists_distinct_explanations_with_scenarios() {
    let o = bdi_check(&["explain", "specs/paper", "--format", "json"]);
    let r = json(&o);
    let entries = r["explanations"].as_array().unwrap();
    assert!(!entries.is_empty());
    // Distinct, and each with a scenario whose run gives it.
    for (i, e) in entries.iter().enumerate() {
        for f in &entries[i + 1..] {
            assert!(e != f);
        }
        let dir = common::temp_dir(&format!("catalogue-{i}"));
        let quote = |v: &serde_json::Value| {
            strings(v)
                .iter()
                .map(|s| format!("{s:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let file = dir.join("s.toml");
        std::fs::write(
            &file,
            format!(
                "initial = [{}]\nrequests = [{}]\n",
                quote(&e["scenario"]["initial"]),
                quote(&e["scenario"]["requests"])
            ),
        )
        .unwrap();
        let user = e["user"].as_str().unwrap();
        let o = bdi_check(&[
            "explain",
            "specs/paper",
            "--scenario",
            file.to_str().unwrap(),
            "--user",
            user,
            "--format",
            "json",
        ]);
        let run = json(&o);
        let text = e["text"].as_str().unwrap();
        assert!(
            run["explanations"]
                .as_array()
                .unwrap()
                .iter()
                .any(|g| g["text"] == text),
            "{text} not given by its scenario"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn explain_refuses_bad_scenarios_with_exit_2() {
    let dir = common::temp_dir("bad-scenario");
    let file = dir.join("s.toml");
    std::fs::write(
        &file,
        "initial = [\"robotAt(kitchen)\"]\nrequests = [\"fly\"]\n",
    )
    .unwrap();
    let o = bdi_check(&[
        "explain",
        "specs/paper",
        "--scenario",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("s.toml:1:"), "{err}");
    assert!(err.contains("robotAt(kitchen)"), "{err}");
    assert_eq!(
        bdi_check(&["explain", "specs/paper", "--user", "nobody"])
            .status
            .code(),
        Some(2)
    );
}
