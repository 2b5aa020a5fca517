//! Scale on the kitchen as the number of cups grows: `cargo bench --bench scale`.
//!
//! Four parts: successor generation (states expanded per second, one thread, with the
//! reference and the compiled reasoning cycle), the visited-state store (inserts per
//! second and bytes per state), the bare search on 1 and 2 threads, and the table of
//! `docs/benchmarks.md`: for 1 to 6 cups, `verify` of the kitchen (`specs/kitchen` with n
//! cups; the reachable property names every cup) with symmetry reduction and on every core,
//! and without symmetry where that finishes in reasonable time. Each row runs in a child
//! process so that its peak memory (`VmHWM`) is its own.
//!
//! `cargo bench --bench scale -- N` runs the rows up to N cups only; `--explain` keeps the
//! manifest's `[explanation]` users, so that the explanation properties are checked too
//! (one more search per user, reduced by the same symmetry when it is on).

use bdi_check::check::explore::{explore_with, peak_memory, Limits, Options};
use bdi_check::check::model::{CompiledAgent, Model};
use bdi_check::check::store::Store;
use bdi_check::check::{verify_with, VerifyOptions};
use bdi_check::model::project::load_project;
use bdi_check::semantics::{Compiled, Semantics};
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

#[path = "common/kitchen.rs"]
mod kitchen;

// The same allocator as the `bdi-check` binary, so that the numbers are the binary's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A temporary project folder with the kitchen's plans and domain and `cups` cups.
fn project(cups: usize, explain: bool) -> PathBuf {
    kitchen::project("scale", cups, explain)
}

/// Successor generation: the first `n` states of the 3-cup kitchen, breadth first, each
/// expanded once more and timed.
fn successors() {
    let dir = project(3, false);
    let p = load_project(&dir).expect("the project loads");
    let sem = Semantics::new(&p).expect("the semantics");
    let mut frontier: Vec<_> = sem.init_states().collect();
    let mut states = Vec::new();
    while states.len() < 20_000 && !frontier.is_empty() {
        let mut next = Vec::new();
        for s in frontier {
            next.extend(sem.next_states(&s).into_iter().map(|(_, t)| t));
            states.push(s);
        }
        frontier = next;
    }
    let start = Instant::now();
    let mut succ = 0usize;
    for s in &states {
        succ += sem.next_states(s).len();
    }
    let t = start.elapsed().as_secs_f64();
    println!(
        "successors, reference cycle: {} states expanded in {t:.3}s: {:.0} states/s, {:.0} successors/s (one thread, 3 cups)",
        states.len(),
        states.len() as f64 / t,
        succ as f64 / t
    );
    // The compiled cycle, from empty tables: what a search pays, misses included.
    let compiled = Compiled::new(&sem).expect("the kitchen's library is local");
    let packed: Vec<_> = states.iter().map(|s| compiled.pack(s)).collect();
    let start = Instant::now();
    let mut succ = 0usize;
    for s in &packed {
        succ += compiled.successors(s).len();
    }
    let t = start.elapsed().as_secs_f64();
    println!(
        "successors, compiled cycle: {} states expanded in {t:.3}s: {:.0} states/s, {:.0} successors/s (one thread, 3 cups)",
        states.len(),
        states.len() as f64 / t,
        succ as f64 / t
    );
    let start = Instant::now();
    let mut x = 0u64;
    for s in &states {
        x ^= sem.fingerprint(s);
    }
    let t = start.elapsed().as_secs_f64();
    println!(
        "fingerprints: {:.0} states/s (checksum {x:x})",
        states.len() as f64 / t
    );
}

/// The store: ten million distinct fingerprints.
fn store() {
    let mut s = Store::new();
    let n = 10_000_000u64;
    let start = Instant::now();
    for k in 0..n {
        let fp = k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (k >> 7);
        s.insert(fp, Some(k.saturating_sub(1) as u32))
            .expect("memory");
    }
    let t = start.elapsed().as_secs_f64();
    println!(
        "store: {n} inserts in {t:.2}s ({:.0}/s), {:.1} bytes per state",
        n as f64 / t,
        s.bytes() as f64 / n as f64
    );
}

