//! Issue 16's whole-run targets on the kitchen, exact: `cargo bench --bench targets`.
//!
//! For each number of cups (4 unless given: `cargo bench --bench targets -- 4 6`), the
//! agent's run alone (`verify --no-symmetry` of the kitchen without its `ltl` properties and
//! explanation users) and the run with every property (both users and the `ltl`
//! properties), one after the other, `--runs N` times (5 unless given): the wall time of
//! each `verify` process, their ratio, and the median ratio. The target is a ratio within
//! 3 at 4 cups and every property under 60 s at 6 cups. Runs alternate so that both meet
//! the same spells of a noisy machine; each row is one pair.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

#[path = "common/kitchen.rs"]
mod kitchen;

/// The wall time of `bdi-check verify --no-symmetry DIR`, and its verdict line.
fn timed(dir: &Path) -> (f64, String) {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_bdi-check"))
        .args(["verify", "--no-symmetry", "--color", "never"])
        .arg(dir)
        .output()
        .expect("bdi-check runs");
    let seconds = start.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let verdict = (stdout.lines())
        .find(|l| l.starts_with("verdict:"))
        .unwrap_or("no verdict")
        .to_string();
    (seconds, verdict)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs = match args.iter().position(|a| a == "--runs") {
        Some(i) => (args.get(i + 1))
            .and_then(|n| n.parse().ok())
            .expect("--runs N"),
        None => 5,
    };
    let mut cups: Vec<usize> = (args.iter().enumerate())
        .filter(|(i, _)| *i == 0 || args[i - 1] != "--runs")
        .filter_map(|(_, a)| a.parse().ok())
        .collect();
    if cups.is_empty() {
        cups = vec![4];
    }
    println!("| cups | run | agent alone s | every property s | ratio |");
    println!("| ---: | ---: | ---: | ---: | ---: |");
    for n in cups {
        let alone = kitchen::project_with("targets-alone", n, false, false);
        let every = kitchen::project_with("targets-every", n, true, true);
        let mut ratios = Vec::new();
        for run in 1..=runs {
            let (a, verdict_a) = timed(&alone);
            let (e, verdict_e) = timed(&every);
            for v in [&verdict_a, &verdict_e] {
                assert!(v.starts_with("verdict: pass"), "{n} cups: {v}");
            }
            ratios.push(e / a);
            println!("| {n} | {run} | {a:.2} | {e:.2} | {:.2} |", e / a);
        }
        ratios.sort_by(f64::total_cmp);
        println!(
            "| {n} | median of {runs} | | | {:.2} |",
            ratios[ratios.len() / 2]
        );
        for dir in [alone, every] {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
}
