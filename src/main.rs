//! The `bdi-check` command line: argument parsing and dispatch, nothing else.

use bdi_check::report::{self, verify::Detail, Format};
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

// Exploration allocates and frees small states at a high rate on every thread (see
// Cargo.toml).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

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
    #[command(subcommand)]
    command: Command,
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
    /// The human or JSON format; the CI formats are taken by [`Output::ci_format`] first
    /// (lint, verify) or refused by [`Output::refuse_ci_format`] (other commands).
    fn format(&self) -> Format {
        match self.format {
            FormatArg::Human => Format::Human,
            FormatArg::Json | FormatArg::Sarif | FormatArg::Junit => Format::Json,
        }
    }

    fn ci_format(&self) -> Option<report::CiFormat> {
        match self.format {
            FormatArg::Sarif => Some(report::CiFormat::Sarif),
            FormatArg::Junit => Some(report::CiFormat::Junit),
            FormatArg::Human | FormatArg::Json => None,
        }
    }

    /// A usage error (exit 2, as clap's) when a command that has no findings to report is
    /// asked for SARIF or JUnit.
    fn refuse_ci_format(&self, command: &str) -> Option<ExitCode> {
        let name = match self.ci_format()? {
            report::CiFormat::Sarif => "sarif",
            report::CiFormat::Junit => "junit",
        };
        eprintln!(
            "error: `--format {name}` is for `lint` and `verify`; `{command}` writes `human` or `json`"
        );
        Some(ExitCode::from(2))
    }

    fn detail(&self) -> Detail {
        if self.quiet {
            Detail::Quiet
        } else if self.verbose {
            Detail::Verbose
        } else {
            Detail::Normal
        }
    }

    fn color(&self) -> bool {
        self.output.is_none() && std::io::stdout().is_terminal()
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
        /// Worker threads for the search (default: every core). Results do not depend on it.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        threads: Option<u32>,
        /// Turn symmetry reduction over `[bounds] symmetry` types off.
        #[arg(long)]
        no_symmetry: bool,
        /// Verify from the K-th of N parts of the initial states only (merge the N reports
        /// with `bdi-check merge`).
        #[arg(long, value_name = "K/N", value_parser = parse_shard)]
        shard: Option<(u32, u32)>,
        #[command(flatten)]
        out: Output,
    },
    /// Merge the JSON reports of `verify --shard K/N` runs into one report and verdict.
    Merge {
        /// The JSON reports, one per shard.
        #[arg(required = true)]
        reports: Vec<PathBuf>,
        /// Output format (`human`: the verdict line; `json`: the merged report).
        #[arg(long, value_enum, default_value = "json")]
        format: FormatArg,
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
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // clap's usage errors are bad input: exit 2, as SPEC §2 asks (help and version: 0).
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match cli.command {
        Command::Parse {
            files,
            include,
            out,
        } => {
            if let Some(code) = out.refuse_ci_format("parse") {
                return code;
            }
            let run = report::outline::parse_files_with(&files, &include);
            let (mut text, err) = report::outline::render(&run, out.format(), out.color());
            if out.quiet && out.format() == Format::Human {
                text = text
                    .lines()
                    .last()
                    .map(|l| format!("{l}\n"))
                    .unwrap_or_default();
            }
            eprint!("{err}");
            finish(&text, out.output, run.report.verdict.exit_code())
        }
        Command::Lint { project, deny, out } => {
            let opts = bdi_check::smt::LintOptions::default();
            let run = report::lint::run(&project, &opts, deny.is_some());
            let (text, err) = match out.ci_format() {
                Some(ci) => (ci.render(&run.report, "lint"), String::new()),
                None => report::lint::render(&run, out.format(), out.detail(), out.color()),
            };
            eprint!("{err}");
            finish(&text, out.output, run.report.verdict.exit_code())
        }
        Command::Verify {
            project,
            max_states,
            max_depth,
            timeout,
            scenarios,
            threads,
            no_symmetry,
            shard,
            out,
        } => {
            let bar = Progress::new();
            let defaults = bdi_check::check::VerifyOptions::default();
            let opts = bdi_check::check::VerifyOptions {
                threads: threads.map_or(defaults.threads, |t| t as usize),
                symmetry: !no_symmetry,
                shard,
                max_memory: bdi_check::check::explore::default_max_memory(),
                compiled: defaults.compiled,
            };
            let run = report::verify::run_with(
                &project,
                max_states,
                max_depth,
                timeout,
                &opts,
                |n, d, t| bar.tick(n, d, t),
            );
            bar.finish();
            if let Some(dir) = &scenarios {
                if let Err(e) = report::verify::write_scenarios(&run.report, dir) {
                    eprintln!(
                        "error: cannot write scenarios into `{}`: {e}",
                        dir.display()
                    );
                    return ExitCode::from(2);
                }
            }
            let text = match (out.ci_format(), out.format()) {
                (Some(ci), _) => ci.render(&run.report, "verify"),
                (None, Format::Json) => {
                    serde_json::to_string_pretty(&run.report).unwrap_or_default() + "\n"
                }
                (None, Format::Human) => {
                    report::verify::render_human(&run, out.detail(), out.color())
                }
            };
            finish(&text, out.output, run.report.verdict.exit_code())
        }
        Command::Explain {
            project,
            scenario,
            user,
            out,
        } => match scenario {
            _ if out.ci_format().is_some() => {
                out.refuse_ci_format("explain").unwrap_or(ExitCode::from(2))
            }
            Some(sc) => {
                let run = report::explain::run(&project, &sc, user.as_deref());
                if !run.diagnostics.is_empty() {
                    if out.format() == Format::Json {
                        let findings: Vec<_> = run
                            .diagnostics
                            .iter()
                            .map(|d| report::Finding::from_input_diagnostic(d, &run.map))
                            .collect();
                        let r = report::Report::new(project.display().to_string(), findings);
                        return finish(
                            &(serde_json::to_string_pretty(&r).unwrap_or_default() + "\n"),
                            out.output,
                            2,
                        );
                    }
                    eprint!(
                        "{}",
                        report::explain::render_human(&run, std::io::stderr().is_terminal())
                    );
                    return ExitCode::from(2);
                }
                let text = match out.format() {
                    Format::Json => report::explain::render_json(&run),
                    Format::Human => report::explain::render_human(&run, out.color()),
                };
                finish(&text, out.output, 0)
            }
            None => match report::explain::catalogue(&project, user.as_deref()) {
                Ok(report::explain::Catalogue { entries, note, .. }) => {
                    let text = match out.format() {
                        Format::Json => {
                            let v = serde_json::json!({
                                "tool": report::Tool::default(),
                                "project": project.display().to_string(),
                                "verdict": "pass",
                                "findings": [],
                                "explanations": entries,
                                "note": note,
                            });
                            serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"
                        }
                        Format::Human => {
                            report::explain::render_catalogue(&entries, note.as_deref())
                        }
                    };
                    finish(&text, out.output, 0)
                }
                Err((map, errs)) => {
                    for d in &errs {
                        eprintln!("{}", d.render(&map, std::io::stderr().is_terminal()));
                    }
                    ExitCode::from(2)
                }
            },
        },
        Command::Graph {
            project,
            plans,
            states: _,
            max_states,
            output,
        } => {
            let p = match bdi_check::model::project::load_project(&project) {
                Ok(p) => p,
                Err(e) => {
                    for d in &e.diagnostics {
                        eprintln!("{}", d.render(&e.map, std::io::stderr().is_terminal()));
                    }
                    return ExitCode::from(2);
                }
            };
            if plans {
                return finish(&report::graph::plans_dot(&p), output, 0);
            }
            let limits = report::verify::limits(&p, max_states, None, None);
            match report::graph::states_dot(&p, limits) {
                Ok((dot, note)) => {
                    if let Some(n) = note {
                        eprintln!("note: {n}");
                    }
                    finish(&dot, output, 0)
                }
                Err(errs) => {
                    for d in &errs {
                        eprintln!("{}", d.render(&p.map, false));
                    }
                    ExitCode::from(2)
                }
            }
        }
        Command::Merge {
            reports,
            format,
            output,
        } => {
            let mut values = Vec::new();
            for path in &reports {
                let read = std::fs::read_to_string(path)
                    .map_err(|e| e.to_string())
                    .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()));
                match read {
                    Ok(v) => values.push(v),
                    Err(e) => {
                        eprintln!("error: cannot read the report `{}`: {e}", path.display());
                        return ExitCode::from(2);
                    }
                }
            }
            match report::verify::merge(&values) {
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
                Ok(merged) => {
                    let verdict = merged["verdict"].as_str().unwrap_or("error").to_string();
                    let code = match verdict.as_str() {
                        "pass" => 0,
                        "fail" => 1,
                        "incomplete" => 3,
                        _ => 2,
                    };
                    let text = match format {
                        FormatArg::Json => {
                            serde_json::to_string_pretty(&merged).unwrap_or_default() + "\n"
                        }
                        FormatArg::Human => format!(
                            "verdict: {verdict} (merged {} reports, {} checks)\n",
                            reports.len(),
                            merged["findings"].as_array().map_or(0, |f| f.len())
                        ),
                        FormatArg::Sarif | FormatArg::Junit => {
                            eprintln!("error: `merge` writes `human` or `json`");
                            return ExitCode::from(2);
                        }
                    };
                    finish(&text, output, code)
                }
            }
        }
        Command::Replay {
            report: path,
            finding,
        } => match report::replay::replay(&path, finding.as_deref()) {
            Err(errs) => {
                for e in errs {
                    eprintln!("{}", e.render(&bdi_check::syntax::SourceMap::new(), false));
                }
                ExitCode::from(2)
            }
            Ok(results) => {
                let mut reached = false;
                for r in &results {
                    let verdict = if r.reached {
                        "still reaches"
                    } else {
                        "no longer reaches"
                    };
                    println!("{}: {verdict} its violation ({})", r.id, r.detail);
                    reached |= r.reached;
                }
                ExitCode::from(u8::from(reached))
            }
        },
    }
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

/// A spinner on stderr with states, depth and states/s, shown once a run passes a second
/// and only when stderr is a terminal.
struct Progress {
    bar: Option<indicatif::ProgressBar>,
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
        Progress { bar }
    }

    fn tick(&self, states: usize, depth: u32, seconds: f64) {
        if let Some(b) = &self.bar {
            if seconds > 1.0 {
                if b.is_hidden() {
                    b.set_draw_target(indicatif::ProgressDrawTarget::stderr());
                }
                b.set_message(format!(
                    "{states} states, depth {depth}, {:.0} states/s",
                    states as f64 / seconds
                ));
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
