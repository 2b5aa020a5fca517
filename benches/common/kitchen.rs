//! What the benches share: `specs/kitchen` with n cups.

use std::path::{Path, PathBuf};

/// The kitchen manifest with `cups` cups; without the explanation users unless `explain`,
/// and without its `ltl` properties (the ltl bench measures those; the other benches keep
/// the figures they were recorded with).
#[allow(dead_code)] // Each bench includes this file; not every bench writes a manifest alone.
pub fn manifest(cups: usize, explain: bool) -> String {
    manifest_with(cups, explain, false)
}

/// [`manifest`], with the `ltl` properties when `ltl`.
pub fn manifest_with(cups: usize, explain: bool, ltl: bool) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen/bdi-check.toml");
    let text = std::fs::read_to_string(root).expect("specs/kitchen/bdi-check.toml");
    let names: Vec<String> = (1..=cups).map(|i| format!("\"cup{i}\"")).collect();
    let away: Vec<String> = (1..=cups)
        .map(|i| format!("cupAt(cup{i}, cupboard)"))
        .collect();
    let mut out = String::new();
    let mut skipping = false;
    let lines: Vec<&str> = text.lines().collect();
    for (k, line) in lines.iter().enumerate() {
        if line.starts_with('[') {
            // A `[[property]]` table with an `ltl` key (its next lines up to the next table).
            let is_ltl = *line == "[[property]]"
                && lines[k + 1..]
                    .iter()
                    .take_while(|l| !l.starts_with('['))
                    .any(|l| l.starts_with("ltl = "));
            skipping = (!explain && line.starts_with("[explanation")) || (!ltl && is_ltl);
        }
        if skipping {
            continue;
        }
        if line.starts_with("cup = [") {
            out.push_str(&format!("cup = [{}]\n", names.join(", ")));
        } else if line.starts_with("reachable = \"robotAt(cupboard)") {
            out.push_str(&format!(
                "reachable = \"robotAt(cupboard) & {}\"\n",
                away.join(" & ")
            ));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out.replace("max_states = 5_000_000", "max_states = 200_000_000")
}

/// A fresh folder named after `bench` with the kitchen's plans and domain and [`manifest`]
/// for `cups` cups.
#[allow(dead_code)] // The spin bench writes its own folder (a seeded bug, the Promela model).
pub fn project(bench: &str, cups: usize, explain: bool) -> PathBuf {
    project_with(bench, cups, explain, false)
}

/// [`project`], with the `ltl` properties when `ltl`.
#[allow(dead_code)] // As `project`.
pub fn project_with(bench: &str, cups: usize, explain: bool, ltl: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "bdi-check-bench-{bench}-{cups}-{explain}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let specs = Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
    for f in ["kitchen.asl", "kitchen.pddl"] {
        std::fs::copy(specs.join(f), dir.join(f)).expect("the kitchen's files");
    }
    std::fs::write(
        dir.join("bdi-check.toml"),
        manifest_with(cups, explain, ltl),
    )
    .expect("writable");
    dir
}

/// `bdi-check verify --format json DIR` with `args` (and `--threads N` when given), by the
/// release binary: its report.
#[allow(dead_code)] // Not every bench reads a report.
pub fn verify_json(dir: &Path, args: &[&str], threads: Option<&str>) -> serde_json::Value {
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_bdi-check"));
    cmd.args(["verify", "--format", "json"]).args(args).arg(dir);
    if let Some(t) = threads {
        cmd.args(["--threads", t]);
    }
    let out = cmd.output().expect("bdi-check runs");
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "{}: verify's JSON: {e}\n{}",
            dir.display(),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}
