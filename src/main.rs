//! The `bdi-check` command line: argument parsing and dispatch, nothing else.

use bdi_check::commands;
use bdi_check::report::{verify::Detail, CiFormat, Format};
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

// Exploration allocates and frees small states at a high rate on every thread (see
// Cargo.toml).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Turns transparent huge pages off for this process, except where the search asks for
/// them (the stores' hash tables: `check::store`), unless `MIMALLOC_ALLOW_THP` says
/// otherwise. mimalloc asks for huge pages on its arenas (`madvise(MADV_HUGEPAGE)`), and the
/// kernel then clears 2 MiB at the first touch of each and, with Debian's `defrag =
/// madvise`, compacts memory to find them: for the small objects a search makes all along
/// that cost more than it saved (5-cup kitchen, 2026-12-04: 4.8-5.0 s instead of 4.0 s;
/// on 2026-12-05 the two were within this machine's noise). A table of a gigabyte read at
/// random is another matter: with 4 KiB pages nearly every lookup missed the TLB, and the
/// 6-cup kitchen's users' searches took 36-37 s each instead of 42 s. Linux 6.18's
/// `PR_THP_DISABLE_EXCEPT_ADVISED` keeps the tables' advice; an older kernel refuses the
/// flag, and the process then goes without huge pages at all. Telling mimalloc not to
/// advise its arenas (`mi_option_allow_thp`) covers the arenas it makes from here on; the
/// one it made before `main` is advised back (`MADV_NOHUGEPAGE`).
fn no_transparent_huge_pages() {
    #[cfg(target_os = "linux")]
    if std::env::var_os("MIMALLOC_ALLOW_THP").is_none() {
        // SAFETY: PR_SET_THP_DISABLE takes integer arguments and touches no memory of ours;
        // on failure (an old kernel) the process keeps the system's setting.
        unsafe {
            mi_option_set(MI_OPTION_ALLOW_THP, 0);
            if libc::prctl(
                libc::PR_SET_THP_DISABLE,
                1,
                PR_THP_DISABLE_EXCEPT_ADVISED,
                0,
                0,
            ) != 0
            {
                libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0);
            }
        }
        for (start, end) in advised_mappings() {
            // SAFETY: advice about mappings of this process: it changes neither what they
            // hold nor whether they are mapped.
            unsafe {
                libc::madvise(
                    start as *mut libc::c_void,
                    end - start,
                    libc::MADV_NOHUGEPAGE,
                )
            };
        }
    }
}

/// The mappings advised for huge pages before `main` ran (mimalloc's first arena, which
/// it reserves for the runtime's first allocations): the address ranges of
/// `/proc/self/smaps` whose `VmFlags` include `hg`.
#[cfg(target_os = "linux")]
fn advised_mappings() -> Vec<(usize, usize)> {
    let Ok(smaps) = std::fs::read_to_string("/proc/self/smaps") else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut range = None;
    for line in smaps.lines() {
        if let Some(flags) = line.strip_prefix("VmFlags:") {
            let advised = flags.split_whitespace().any(|f| f == "hg");
            out.extend(range.take().filter(|_| advised));
        } else if let Some((a, b)) = line.split_once(' ').and_then(|(r, _)| r.split_once('-')) {
            if let (Ok(a), Ok(b)) = (usize::from_str_radix(a, 16), usize::from_str_radix(b, 16)) {
                range = Some((a, b));
            }
        }
    }
    out
}

// mimalloc's `mi_option_set`, in the library the `mimalloc` crate links (its own binding
// needs the crate's `extended` feature and another crate for C types).
extern "C" {
    fn mi_option_set(option: std::ffi::c_int, value: std::ffi::c_long);
}

/// `mi_option_allow_thp` in mimalloc's `mi_option_t` (the 44th option, in the headers of mimalloc
/// v3, which the crate builds).
const MI_OPTION_ALLOW_THP: std::ffi::c_int = 43;

/// Linux 6.18's flag of `PR_SET_THP_DISABLE`: regions advised with `MADV_HUGEPAGE` keep
/// huge pages.
const PR_THP_DISABLE_EXCEPT_ADVISED: libc::c_ulong = 1 << 1;

/// `mi_option_purge_delay` in mimalloc's `mi_option_t` (the 16th option, in the headers of
/// both versions the crate builds).
const MI_OPTION_PURGE_DELAY: std::ffi::c_int = 15;

