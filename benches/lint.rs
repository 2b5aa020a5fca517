//! Lint time on the kitchen as the number of cups grows: `cargo bench --bench lint`.
//!
//! Each size is a generated project (the kitchen's plans and PDDL domain, n cups) in a
//! temporary folder. The initial states are fixed but for the door, so that loading stays
//! cheap and the time measured is lint's. Prints one line per size.

use bdi_check::findings::Status;
use bdi_check::model::project::load_project;
use bdi_check::smt::{lint, LintOptions};
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
        let project = match load_project(&dir) {
            Ok(p) => p,
            Err(e) => panic!("the generated project does not load: {:?}", e.diagnostics),
        };
        let start = Instant::now();
        let findings = lint(&project, &LintOptions::default());
        let seconds = start.elapsed().as_secs_f64();
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
    let _ = std::fs::remove_dir_all(&root);
}
