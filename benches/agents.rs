//! Several agents: `cargo bench --bench agents` prints, for `specs/two-robots`, for a
//! generated ping-pong of one ponger and N pinger instances and for a collector told by N
//! workers that each take four cycles of their own first (N = 1 to 4, or up to the first
//! argument; ping-pong 5 takes about two minutes without symmetry), the states and
//! transitions of the search with symmetry over instances and partial-order reduction
//! (`sym+por`), with symmetry alone (`sym`), with partial-order reduction alone (`por`)
//! and over every interleaving (`full`), the states of the search of every interleaving
//! that the checks of runs going on for ever need when the first was reduced (`liveness`),
//! the time of the whole `verify` (loading, lint and both searches included) and the
//! states per second of both searches.

use std::path::{Path, PathBuf};
use std::time::Instant;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A ping-pong project of `n` pingers in a fresh folder.
fn ping_pong(n: usize) -> PathBuf {
    let dir = std::env::temp_dir()
        .join("bdi-check-bench")
        .join(format!("ping-pong-{n}"));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    // Jason names one instance after its agent, several `pinger1` ... `pingerN`.
    let names: Vec<String> = if n == 1 {
        vec!["pinger".into()]
    } else {
        (1..=n).map(|i| format!("pinger{i}")).collect()
    };
    let pingers: Vec<String> = names.iter().map(|p| format!("\"{p}\"")).collect();
    let all: Vec<String> = names.iter().map(|p| format!("ponged({p})")).collect();
    let files = [
        (
            "bdi-check.toml",
            format!(
                "[[agent]]\nname = \"ponger\"\nplans = \"ponger.asl\"\nactions = \"ping.pddl\"\n\n[[agent]]\nname = \"pinger\"\nplans = \"pinger.asl\"\ninstances = {n}\n\n[objects]\nagent = [\"ponger\", {}]\n\n[invariants]\nno_pong_for_the_ponger = \"not ponged(ponger)\"\n\n[[property]]\nname = \"all_answered\"\nreachable = \"{}\"\n\n[bounds]\nmax_states = 50_000_000\n",
                pingers.join(", "),
                all.join(" & ")
            ),
        ),
        (
            "ping.pddl",
            "(define (domain ping)\n  (:requirements :strips :typing)\n  (:types agent)\n  (:predicates (ponged ?a - agent))\n  (:action pong :parameters (?a - agent)\n    :precondition (not (ponged ?a)) :effect (ponged ?a)))\n".into(),
        ),
        ("ponger.asl", "+!ping[source(A)] <- pong(A).\n".into()),
        ("pinger.asl", "!start.\n+!start <- .send(ponger, achieve, ping).\n".into()),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("a project file");
    }
    dir
}

/// A collector told `done` by `n` workers, each of which first takes four cycles of its
/// own (adopting its plan, three mental notes): the case partial-order reduction is for.
fn workers(n: usize) -> PathBuf {
    let dir = std::env::temp_dir()
        .join("bdi-check-bench")
        .join(format!("workers-{n}"));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let files = [
        (
            "bdi-check.toml",
            format!("[[agent]]\nname = \"collector\"\nplans = \"collector.asl\"\nactions = \"d.pddl\"\n\n[[agent]]\nname = \"worker\"\nplans = \"worker.asl\"\ninstances = {n}\n\n[bounds]\nmax_states = 50_000_000\n"),
        ),
        (
            "d.pddl",
            "(define (domain d) (:requirements :strips) (:predicates (p)) (:action a :parameters () :precondition () :effect (p)))\n".into(),
        ),
        (
            "worker.asl",
            "!work.\n+!work <- +step1; +step2; +step3; .send(collector, tell, done).\n".into(),
        ),
        ("collector.asl", "+done[source(A)] <- .print(A).\n".into()),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("a project file");
    }
    dir
}

fn row(name: &str, dir: &Path) {
    for (symmetry, partial_order) in [(true, true), (true, false), (false, true), (false, false)] {
        one(name, dir, symmetry, partial_order);
    }
}

fn one(name: &str, dir: &Path, symmetry: bool, partial_order: bool) {
    let mode = match (symmetry, partial_order) {
        (true, true) => "sym+por",
        (true, false) => "sym",
        (false, true) => "por",
        (false, false) => "full",
    };
    let name = format!("{name} {mode}");
    let started = Instant::now();
    let bounds = bdi_check::commands::verify::Bounds::default();
    let run = bdi_check::commands::verify::run(
        dir,
        &bounds,
        &bdi_check::check::VerifyOptions {
            threads: 1,
            symmetry,
            partial_order,
            ..Default::default()
        },
        |_, _, _, _| {},
    );
    let seconds = started.elapsed().as_secs_f64();
    let Some(stats) = run.report.stats.as_ref() else {
        println!("{name:<22} not verified: {:?}", run.report.verdict);
        return;
    };
    // The search of every interleaving the checks of runs that go on for ever need when
    // the first was reduced.
    let again = stats
        .liveness_states
        .map_or_else(|| "-".to_string(), |n| n.to_string());
    println!(
        "{name:<22} {:>10} {:>12} {:>10} {:>8.2} {:>12.0}   {:?}",
        stats.states,
        stats.transitions,
        again,
        seconds,
        (stats.states + stats.liveness_states.unwrap_or(0)) as f64 / seconds,
        run.report.verdict
    );
}

fn main() {
    let most: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(4);
    println!(
        "{:<22} {:>10} {:>12} {:>10} {:>8} {:>12}   verdict",
        "project", "states", "transitions", "liveness", "seconds", "states/s"
    );
    row(
        "two-robots",
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/two-robots"),
    );
    for n in 1..=most {
        row(&format!("ping-pong {n}"), &ping_pong(n));
    }
    for n in 1..=most + 1 {
        row(&format!("workers {n}"), &workers(n));
    }
}
