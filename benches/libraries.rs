//! Throughput on libraries nobody tuned for: `cargo bench --bench libraries`.
//!
//! Speed must not depend on who wrote the plan library (issue 16). This bench runs
//! `verify --no-symmetry --format json` (the release binary, one process per library) on
//! `specs/kitchen` with 4 cups and on generated store-cup libraries of 4 to 6 cups written
//! another way (one task, `max` = cups requests, contexts that bind the cup's place with
//! `cupAt(C, P) & P \== dishwasher`, plans that overlap for lint to confirm, a disjunctive
//! invariant), each with and without its explanation users, and prints per library the
//! states and states/s of the agent's search and of each user's search, and the whole
//! run's time. `-- --threads N` passes `--threads N` on.

use std::path::{Path, PathBuf};

#[path = "common/kitchen.rs"]
mod kitchen;

/// The generated store-cup library: a plan per door state and one for a stored cup.
const STORE_ASL: &str = r#"// A store-cup library written apart from specs/kitchen.
+!storeCup(C) : cupAt(C, P) & P \== dishwasher & holding(none) & dishwasherDoor(closed)
   <- navigateTo(dishwasher);
      openDoor(dishwasher);
      navigateTo(P);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C);
      closeDoor(dishwasher).
+!storeCup(C) : cupAt(C, P) & P \== dishwasher & holding(none) & not dishwasherDoor(closed)
   <- navigateTo(P);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C).
+!storeCup(C) : cupAt(C, dishwasher).
"#;

/// A folder with the store-cup library over `cups` cups (with a newcomer and a user who
/// knows the routine when `explain`).
fn store(cups: usize, explain: bool) -> PathBuf {
    let dir = std::env::temp_dir()
        .join("bdi-check-bench-libraries")
        .join(format!("store-{cups}-{explain}"));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        root.join("specs/kitchen/kitchen.pddl"),
        dir.join("kitchen.pddl"),
    )
    .expect("the kitchen's domain");
    std::fs::write(dir.join("store.asl"), STORE_ASL).expect("writable");
    let names: Vec<String> = (1..=cups).map(|i| format!("\"c{i}\"")).collect();
    let users = if explain {
        "\n[explanation]\nmodifies = \"syntactic\"\n\n[explanation.users.newcomer]\nexpected = []\n\n[explanation.users.regular]\nexpected = [[\"!storeCup(C)\", \"navigateTo(dishwasher)\"], [\"navigateTo(dishwasher)\", \"openDoor(dishwasher)\"], [\"pickUp(C)\", \"navigateTo(dishwasher)\"], [\"navigateTo(dishwasher)\", \"putDown(C)\"]]\n"
    } else {
        ""
    };
    let manifest = format!(
        "[agent]\nplans = \"store.asl\"\nactions = \"kitchen.pddl\"\n\n[objects]\ncup = [{}]\n\n[initial]\nfacts = [\"robotAt(table)\", \"holding(none)\"]\nvary = [\"cupAt\", \"dishwasherDoor\"]\nconstraints = [\".count(cupAt(C, _), 1)\", \".count(dishwasherDoor(_), 1)\"]\n\n[requests]\ngoals = [\"storeCup(C)\"]\nmax = {cups}\narrival = \"idle\"\n\n[invariants]\nhand = \".count(holding(_), 1)\"\ncup = \"(holding(C) & .count(cupAt(C, _), 0)) | (not holding(C) & .count(cupAt(C, _), 1))\"\n{users}\n[bounds]\nmax_states = 50_000_000\nmax_depth = 2_000\n",
        names.join(", ")
    );
    std::fs::write(dir.join("bdi-check.toml"), manifest).expect("writable");
    dir
}

/// `specs/kitchen` with `cups` cups (the reachable property naming every cup), with its
/// users when `explain` (as scale.rs).
fn kitchen(cups: usize, explain: bool) -> PathBuf {
    kitchen::project("libraries", cups, explain)
}

/// One `verify --no-symmetry` of `dir`: its JSON.
fn verify(dir: &Path, threads: Option<&str>) -> serde_json::Value {
    kitchen::verify_json(dir, &["--no-symmetry"], threads)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let threads = args
        .iter()
        .position(|a| a == "--threads")
        .map(|i| args.get(i + 1).expect("--threads N").as_str());
    let mut rows: Vec<(String, PathBuf)> = Vec::new();
    for explain in [false, true] {
        rows.push((
            format!("kitchen, 4 cups, users {explain}"),
            kitchen(4, explain),
        ));
        for cups in 4..=6 {
            rows.push((
                format!("store-cup, {cups} cups, users {explain}"),
                store(cups, explain),
            ));
        }
    }
    println!(
        "| library | phase | states | seconds | states/s |\n| --- | --- | ---: | ---: | ---: |"
    );
    for (name, dir) in rows {
        let v = verify(&dir, threads);
        let stats = &v["stats"];
        for p in stats["phases"].as_array().into_iter().flatten() {
            let (Some(states), Some(s)) = (p["states"].as_u64(), p["seconds"].as_f64()) else {
                continue;
            };
            println!(
                "| {name} | {} | {states} | {s:.2} | {:.0} |",
                p["name"].as_str().unwrap_or("?"),
                states as f64 / s.max(1e-9)
            );
        }
        println!(
            "| {name} | whole run ({}) | {} | {:.2} | |",
            v["verdict"].as_str().unwrap_or("?"),
            stats["states"],
            stats["seconds"].as_f64().unwrap_or(f64::NAN)
        );
    }
}
