//! What the CLI test targets share.

use std::process::{Command, Output};

/// Runs the `bdi-check` binary from the crate root, as a user in a checkout would.
pub fn bdi_check(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bdi-check"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("bdi-check runs")
}

/// `bdi-check replay REPORT --finding ID`: its exit code and its standard output.
#[allow(dead_code)] // not every test target replays
pub fn replay_finding(report: &std::path::Path, id: &str) -> (i32, String) {
    let o = bdi_check(&["replay", report.to_str().unwrap(), "--finding", id]);
    (
        o.status.code().expect("replay exits"),
        String::from_utf8_lossy(&o.stdout).into_owned(),
    )
}

/// The names of a JSON report's phases (`stats.phases`), in order.
#[allow(dead_code)] // not every test target reads phases
pub fn phase_names(r: &serde_json::Value) -> Vec<&str> {
    r["stats"]["phases"]
        .as_array()
        .unwrap_or_else(|| panic!("no phases: {r:#}"))
        .iter()
        .map(|p| p["name"].as_str().expect("a phase's name"))
        .collect()
}

/// A fresh, empty directory for one test's files, under `bdi-check-tests/PID` in the
/// system's temporary directory. The test harness has no hook at exit, so the first call of
/// a process removes what test processes no longer running left there.
#[allow(dead_code)] // not every test target writes files
pub fn temp_dir(name: &str) -> std::path::PathBuf {
    static SWEPT: std::sync::Once = std::sync::Once::new();
    let root = std::env::temp_dir().join("bdi-check-tests");
    SWEPT.call_once(|| sweep(&root));
    let d = root.join(std::process::id().to_string()).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Removes the folders of `root` named after a process that has ended (Linux: no
/// `/proc/PID`); elsewhere, none.
#[allow(dead_code)]
fn sweep(root: &std::path::Path) {
    if !std::path::Path::new("/proc/self").exists() {
        return;
    }
    for e in std::fs::read_dir(root).into_iter().flatten().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let ended = name.parse::<u32>().is_ok_and(|pid| {
            pid != std::process::id() && !std::path::Path::new(&format!("/proc/{pid}")).exists()
        });
        if ended {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// Runs `verify --format json` on a project; returns the exit code, the report, and where
/// the report was written (in `temp_dir(tag)`).
#[allow(dead_code)] // not every test target verifies
pub fn verify_json(project: &str, tag: &str) -> (i32, serde_json::Value, std::path::PathBuf) {
    report_json(&["verify", project], tag)
}

/// Runs a command that writes a JSON report (`args`, then `--format json -o FILE`);
/// returns the exit code, the report, and where it was written (in `temp_dir(tag)`).
#[allow(dead_code)] // not every test target writes reports
pub fn report_json(args: &[&str], tag: &str) -> (i32, serde_json::Value, std::path::PathBuf) {
    let file = temp_dir(tag).join("report.json");
    let mut all = args.to_vec();
    all.extend(["--format", "json", "-o", file.to_str().unwrap()]);
    let o = bdi_check(&all);
    let text = std::fs::read_to_string(&file)
        .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    (
        o.status.code().unwrap(),
        serde_json::from_str(&text).unwrap(),
        file,
    )
}

/// A counterexample's steps as `agent kind text` (`?` for a step that names no agent).
#[allow(dead_code)] // not every test target reads runs of several agents
pub fn agent_steps(f: &serde_json::Value) -> Vec<String> {
    f["counterexample"]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            format!(
                "{} {} {}",
                s["agent"].as_str().unwrap_or("?"),
                s["kind"].as_str().unwrap(),
                s["text"].as_str().unwrap()
            )
        })
        .collect()
}

/// A finding's counterexample as `kind text` lines.
#[allow(dead_code)] // not every test target reads counterexamples
pub fn steps(f: &serde_json::Value) -> Vec<String> {
    f["counterexample"]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            format!(
                "{} {}",
                s["kind"].as_str().unwrap(),
                s["text"].as_str().unwrap()
            )
        })
        .collect()
}