/// One table row, in this process: prints a tab-separated line.
fn row(cups: usize, symmetry: bool, explain: bool) {
    let dir = project(cups, explain);
    let p = load_project(&dir).expect("the project loads");
    let limits = Limits {
        max_states: 200_000_000,
        max_depth: 2_000,
        timeout: Some(600.0),
    };
    let opts = VerifyOptions {
        symmetry,
        ..VerifyOptions::default()
    };
    let start = Instant::now();
    let v = verify_with(&p, limits, &opts, |_, _, _, _| {}, &[]).expect("the kitchen verifies");
    let total = start.elapsed().as_secs_f64();
    let failed = v
        .findings
        .iter()
        .filter(|f| f.status == bdi_check::findings::Status::Fail)
        .count();
    let s = &v.stats;
    println!(
        "{cups}\t{}\t{}\t{}\t{:.2}\t{total:.2}\t{:.0}\t{}\t{:.1}\t{:.1}\t{}\t{failed}",
        if symmetry { "on" } else { "off" },
        s.states,
        s.transitions,
        s.seconds,
        s.states_per_second,
        peak_memory().unwrap_or(0) / (1 << 20),
        v.memory.0 as f64 / s.states.max(1) as f64,
        v.memory.1 as f64 / s.transitions.max(1) as f64,
        if s.complete { "yes" } else { "no" },
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A bare search (no checks, no edges, no symmetry) of the 4-cup kitchen with the compiled
/// reasoning cycle, per thread count: the raw speed of the explorer.
fn threads() {
    let dir = project(4, false);
    let p = load_project(&dir).expect("the project loads");
    let sem = Semantics::new(&p).expect("the semantics");
    for threads in [1, 2] {
        // A fresh one per run: its memo tables fill as the search goes.
        let compiled = Compiled::new(&sem).expect("the kitchen's library is local");
        let opts = Options {
            threads,
            keep_edges: false,
            max_memory: None,
            shard: None,
            sample: None,
            room_for: 0,
            numbered: true,
            places: 0,
        };
        let limits = Limits {
            max_states: u64::MAX,
            max_depth: u64::MAX,
            timeout: None,
        };
        let model = CompiledAgent {
            compiled: &compiled,
            symmetry: None,
        };
        let g = explore_with(
            &model,
            limits,
            &opts,
            |_, _| (),
            |_, _, ()| {},
            |_, _, _, _| {},
            |_, _, _| {},
        );
        println!(
            "bare search, 4 cups, no symmetry, {threads} thread(s): {} states in {:.2}s, {:.0} states/s",
            g.len(),
            g.seconds,
            g.len() as f64 / g.seconds
        );
        println!("  compiled tables: {:?}", compiled.sizes());
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let explain = args.iter().any(|a| a == "--explain");
    if let Some(i) = args.iter().position(|a| a == "--row") {
        let cups = args[i + 1].parse().expect("cups");
        row(cups, args[i + 2] == "on", explain);
        return;
    }
    let max: usize = args
        .iter()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(6);
    if args.iter().any(|a| a == "--threads-only") {
        threads();
        return;
    }
    successors();
    store();
    threads();
    println!(
        "cups\tsymmetry\tstates\ttransitions\tsearch s\ttotal s\tstates/s\tpeak MiB\tstore B/state\tedge B/transition\tcomplete\tfailed"
    );
    let exe = std::env::current_exe().expect("the bench binary");
    for cups in 1..=max {
        // Without symmetry, 6 cups (about a minute, 2 GiB), and 5 cups with the users'
        // searches, take too long to be worth a bench run.
        let exact = if explain { 4 } else { 5 };
        let modes: &[&str] = if cups <= exact {
            &["on", "off"]
        } else {
            &["on"]
        };
        for mode in modes {
            let mut cmd = Command::new(&exe);
            cmd.args(["--row", &cups.to_string(), mode]);
            if explain {
                cmd.arg("--explain");
            }
            let out = cmd.output().expect("the row runs");
            print!("{}", String::from_utf8_lossy(&out.stdout));
            if !out.status.success() {
                eprint!("{}", String::from_utf8_lossy(&out.stderr));
            }
        }
    }
}