/// Keeps the memory the process frees for its later allocations, unless
/// `MIMALLOC_PURGE_DELAY` says otherwise. mimalloc gives freed memory back to the system a
/// second after it is freed, and the next allocations fault fresh pages in, which the
/// kernel clears: the users' and the products' searches grow tables and free the old
/// ones, and on this project's machine clearing pages was a quarter of a user's search.
/// Without purging, the 5-cup kitchen with both users, exact, on one thread: the
/// newcomer's search 5.3 s instead of 7.5 s, system time 0.6 s instead of 2.5 s; with
/// every property on two cores 9.9-10.7 s instead of 10.7-13.1 s, its peak a few percent
/// higher (2.20-2.27 GB against 2.01-2.30 GB). mimalloc's `MIMALLOC_PURGE_DELAY=-1` does the
/// same from the environment.
fn keep_freed_memory() {
    if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
        // SAFETY: sets one of mimalloc's options (an integer); mimalloc reads it when it
        // decides whether to purge.
        unsafe { mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    }
}

/// A number of seconds: finite and not negative (`-1`, `inf` and `NaN` are usage errors).
fn seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        Ok(_) => Err(format!(
            "`{s}` is not a number of seconds (finite, at least 0)"
        )),
        Err(e) => Err(e.to_string()),
    }
}

/// Verifies Jason AgentSpeak plan libraries before they run on a robot.
#[derive(Parser, Debug)]
#[command(name = "bdi-check", version, about, long_about = None)]
struct Cli {
    /// When to colour the output: `auto` does for a terminal, unless `NO_COLOR` is set or
    /// `TERM=dumb` (`CLICOLOR_FORCE` forces it).
    #[arg(long, global = true, value_enum, default_value = "auto")]
    color: ColorArg,
    #[command(subcommand)]
    command: Command,
}

/// `merge --format`: the merged report is JSON (or its human summary).
#[derive(Clone, Copy, Debug, ValueEnum)]
enum MergeFormat {
    /// The failing findings and the verdict line.
    Human,
    /// The merged report.
    Json,
    /// The merged report as SARIF 2.1.0.
    Sarif,
    /// The merged report as JUnit XML.
    Junit,
}

/// `--color`.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum ColorArg {
    /// For a terminal, as the environment allows.
    Auto,
    /// Always.
    Always,
    /// Never.
    Never,
}

/// Output formats.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum FormatArg {
    /// Text for people.
    Human,
    /// The JSON report.
    Json,
    /// SARIF 2.1.0, for code scanning (lint and verify).
    Sarif,
    /// JUnit XML, for CI test reports (lint and verify).
    Junit,
    /// One self-contained HTML page (lint, verify, simulate, and explain with a scenario).
    Html,
}

/// Options every command shares.
#[derive(Args, Debug)]
struct Output {
    /// Output format.
    #[arg(long, value_enum, default_value = "human")]
    format: FormatArg,
    /// Write the report to this file instead of stdout.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Print the verdict line only.
    #[arg(short, long)]
    quiet: bool,
    /// Print every check, passed ones too.
    #[arg(short, long)]
    verbose: bool,
}

impl Output {
    /// How the command is to write its report.
    fn style(&self) -> commands::Style {
        let (format, ci) = match self.format {
            FormatArg::Human => (Format::Human, None),
            FormatArg::Json => (Format::Json, None),
            FormatArg::Sarif => (Format::Json, Some(CiFormat::Sarif)),
            FormatArg::Junit => (Format::Json, Some(CiFormat::Junit)),
            FormatArg::Html => (Format::Human, None),
        };
        let detail = if self.quiet {
            Detail::Quiet
        } else if self.verbose {
            Detail::Verbose
        } else {
            Detail::Normal
        };
        commands::Style {
            format,
            ci,
            detail,
            html: matches!(self.format, FormatArg::Html),
            color: self.output.is_none() && stdout_color(),
            stderr_color: stderr_color(),
        }
    }
}

/// The search options `verify` and `simulate` share.
#[derive(Args, Debug)]
struct Search {
    /// Stop after this many distinct states (overrides `[bounds] max_states`).
    #[arg(long)]
    max_states: Option<u64>,
    /// Do not expand states deeper than this (overrides `[bounds] max_depth`).
    #[arg(long)]
    max_depth: Option<u64>,
    /// Stop after this many seconds.
    #[arg(long, value_parser = seconds)]
    timeout: Option<f64>,
    /// Write one replayable scenario file per counterexample into this folder.
    #[arg(long)]
    scenarios: Option<PathBuf>,
    /// Threads that search (default: every core). Results do not depend on it.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Turn symmetry reduction off: over `[bounds] symmetry` types, and over instances of
    /// one agent.
    #[arg(long)]
    no_symmetry: bool,
    /// Turn partial-order reduction among several agents off: every interleaving, and
    /// shortest counterexamples.
    #[arg(long)]
    no_partial_order: bool,
    /// `--deny warnings`: failing warnings (static warnings no run settled) fail the run.
    #[arg(long, value_name = "LEVEL", value_parser = ["warnings"])]
    deny: Option<String>,
}

