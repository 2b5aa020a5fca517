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

/// A fresh, empty directory for one test's files.
#[allow(dead_code)] // not every test target writes files
pub fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("bdi-check-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
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
