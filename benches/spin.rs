//! A peer benchmark: SPIN and bdi-check on the kitchen, `cargo bench --bench spin`.
//!
//! For 3 to 5 cups (`-- N` stops at N cups; `-- 6` or `--six` adds the 6-cup row, which
//! takes minutes and several GiB), the bench writes the kitchen as a Promela model (the
//! text of `promela` below; `benches/kitchen-3.pml` is its 3-cup instance, for reading),
//! runs Debian's `spin -a`, `gcc` and `./pan` on it in a temporary folder, runs the release
//! binary's `verify --no-symmetry --format json` on `specs/kitchen` with n cups (the
//! explanation users left out, as `benches/scale.rs` does), and prints the states, seconds
//! and peak memory of both side by side. Each tool runs as a child process under
//! `/usr/bin/time`, whose maximum resident set size is its peak memory.
//!
//! The two searches are not of the same transition system: bdi-check explores Jason's
//! reasoning cycle (event queue, intention stack, one cycle per transition), the Promela
//! model only the plans' choices and the actions. Their state counts differ for that reason;
//! the checks are the same (invariants, the `always` property, action and goal failures,
//! stuck states), except the `reachable` property, which SPIN's safety search does not
//! check.
//!
//! `--seeded-bug` runs both on 3 cups with the same bug seeded (`pickUp` keeps
//! `holding(none)`, which breaks the invariant `one_item_in_hand`) and prints what each
//! finds. `--collapse` compiles pan with `-DCOLLAPSE`; `--threads N` runs bdi-check on N
//! threads (pan runs on one, bdi-check by default on every core). `--write-model` rewrites
//! `benches/kitchen-3.pml`; `--model N` prints the model of N cups. Without `spin` on the
//! PATH the bench says so and exits successfully.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

#[path = "common/kitchen.rs"]
mod kitchen;

/// Requests per run: the manifest's `max`, which `benches/scale.rs` keeps for every cup
/// count, so that bdi-check's search is that of its exact rows (`--no-symmetry`).
const MAX_REQUESTS: usize = 2;

/// The compiler flags of pan: an exhaustive safety search (`SAFETY`: no cycle detection,
/// which invariants do not need), without array bound checks (the model's indices are
/// bounded by construction), every state stored whole (exact: no bitstate or hash
/// compaction, whose searches can miss states), and a memory limit above the 6-cup
/// search's need. Of the exact storages this is the fastest here: `--collapse` adds
/// `-DCOLLAPSE`, which needs about 30% less memory and 1.4-2 times the time (4-5 cups).
const PAN_FLAGS: &[&str] = &["-O2", "-DSAFETY", "-DNOBOUNDCHECK", "-DMEMLIM=16384"];

