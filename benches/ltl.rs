//! The LTL properties' cost beside the agent's search: `cargo bench --bench ltl [-- CUPS...]`.
//!
//! Runs `verify --format json` (the release binary) on `specs/kitchen` with its four `ltl`
//! properties and without its explanation users, at 2 to 4 cups (or the counts given),
//! exact (`--no-symmetry`: the product reads the agent's own graph) and with symmetry (the
//! LTL properties then take an exact search of their own), and prints each phase's states,
//! seconds and states/s: the agent's search, the exact search for the LTL properties, and
//! the product of the graph with the properties' Büchi automata (its states summed over the
//! properties and their instances). `-- --threads N` passes `--threads N` on.

use std::path::Path;

#[path = "common/kitchen.rs"]
mod kitchen;

fn verify(dir: &Path, symmetry: bool, threads: Option<&str>) -> serde_json::Value {
    let args: &[&str] = if symmetry { &[] } else { &["--no-symmetry"] };
    kitchen::verify_json(dir, args, threads)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let threads = args
        .iter()
        .position(|a| a == "--threads")
        .map(|i| args.get(i + 1).expect("--threads N").as_str());
    let mut cups: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if cups.is_empty() {
        cups = vec![2, 3, 4];
    }
    println!(
        "| cups | symmetry | phase | states | seconds | states/s |\n| ---: | --- | --- | ---: | ---: | ---: |"
    );
    for n in cups {
        let dir = kitchen::project_with("ltl", n, false, true);
        for symmetry in [false, true] {
            let v = verify(&dir, symmetry, threads);
            let stats = &v["stats"];
            for p in stats["phases"].as_array().into_iter().flatten() {
                let (Some(states), Some(s)) = (p["states"].as_u64(), p["seconds"].as_f64()) else {
                    continue;
                };
                println!(
                    "| {n} | {symmetry} | {} | {states} | {s:.2} | {:.0} |",
                    p["name"].as_str().unwrap_or("?"),
                    states as f64 / s.max(1e-9)
                );
            }
            println!(
                "| {n} | {symmetry} | whole run ({}) | {} | {:.2} | |",
                v["verdict"].as_str().unwrap_or("?"),
                stats["states"],
                stats["seconds"].as_f64().unwrap_or(f64::NAN)
            );
        }
    }
}