impl Search {
    /// Runs `verify` (or, with `sample`, `simulate`) with these options.
    fn run(
        self,
        project: &std::path::Path,
        shard: Option<(u32, u32)>,
        sample: Option<bdi_check::check::sample::Sample>,
        out: &Output,
    ) -> commands::Output {
        let bar = Progress::new();
        let defaults = bdi_check::check::VerifyOptions::default();
        let opts = bdi_check::check::VerifyOptions {
            threads: self.threads.map_or(defaults.threads, |t| t as usize),
            symmetry: !self.no_symmetry,
            shard,
            max_memory: bdi_check::check::explore::default_max_memory(),
            compiled: defaults.compiled,
            sample,
            partial_order: !self.no_partial_order,
            stored_users: defaults.stored_users,
        };
        let bounds = commands::verify::Bounds {
            max_states: self.max_states,
            max_depth: self.max_depth,
            timeout: self.timeout,
            deny_warnings: self.deny.is_some(),
        };
        let done = commands::verify::command(
            project,
            &bounds,
            &opts,
            self.scenarios.as_deref(),
            &out.style(),
            |phase, n, d, t| bar.tick(phase, n, d, t),
        );
        bar.finish();
        done
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse .asl, .pddl or bdi-check.toml files and report every error.
    Parse {
        /// The files to parse.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// A folder where `include` looks after the including file's own (Jason's
        /// `aslSourcePath`); may be given several times.
        #[arg(short = 'I', value_name = "DIR")]
        include: Vec<PathBuf>,
        #[command(flatten)]
        out: Output,
    },
    /// Static checks of the plan library with z3, no state exploration.
    Lint {
        /// The project folder or its bdi-check.toml.
        project: PathBuf,
        /// `--deny warnings`: failing warnings fail the run.
        #[arg(long, value_name = "LEVEL", value_parser = ["warnings"])]
        deny: Option<String>,
        #[command(flatten)]
        out: Output,
    },
    /// Explore every reachable state of a project and check its properties.
    Verify {
        /// The project folder or its bdi-check.toml.
        project: PathBuf,
        /// Verify from the K-th of N parts of the initial states only (merge the N reports
        /// with `bdi-check merge`).
        #[arg(long, value_name = "K/N", value_parser = parse_shard)]
        shard: Option<(u32, u32)>,
        #[command(flatten)]
        search: Search,
        #[command(flatten)]
        out: Output,
    },
    /// Follow random runs, for state spaces too large to exhaust: lint, then the checks of
    /// `verify` on the states the runs reach. A violation comes with its run; with none,
    /// the result is incomplete (exit 3), never a pass.
    Simulate {
        /// The project folder or its bdi-check.toml.
        project: PathBuf,
        /// How many runs to follow side by side (at every depth, this many of the states
        /// reached are expanded, chosen at random).
        #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// The seed of the random choices: the same seed follows the same runs.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        #[command(flatten)]
        search: Search,
        #[command(flatten)]
        out: Output,
    },
    /// Merge the JSON reports of `verify --shard K/N` runs into one report and verdict.
    Merge {
        /// The JSON reports, one per shard.
        #[arg(required = true)]
        reports: Vec<PathBuf>,
        /// Output format (`human`: the failing findings and the verdict line; `json`: the
        /// merged report, which `lint`/`verify`'s SARIF and JUnit are made from).
        #[arg(long, value_enum, default_value = "json")]
        format: MergeFormat,
        /// Write the merged report to this file instead of stdout.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
    },
    /// Run one scenario and print its trace with the explanations each user gets; without a
    /// scenario, list every distinct explanation the runs give, per user.
    Explain {
        /// The project folder or its bdi-check.toml.
        project: PathBuf,
        /// A scenario file (`initial = [...]`, `requests = [...]`).
        #[arg(long)]
        scenario: Option<PathBuf>,
        /// Only this user's explanations.
        #[arg(long)]
        user: Option<String>,
        #[command(flatten)]
        out: Output,
    },
    /// Draw the goal-plan tree (`--plans`) or the state graph (`--states`) as DOT.
    #[command(group(clap::ArgGroup::new("what").required(true).args(["plans", "states"])))]
    Graph {
        /// The project folder or its bdi-check.toml.
        project: PathBuf,
        /// The goal-plan tree: goals, the plans for them with their contexts, subgoals.
        #[arg(long)]
        plans: bool,
        /// The state graph (or the part the counterexamples go through, when it is large).
        #[arg(long)]
        states: bool,
        /// Stop after this many distinct states (overrides `[bounds] max_states`).
        #[arg(long)]
        max_states: Option<u64>,
        /// Write the DOT text to this file instead of stdout.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
    },
    /// Replay the counterexamples of a JSON report against the project as it is now.
    Replay {
        /// A report written by `verify --format json`.
        report: PathBuf,
        /// Replay only this finding.
        #[arg(long)]
        finding: Option<String>,
    },
    /// A counterexample step by step, with the agent's whole state after each transition.
    ///
    /// Exit 1 while the run still reaches its violation, 0 once it does not, 2 on bad input.
    Trace {
        /// A report written by `verify --format json`.
        report: PathBuf,
        /// The finding whose run to trace (its `id` in the report).
        #[arg(long)]
        finding: String,
        #[command(flatten)]
        out: Output,
    },
}

fn main() -> ExitCode {
    no_transparent_huge_pages();
    keep_freed_memory();
    // One command per process: what a verification allocated goes with the process.
    bdi_check::check::leave_memory_to_exit();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // clap's usage errors are bad input: exit 2, as SPEC §2 asks (help and version: 0).
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    anstream::ColorChoice::write_global(match cli.color {
        ColorArg::Auto => anstream::ColorChoice::Auto,
        ColorArg::Always => anstream::ColorChoice::Always,
        ColorArg::Never => anstream::ColorChoice::Never,
    });
    let (done, output) = match cli.command {
        Command::Parse {
            files,
            include,
            out,
        } => (
            commands::parse::command(&files, &include, out.quiet, &out.style()),
            out.output,
        ),
        Command::Lint { project, deny, out } => (
            commands::lint::command(&project, deny.is_some(), &out.style()),
            out.output,
        ),
        Command::Verify {
            project,
            shard,
            search,
            out,
        } => (search.run(&project, shard, None, &out), out.output),
        Command::Simulate {
            project,
            runs,
            seed,
            search,
            out,
        } => {
            let sample = bdi_check::check::sample::Sample { runs, seed };
            (search.run(&project, None, Some(sample), &out), out.output)
        }
        Command::Explain {
            project,
            scenario,
            user,
            out,
        } => (
            commands::explain::command(
                &project,
                scenario.as_deref(),
                user.as_deref(),
                &out.style(),
            ),
            out.output,
        ),
        Command::Graph {
            project,
            plans,
            states: _,
            max_states,
            output,
        } => (
            commands::graph::command(&project, plans, max_states, stderr_color()),
            output,
        ),
        Command::Merge {
            reports,
            format,
            output,
        } => {
            let done = match format {
                MergeFormat::Json => commands::merge::command(&reports, Format::Json, None),
                MergeFormat::Human => commands::merge::command(&reports, Format::Human, None),
                MergeFormat::Sarif => {
                    commands::merge::command(&reports, Format::Json, Some(CiFormat::Sarif))
                }
                MergeFormat::Junit => {
                    commands::merge::command(&reports, Format::Json, Some(CiFormat::Junit))
                }
            };
            (done, output)
        }
        Command::Replay {
            report: path,
            finding,
        } => (commands::replay::command(&path, finding.as_deref()), None),
        Command::Trace {
            report: path,
            finding,
            out,
        } => (
            commands::trace::command(&path, &finding, &out.style()),
            out.output,
        ),
    };
    eprint!("{}", done.stderr);
    match done.report {
        Some(text) => finish(&text, output, done.code),
        None => ExitCode::from(done.code as u8),
    }
}

// Whether a stream gets colour: `--color`, set as anstream's global choice, with the
// environment's `NO_COLOR`, `CLICOLOR_FORCE` and `TERM` under `auto`.
fn stdout_color() -> bool {
    anstream::AutoStream::choice(&std::io::stdout()) != anstream::ColorChoice::Never
}

fn stderr_color() -> bool {
    anstream::AutoStream::choice(&std::io::stderr()) != anstream::ColorChoice::Never
}

/// Parses `K/N` with `1 <= K <= N`.
fn parse_shard(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected K/N with 1 <= K <= N (e.g. 1/4), found `{s}`");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let k: u32 = k.trim().parse().map_err(|_| bad())?;
    let n: u32 = n.trim().parse().map_err(|_| bad())?;
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// A spinner on stderr with the phase, its states, depth and states/s, shown once a run
/// passes a second and only when stderr is a terminal.
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    started: std::time::Instant,
}

impl Progress {
    fn new() -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = indicatif::ProgressBar::hidden();
            b.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg}")
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
            );
            b
        });
        Progress {
            bar,
            started: std::time::Instant::now(),
        }
    }

    /// `phase` has reached `states` states and `depth` in `seconds`.
    fn tick(&self, phase: &str, states: usize, depth: u32, seconds: f64) {
        if let Some(b) = &self.bar {
            if self.started.elapsed().as_secs_f64() > 1.0 {
                if b.is_hidden() {
                    b.set_draw_target(indicatif::ProgressDrawTarget::stderr());
                }
                b.set_message(if states == 0 {
                    format!("{phase}...")
                } else {
                    format!(
                        "{phase}: {states} states, depth {depth}, {:.0} states/s",
                        states as f64 / seconds.max(1e-9)
                    )
                });
                b.tick();
            }
        }
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

/// Writes the report to `-o FILE` or stdout and exits with `code`.
fn finish(text: &str, output: Option<PathBuf>, code: i32) -> ExitCode {
    let written = match output {
        Some(path) => std::fs::write(&path, text).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot write `{}`: {e}", path.display()))
        }),
        None => {
            let mut stdout = std::io::stdout().lock();
            stdout
                .write_all(text.as_bytes())
                .and_then(|_| stdout.flush())
        }
    };
    match written {
        Ok(()) => ExitCode::from(code as u8),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    extern "C" {
        fn mi_option_get(option: std::ffi::c_int) -> std::ffi::c_long;
    }

    /// Whether mimalloc reads `env`, set to `value` before the process starts, into its
    /// option number `option` (run in a child process: the test `name` again).
    fn read_from_environment(name: &str, option: std::ffi::c_int, env: &str, value: &str) {
        const CHILD: &str = "BDI_CHECK_OPTION_CHILD";
        // SAFETY: reads one of mimalloc's options.
        let read = unsafe { mi_option_get(option) };
        if let Ok(v) = std::env::var(CHILD) {
            assert_eq!(read.to_string(), v);
            return;
        }
        let exe = std::env::current_exe().expect("the test binary");
        let out = std::process::Command::new(exe)
            .args([name, "--exact", "--test-threads=1"])
            .env(env, value)
            .env(CHILD, value)
            .output()
            .expect("the test binary runs");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success() && stdout.contains("1 passed"),
            "{stdout}"
        );
    }

    #[test]
    fn the_option_kept_at_minus_one_is_mimallocs_purge_delay() {
        let name = "tests::the_option_kept_at_minus_one_is_mimallocs_purge_delay";
        read_from_environment(name, MI_OPTION_PURGE_DELAY, "MIMALLOC_PURGE_DELAY", "1234");
        if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
            keep_freed_memory();
            // SAFETY: reads one of mimalloc's options.
            assert_eq!(unsafe { mi_option_get(MI_OPTION_PURGE_DELAY) }, -1);
        }
    }

    #[test]
    #[cfg(target_os = "linux")]
    fn the_mappings_advised_for_huge_pages_are_found() {
        const SIZE: usize = 4 << 20;
        // SAFETY: a fresh private anonymous mapping, advised, looked up, unmapped.
        unsafe {
            let p = libc::mmap(
                std::ptr::null_mut(),
                SIZE,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            );
            assert_ne!(p, libc::MAP_FAILED);
            let (a, b) = (p as usize, p as usize + SIZE);
            let found = |m: &[(usize, usize)]| m.iter().any(|&(x, y)| x <= a && b <= y);
            assert!(!found(&advised_mappings()));
            if libc::madvise(p, SIZE, libc::MADV_HUGEPAGE) == 0 {
                assert!(found(&advised_mappings()));
                libc::madvise(p, SIZE, libc::MADV_NOHUGEPAGE);
                assert!(!found(&advised_mappings()));
            }
            libc::munmap(p, SIZE);
        }
    }

    #[test]
    fn the_option_turned_off_is_mimallocs_allow_thp() {
        let name = "tests::the_option_turned_off_is_mimallocs_allow_thp";
        read_from_environment(name, MI_OPTION_ALLOW_THP, "MIMALLOC_ALLOW_THP", "7");
    }
}