/// The Promela model of the kitchen with `cups` cups and `max` requests per run; with
/// `bug`, `pickUp` forgets to delete `holding(none)`.
fn promela(cups: usize, max: usize, bug: bool) -> String {
    let all =
        |f: &dyn Fn(usize) -> String, sep: &str| (0..cups).map(f).collect::<Vec<_>>().join(sep);
    // unloadDishwasher's next answer: the first cup left, else CUPS.
    let first = (0..cups).rev().fold("CUPS".to_string(), |rest, i| {
        format!("(todo[{i}] -> {i} : {rest})")
    });
    let mut m = String::new();
    let w = &mut m;
    writeln!(
        w,
        r#"/* The kitchen robot of specs/kitchen with {cups} cups, for SPIN (benches/spin.rs writes it;
 * this text is that bench's `promela` function, do not edit it by hand).
 *
 * What is modelled, at the level of actions:
 * - the state: every atom of kitchen.pddl over its objects, one bit each, as bdi-check
 *   has them (robotAt per location, holding per item with holding[0] = holding(none),
 *   cupAt per cup and location, used per cup, dishwasherDoor open/closed, dirty per
 *   location), so that the invariants are the manifest's, counts of atoms included;
 * - the initial states: every assignment of the manifest's `vary` atoms that satisfies its
 *   constraints and invariants (each cup on the table, in the dishwasher or in the
 *   cupboard, used or not but never used in the cupboard; the door open or closed; the
 *   table dirty or not; robotAt(table) and holding(none)), chosen nondeterministically;
 * - the requests: at most MAXREQ per run, each ground goal of [requests] at most once,
 *   arriving only when the robot is idle (arrival = "idle"); the run may stop at any idle
 *   point (the end label);
 * - the plan library kitchen.asl: each goal is an inline whose `if` takes the first
 *   applicable plan in source order (plan_selection = "first"; no applicable plan is a
 *   goal failure, an assertion), each body step in order, the plan's variables C and L
 *   in the locals c and l; `for` snapshots its answers and runs in cup order;
 * - the actions of kitchen.pddl: one d_step each, whose assert is the precondition (an
 *   action attempted when it does not hold is a failure, as bdi-check's action-failure
 *   check) followed by the effects;
 * - the [invariants] and the `always` property: a monitor process's assertions, checked
 *   in every state once the initial state is set up;
 * - stuck states (bdi-check's deadlock check): pan's invalid end states.
 *
 * What is abstracted: Jason's reasoning cycle. bdi-check's states hold the event queue, the
 * intention stack with its frames and the belief base in Jason's order, and one transition
 * is one reasoning cycle (an event selected and a plan adopted, or one body step); here one
 * transition is one Promela statement, mostly an action or a plan's choice, the intention
 * stack is the program counter, and the order of `for`'s answers is the cups' (Jason's is
 * its belief base's). The state counts of the two searches differ for that reason. The
 * `reachable` property is not checked here: pan's safety search finds violations, and a
 * witness is one only as the failure of an assertion that it is unreachable. */

#define CUPS {cups}
#define MAXREQ {max}
#define TABLE 0
#define DISHWASHER 1
#define CUPBOARD 2

bit robotAt[3];
bit holding[CUPS + 1];   /* holding[0]: holding(none); holding[c + 1]: the cup c */
typedef Places {{ bit at[3] }};
Places cupAt[CUPS];
bit used[CUPS];
bit doorOpen;            /* dishwasherDoor(open) */
bit doorClosed;          /* dishwasherDoor(closed) */
bit dirty[3];
bit requested[2 * CUPS + 3];   /* storeCup(c), putAway(c), runDishwasher, unloadDishwasher, wipeTable */
byte nreq;               /* requests made */
bit ready;               /* the initial state is set up */

/* [invariants] and the property no_used_cup_in_cupboard */
#define one_location (robotAt[TABLE] + robotAt[DISHWASHER] + robotAt[CUPBOARD] == 1)
#define one_item_in_hand ({hands} == 1)
#define placed(c) (cupAt[c].at[TABLE] + cupAt[c].at[DISHWASHER] + cupAt[c].at[CUPBOARD])
#define held_or_placed(c) ((holding[c + 1] && placed(c) == 0) || (!holding[c + 1] && placed(c) == 1))
#define cup_held_or_in_one_place ({held})
#define door_open_or_closed (doorOpen + doorClosed == 1)
#define no_used_cup_in_cupboard ({cupboard})
#define INVARIANTS (one_location && one_item_in_hand && cup_held_or_in_one_place && door_open_or_closed && no_used_cup_in_cupboard)

/* The monitor: blocked while the invariants hold, so that it adds no states (its end label
 * makes that a valid end state), and enabled in any stored state where they fail, so that
 * the assertion of the first that fails fails there. Unlike a never claim, it leaves
 * pan's check of invalid end states on: a state where the robot is stuck outside its idle
 * point is an error. */
active proctype monitor() {{
end:
  ready && !INVARIANTS ->
  assert(one_location);
  assert(one_item_in_hand);
  assert(cup_held_or_in_one_place);
  assert(door_open_or_closed);
  assert(no_used_cup_in_cupboard)
}}

/* The actions of kitchen.pddl: the precondition, then the effects. Each call is a d_step
 * of its own: one transition. */

inline navigateTo(to) {{
  assert(robotAt[TABLE] || robotAt[DISHWASHER] || robotAt[CUPBOARD]);
  robotAt[TABLE] = (to == TABLE);
  robotAt[DISHWASHER] = (to == DISHWASHER);
  robotAt[CUPBOARD] = (to == CUPBOARD)
}}

/* Cups in the dishwasher can only be reached through an open door. */
inline pickUp(cup) {{
  assert(holding[0]
         && ((robotAt[TABLE] && cupAt[cup].at[TABLE]) || (robotAt[DISHWASHER] && cupAt[cup].at[DISHWASHER])
             || (robotAt[CUPBOARD] && cupAt[cup].at[CUPBOARD]))
         && (!cupAt[cup].at[DISHWASHER] || doorOpen));
  holding[cup + 1] = 1;
{release}  cupAt[cup].at[TABLE] = 0;
  cupAt[cup].at[DISHWASHER] = 0;
  cupAt[cup].at[CUPBOARD] = 0
}}

/* A cup goes where the robot stands; never a used cup into the cupboard. */
inline putDown(cup) {{
  assert(holding[cup + 1] && (!robotAt[DISHWASHER] || doorOpen) && (!robotAt[CUPBOARD] || !used[cup]));
  holding[cup + 1] = 0;
  holding[0] = 1;
  cupAt[cup].at[TABLE] = cupAt[cup].at[TABLE] || robotAt[TABLE];
  cupAt[cup].at[DISHWASHER] = cupAt[cup].at[DISHWASHER] || robotAt[DISHWASHER];
  cupAt[cup].at[CUPBOARD] = cupAt[cup].at[CUPBOARD] || robotAt[CUPBOARD]
}}

inline openDoor(a) {{
  assert(a == DISHWASHER && robotAt[DISHWASHER] && holding[0] && doorClosed);
  doorOpen = 1;
  doorClosed = 0
}}

inline closeDoor(a) {{
  assert(a == DISHWASHER && robotAt[DISHWASHER] && holding[0] && doorOpen);
  doorClosed = 1;
  doorOpen = 0
}}

/* A wash cycle cleans every cup inside. */
inline startDishwasher(a) {{
  assert(a == DISHWASHER && robotAt[DISHWASHER] && doorClosed);
{wash}
}}

inline wipe(loc) {{
  assert(robotAt[loc] && holding[0]);
  dirty[loc] = 0
}}

/* The plans of kitchen.asl, one inline per goal: the first applicable plan in source
 * order, else the goal fails. */

inline openDishwasherIfNeed() {{
  if
  :: !doorOpen && holding[0] ->            /* @openDishwasherIfNeed */
     d_step {{ navigateTo(DISHWASHER) }};
     d_step {{ openDoor(DISHWASHER) }}
  :: else ->
     if
     :: doorOpen                            /* @dishwasherAlreadyOpen */
     :: else -> assert(false)               /* no applicable plan */
     fi
  fi
}}

/* @fetch: cupAt(C, L), the first answer (the invariants leave one). */
inline fetch() {{
  d_step {{
    assert(placed(c) > 0);                  /* no applicable plan otherwise */
    l = (cupAt[c].at[TABLE] -> TABLE : (cupAt[c].at[DISHWASHER] -> DISHWASHER : CUPBOARD))
  }};
  d_step {{ navigateTo(l) }};
  d_step {{ pickUp(c); l = 0 }}   /* @fetch ends with its last step, as in Jason: L goes */
}}

inline deliver(dest) {{
  if
  :: holding[c + 1] ->                      /* @deliver */
     d_step {{ navigateTo(dest) }};
     d_step {{ putDown(c) }}
  :: else -> assert(false)
  fi
}}

inline storeCup() {{
  if
  :: used[c] && !cupAt[c].at[DISHWASHER] -> /* @storeUsedCup */
     openDishwasherIfNeed();
     fetch();
     deliver(DISHWASHER)
  :: else                                   /* @storeNothing */
  fi
}}

inline putAway() {{
  if
  :: !used[c] && !cupAt[c].at[CUPBOARD] ->  /* @putAwayCup */
     if                                     /* !reach(C) */
     :: cupAt[c].at[DISHWASHER] ->          /* @reachIntoDishwasher */
        openDishwasherIfNeed()
     :: else                                /* @reachDirectly */
     fi;
     fetch();
     deliver(CUPBOARD)
  :: else                                   /* @putAwayNothing */
  fi
}}

inline runDishwasher() {{
  if
  :: {any_in_dishwasher} ->   /* @runDishwasher */
     if                                     /* !closeDishwasherIfNeed */
     :: doorOpen ->                         /* @closeOpenDishwasher */
        d_step {{ navigateTo(DISHWASHER) }};
        d_step {{ closeDoor(DISHWASHER) }}
     :: else                                /* @dishwasherAlreadyClosed */
     fi;
     if                                     /* !startWash */
     :: doorClosed ->                       /* @startWash */
        d_step {{ navigateTo(DISHWASHER) }};
        d_step {{ startDishwasher(DISHWASHER) }}
     :: else -> assert(false)
     fi
  :: else                                   /* @runEmptyDishwasher */
  fi
}}

/* @unloadDishwasher: for (cupAt(C, dishwasher) & not used(C)) {{ !putAway(C) }} */
inline unloadDishwasher() {{
  d_step {{
{snapshot}
  }};
  do
  :: d_step {{                               /* the next answer, or CUPS when none is left */
{next}
     }};
     if
     :: c == CUPS -> break
     :: else -> putAway()
     fi
  od
}}

inline wipeTable() {{
  if
  :: dirty[TABLE] ->                        /* @wipeDirtyTable */
     d_step {{ navigateTo(TABLE) }};
     d_step {{ wipe(TABLE) }}
  :: else                                   /* @tableAlreadyClean */
  fi
}}

active proctype robot() {{
  byte c;          /* the running plans' variable C */
  byte l;          /* @fetch's variable L */
  bit todo[CUPS];  /* the answers @unloadDishwasher's for has left */

  /* [initial]: robotAt(table), holding(none), and every assignment of the vary atoms
   * that satisfies the constraints and the invariants. */
  atomic {{
    robotAt[TABLE] = 1;
    holding[0] = 1;"#,
        hands = (0..=cups)
            .map(|i| format!("holding[{i}]"))
            .collect::<Vec<_>>()
            .join(" + "),
        held = all(&|c| format!("held_or_placed({c})"), " && "),
        cupboard = all(&|c| format!("!(used[{c}] && cupAt[{c}].at[CUPBOARD])"), " && "),
        release = if bug {
            "  /* seeded bug: holding(none) is not deleted */\n"
        } else {
            "  holding[0] = 0;\n"
        },
        wash = all(
            &|c| format!("  used[{c}] = used[{c}] && !cupAt[{c}].at[DISHWASHER]"),
            ";\n"
        ),
        any_in_dishwasher = all(&|c| format!("cupAt[{c}].at[DISHWASHER]"), " || "),
        snapshot = all(
            &|c| format!("    todo[{c}] = cupAt[{c}].at[DISHWASHER] && !used[{c}]"),
            ";\n"
        ),
        next = format_args!(
            "       c = {first};\n       if\n       :: c < CUPS -> todo[c] = 0\n       :: else\n       fi"
        ),
    )
    .unwrap();
    for c in 0..cups {
        writeln!(
            w,
            "    if\n    :: cupAt[{c}].at[TABLE] = 1\n    :: cupAt[{c}].at[TABLE] = 1; used[{c}] = 1\n    :: cupAt[{c}].at[DISHWASHER] = 1\n    :: cupAt[{c}].at[DISHWASHER] = 1; used[{c}] = 1\n    :: cupAt[{c}].at[CUPBOARD] = 1\n    fi;"
        )
        .unwrap();
    }
    writeln!(
        w,
        "    if\n    :: doorOpen = 1\n    :: doorClosed = 1\n    fi;\n    if\n    :: dirty[TABLE] = 1\n    :: skip\n    fi;\n    ready = 1\n  }};\n\n  /* Idle: the next request, or none (the run stops here). */\nend_idle:\n  if"
    )
    .unwrap();
    let mut requests: Vec<(String, String, &str)> = Vec::new();
    for c in 0..cups {
        requests.push((
            format!("storeCup(cup{})", c + 1),
            format!("{c}"),
            "storeCup()",
        ));
    }
    for c in 0..cups {
        requests.push((
            format!("putAway(cup{})", c + 1),
            format!("{c}"),
            "putAway()",
        ));
    }
    requests.push(("runDishwasher".into(), "0".into(), "runDishwasher()"));
    requests.push(("unloadDishwasher".into(), "0".into(), "unloadDishwasher()"));
    requests.push(("wipeTable".into(), "0".into(), "wipeTable()"));
    for (i, (goal, c, body)) in requests.iter().enumerate() {
        writeln!(
            w,
            "  :: d_step {{ nreq < MAXREQ && !requested[{i}] -> requested[{i}] = 1; nreq++; c = {c} }};   /* !{goal} */\n     {body}"
        )
        .unwrap();
    }
    writeln!(
        w,
        "  fi;\n  atomic {{ c = 0; l = 0 }};   /* the intention is done: its variables go */\n  goto end_idle\n}}"
    )
    .unwrap();
    m
}

/// The kitchen manifest with `cups` cups, without the explanation users (as scale.rs).
fn manifest(cups: usize) -> String {
    let out = kitchen::manifest(cups, false);
    assert!(out.contains(&format!("max = {MAX_REQUESTS}\n")));
    out
}

/// A temporary folder for one row: the kitchen project with `cups` cups (with the seeded
/// bug in `pickUp` when `bug`), and the Promela model of the same.
fn project(cups: usize, bug: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "bdi-check-bench-spin-{cups}-{bug}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let specs = Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
    std::fs::copy(specs.join("kitchen.asl"), dir.join("kitchen.asl")).expect("kitchen.asl");
    let mut pddl = std::fs::read_to_string(specs.join("kitchen.pddl")).expect("kitchen.pddl");
    if bug {
        let keep = "(holding ?c)\n                 (not (holding none))";
        assert!(pddl.contains(keep), "pickUp's effect as expected");
        pddl = pddl.replace(keep, "(holding ?c)");
    }
    std::fs::write(dir.join("kitchen.pddl"), pddl).expect("writable");
    std::fs::write(dir.join("bdi-check.toml"), manifest(cups)).expect("writable");
    std::fs::write(dir.join("kitchen.pml"), promela(cups, MAX_REQUESTS, bug)).expect("writable");
    dir
}

/// What one child process did: its output, wall seconds and peak resident memory in MiB
/// (from `/usr/bin/time`, when there is one).
struct Run {
    out: Output,
    seconds: f64,
    peak_mib: Option<f64>,
}

/// Runs `program` with `args` in `dir`, timed, under `/usr/bin/time` for its peak memory.
fn run(dir: &Path, program: &str, args: &[&str]) -> Run {
    let time = Path::new("/usr/bin/time");
    let peak = dir.join("peak");
    let _ = std::fs::remove_file(&peak);
    let mut cmd = if time.exists() {
        let mut c = Command::new(time);
        c.arg("-f").arg("%M").arg("-o").arg(&peak).arg(program);
        c
    } else {
        Command::new(program)
    };
    cmd.args(args).current_dir(dir);
    let start = Instant::now();
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{program} runs: {e}"));
    let seconds = start.elapsed().as_secs_f64();
    let peak_mib = std::fs::read_to_string(&peak)
        .ok()
        .and_then(|t| t.lines().last()?.trim().parse::<f64>().ok())
        .map(|kib| kib / 1024.0);
    Run {
        out,
        seconds,
        peak_mib,
    }
}

/// The number before `label` on a line of pan's report, e.g. `  116886 states, stored`.
fn pan_number(report: &str, label: &str) -> Option<f64> {
    report
        .lines()
        .find(|l| l.contains(label))?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// SPIN's side of a row.
struct Spin {
    states: u64,
    transitions: u64,
    errors: u64,
    /// pan's first error line, e.g. `pan:1: assertion violated ...`.
    error: Option<String>,
    pan_seconds: f64,
    total_seconds: f64,
    peak_mib: Option<f64>,
}

/// pan's hash table size (`-w`, bits) for `cups` cups: its default, 24, up to 5 cups (7.4 M
/// states), and above that the power of two next above the states, as SPIN's manual
/// advises (6 cups: 49 M states, 58 s with `-w26` against 75 s with `-w24`).
fn hash_bits(cups: usize) -> u32 {
    match cups {
        ..=5 => 24,
        6 => 26,
        _ => 28,
    }
}

/// `spin -a`, `gcc` and `./pan` on `dir/kitchen.pml` (pan with `-DCOLLAPSE` if `collapse`).
fn spin(dir: &Path, cups: usize, collapse: bool) -> Spin {
    let generate = run(dir, "spin", &["-a", "kitchen.pml"]);
    assert!(
        generate.out.status.success(),
        "spin -a fails:\n{}",
        String::from_utf8_lossy(&generate.out.stdout)
    );
    let mut gcc = PAN_FLAGS.to_vec();
    if collapse {
        gcc.push("-DCOLLAPSE");
    }
    gcc.extend(["-o", "pan", "pan.c"]);
    let compile = run(dir, "gcc", &gcc);
    assert!(
        compile.out.status.success(),
        "gcc fails:\n{}",
        String::from_utf8_lossy(&compile.out.stderr)
    );
    // The depth bound is far above the longest run (two tasks of a few dozen steps):
    // pan says so when it cuts a run.
    let w = format!("-w{}", hash_bits(cups));
    let pan = run(dir, "./pan", &["-m100000", &w]);
    let report = String::from_utf8_lossy(&pan.out.stdout).to_string();
    assert!(
        !report.contains("max search depth too small"),
        "pan's depth bound is reached:\n{report}"
    );
    let errors = report
        .lines()
        .find_map(|l| l.split("errors: ").nth(1))
        .and_then(|e| e.trim().parse().ok())
        .unwrap_or_else(|| panic!("pan's report names its errors:\n{report}"));
    Spin {
        states: pan_number(&report, "states, stored").unwrap_or(0.0) as u64,
        transitions: pan_number(&report, "transitions (= stored+matched)").unwrap_or(0.0) as u64,
        errors,
        error: report
            .lines()
            .find(|l| l.starts_with("pan:1:"))
            .map(str::to_string),
        pan_seconds: report
            .lines()
            .find_map(|l| l.strip_prefix("pan: elapsed time "))
            .and_then(|t| t.split_whitespace().next()?.parse().ok())
            .unwrap_or(pan.seconds),
        total_seconds: generate.seconds + compile.seconds + pan.seconds,
        peak_mib: pan.peak_mib,
    }
}

/// bdi-check's side of a row.
struct Bdi {
    states: u64,
    transitions: u64,
    verdict: String,
    /// The failed findings: `check: message`.
    failed: Vec<String>,
    search_seconds: f64,
    seconds: f64,
    wall_seconds: f64,
    peak_mib: Option<f64>,
}

/// The release binary's exact `verify` of `dir`, on `threads` threads (every core if
/// none).
fn bdi_check(dir: &Path, threads: Option<&str>) -> Bdi {
    let exe = env!("CARGO_BIN_EXE_bdi-check");
    let mut args = vec!["verify", "--no-symmetry", "--format", "json", "."];
    if let Some(t) = threads {
        args.extend(["--threads", t]);
    }
    let r = run(dir, exe, &args);
    let v: serde_json::Value = serde_json::from_slice(&r.out.stdout).unwrap_or_else(|e| {
        panic!(
            "verify's JSON: {e}\n{}",
            String::from_utf8_lossy(&r.out.stderr)
        )
    });
    let stats = &v["stats"];
    let search = stats["phases"]
        .as_array()
        .and_then(|p| p.iter().find(|p| p["name"] == "search"))
        .and_then(|p| p["seconds"].as_f64())
        .unwrap_or(f64::NAN);
    Bdi {
        states: stats["states"].as_u64().unwrap_or(0),
        transitions: stats["transitions"].as_u64().unwrap_or(0),
        verdict: v["verdict"].as_str().unwrap_or("?").to_string(),
        failed: v["findings"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|f| f["status"] == "fail" && f["severity"] != "note")
            .map(|f| {
                format!(
                    "{}: {}",
                    f["check"].as_str().unwrap_or("?"),
                    f["message"].as_str().unwrap_or("?")
                )
            })
            .collect(),
        search_seconds: search,
        seconds: stats["seconds"].as_f64().unwrap_or(f64::NAN),
        wall_seconds: r.seconds,
        peak_mib: r.peak_mib,
    }
}

fn mib(m: Option<f64>) -> String {
    m.map_or("-".into(), |m| format!("{m:.0}"))
}

/// The 3-cup model as committed, for people to read.
fn committed_model() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/kitchen-3.pml")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = args.iter().position(|a| a == "--model") {
        let cups = args
            .get(i + 1)
            .and_then(|n| n.parse().ok())
            .expect("--model N");
        print!("{}", promela(cups, MAX_REQUESTS, false));
        return;
    }
    if args.iter().any(|a| a == "--write-model") {
        std::fs::write(committed_model(), promela(3, MAX_REQUESTS, false)).expect("writable");
        return;
    }
    if std::fs::read_to_string(committed_model()).ok() != Some(promela(3, MAX_REQUESTS, false)) {
        eprintln!("warning: benches/kitchen-3.pml is not the model this bench runs (`cargo bench --bench spin -- --write-model` rewrites it)");
    }
    if Command::new("spin").arg("-V").output().is_err() {
        println!("spin is not installed (Debian: apt-get install spin): nothing to compare");
        return;
    }
    let version = Command::new("spin").arg("-V").output().expect("spin -V");
    println!("{}", String::from_utf8_lossy(&version.stdout).trim());
    let collapse = args.iter().any(|a| a == "--collapse");
    let threads = args
        .iter()
        .position(|a| a == "--threads")
        .map(|i| args.get(i + 1).expect("--threads N").as_str());
    println!(
        "pan compiled with gcc {}{}, run with -m100000 and -w24 (-w26 at 6 cups)",
        PAN_FLAGS.join(" "),
        if collapse { " -DCOLLAPSE" } else { "" }
    );

    if args.iter().any(|a| a == "--seeded-bug") {
        let dir = project(3, true);
        let s = spin(&dir, 3, collapse);
        let b = bdi_check(&dir, threads);
        println!(
            "seeded bug (pickUp keeps holding(none)), 3 cups:\nSPIN: {} error(s) after {} states: {}\nbdi-check: verdict {} after {} states",
            s.errors,
            s.states,
            s.error.as_deref().unwrap_or("-"),
            b.verdict,
            b.states
        );
        for f in &b.failed {
            println!("  {f}");
        }
        let _ = std::fs::remove_dir_all(dir);
        return;
    }

    let six = args.iter().any(|a| a == "--six");
    let last: usize = args
        .iter()
        .enumerate()
        .filter(|(i, _)| *i == 0 || args[i - 1] != "--threads")
        .find_map(|(_, a)| a.parse().ok())
        .unwrap_or(if six { 6 } else { 5 });
    println!(
        "cups\tSPIN states\tSPIN transitions\tSPIN errors\tpan s\tspin+gcc+pan s\tSPIN peak MiB\tbdi-check states\tbdi-check transitions\tverdict\tsearch s\tverify s\twall s\tbdi-check peak MiB"
    );
    for cups in 3..=last {
        let dir = project(cups, false);
        let s = spin(&dir, cups, collapse);
        let b = bdi_check(&dir, threads);
        println!(
            "{cups}\t{}\t{}\t{}\t{:.2}\t{:.2}\t{}\t{}\t{}\t{}\t{:.2}\t{:.2}\t{:.2}\t{}",
            s.states,
            s.transitions,
            s.errors,
            s.pan_seconds,
            s.total_seconds,
            mib(s.peak_mib),
            b.states,
            b.transitions,
            b.verdict,
            b.search_seconds,
            b.seconds,
            b.wall_seconds,
            mib(b.peak_mib),
        );
        let _ = std::fs::remove_dir_all(dir);
    }
}
