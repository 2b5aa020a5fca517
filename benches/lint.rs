//! Lint time as the domain and the library grow: `cargo bench --bench lint`.
//!
//! Each size is a generated project in a temporary folder, with the kitchen's PDDL domain:
//! first the kitchen's plans with n cups (the initial states fixed but for the door, so that
//! loading stays cheap and the time measured is lint's), then libraries of 500 to 2,000
//! plans of three shapes (a chain of subgoals, independent requests, one trigger's plans
//! hiding each other), whose time per plan must not grow with their size (issue 18).
//! Prints one line per size.

use bdi_check::findings::Status;
use bdi_check::model::project::{load_project, Project};
use bdi_check::smt::{lint, LintFinding, LintOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn manifest(cups: usize, specs: &Path) -> String {
    let names: Vec<String> = (1..=cups).map(|i| format!("\"cup{i}\"")).collect();
    let on_table: Vec<String> = (1..=cups)
        .map(|i| format!("\"cupAt(cup{i}, table)\""))
        .collect();
    format!(
        r#"[agent]
plans = "kitchen.asl"
actions = "{pddl}"

[objects]
cup = [{names}]

[initial]
facts = ["robotAt(table)", "holding(none)", {on_table}]
vary = ["dishwasherDoor"]
constraints = [".count(dishwasherDoor(_), 1)"]

[requests]
goals = ["storeCup(C)", "putAway(C)", "runDishwasher", "unloadDishwasher", "wipeTable"]
max = 2

[invariants]
one_location = ".count(robotAt(_), 1)"
one_item_in_hand = ".count(holding(_), 1)"
cup_held_or_in_one_place = "(holding(C) & .count(cupAt(C, _), 0)) | (not holding(C) & .count(cupAt(C, _), 1))"
door_open_or_closed = ".count(dishwasherDoor(_), 1)"
"#,
        pddl = specs.join("kitchen.pddl").display(),
        names = names.join(", "),
        on_table = on_table.join(", "),
    )
}

fn main() {
    let specs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
    let root = std::env::temp_dir().join(format!("bdi-check-lint-bench-{}", std::process::id()));
    for cups in [2usize, 10, 50] {
        let dir = root.join(format!("kitchen-{cups}"));
        std::fs::create_dir_all(&dir).expect("temporary folder");
        std::fs::copy(specs.join("kitchen.asl"), dir.join("kitchen.asl")).expect("copy plans");
        std::fs::write(dir.join("bdi-check.toml"), manifest(cups, &specs)).expect("manifest");
        let (project, findings, seconds) = load_and_lint(&dir);
        let count = |s: Status| findings.iter().filter(|f| f.finding.status == s).count();
        println!(
            "lint kitchen with {cups:>2} cups ({:>4} atoms, {:>3} ground actions): {seconds:>7.3} s, {} failed, {} passed, {} undecided",
            project.atoms.len(),
            project.actions.len(),
            count(Status::Fail),
            count(Status::Pass),
            count(Status::Unknown),
        );
    }
    for shape in [Shape::Chain, Shape::Flat, Shape::OneTrigger] {
        for plans in [500usize, 1000, 2000] {
            let dir = root.join(format!("{shape:?}-{plans}"));
            std::fs::create_dir_all(&dir).expect("temporary folder");
            let (asl, goals) = library(shape, plans);
            std::fs::write(dir.join("agent.asl"), asl).expect("plans");
            std::fs::write(dir.join("bdi-check.toml"), library_manifest(&goals, &specs))
                .expect("manifest");
            let (_, findings, seconds) = load_and_lint(&dir);
            println!(
                "lint {shape:?} library of {plans:>4} plans: {seconds:>7.3} s, {:>5.2} ms per plan, {} findings",
                seconds * 1000.0 / plans as f64,
                findings.len(),
            );
        }
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// Loads a generated project and lints it: the project, the findings and lint's seconds.
fn load_and_lint(dir: &Path) -> (Project, Vec<LintFinding>, f64) {
    let project = match load_project(dir) {
        Ok(p) => p,
        Err(e) => panic!("the generated project does not load: {:?}", e.diagnostics),
    };
    let start = Instant::now();
    let findings = lint(&project, &LintOptions::default());
    let seconds = start.elapsed().as_secs_f64();
    (project, findings, seconds)
}

/// How a generated library's plans relate.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// Goal i has two plans with complementary contexts; the first posts goal i + 1.
    Chain,
    /// Every plan is the only one of its own requested goal.
    Flat,
    /// All plans are for one goal, with the same context: each hides the next.
    OneTrigger,
}

/// A library of `n` plans of `shape` over the kitchen's domain, and the goals requested.
fn library(shape: Shape, n: usize) -> (String, Vec<String>) {
    let mut asl = String::new();
    let mut goals = Vec::new();
    match shape {
        Shape::Chain => {
            for i in 0..n / 2 {
                let next = if i + 1 < n / 2 {
                    format!("; !task{}(C)", i + 1)
                } else {
                    String::new()
                };
                asl += &format!(
                    "+!task{i}(C) : used(C) & not cupAt(C, dishwasher) <- navigateTo(table){next}.\n\
                     +!task{i}(C) : not used(C) | cupAt(C, dishwasher) <- navigateTo(cupboard).\n"
                );
            }
            goals.push("task0(C)".to_string());
        }
        Shape::Flat => {
            for i in 0..n {
                asl += &format!("+!task{i}(C) : used(C) <- navigateTo(table).\n");
                goals.push(format!("task{i}(C)"));
            }
        }
        Shape::OneTrigger => {
            for _ in 0..n {
                asl += "+!task(C) : used(C) & cupAt(C, table) <- navigateTo(table).\n";
            }
            goals.push("task(C)".to_string());
        }
    }
    (asl, goals)
}

fn library_manifest(goals: &[String], specs: &Path) -> String {
    let goals: Vec<String> = goals.iter().map(|g| format!("\"{g}\"")).collect();
    format!(
        r#"[agent]
plans = "agent.asl"
actions = "{pddl}"

[objects]
cup = ["cup1", "cup2"]

[initial]
facts = ["robotAt(table)", "holding(none)", "cupAt(cup1, table)", "cupAt(cup2, table)", "dishwasherDoor(closed)"]
vary = ["used"]

[requests]
goals = [{goals}]
max = 1

[invariants]
one_location = ".count(robotAt(_), 1)"
"#,
        pddl = specs.join("kitchen.pddl").display(),
        goals = goals.join(", "),
    )
}
