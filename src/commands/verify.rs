//! `bdi-check verify`: load a project, lint it, explore every reachable state and settle
//! the lint warnings (rendered by [`crate::report::verify`]).

use super::{Output, Style};
use crate::check::explore::Limits;
use crate::check::{verify_with, VerifyOptions};
use crate::findings::{Finding, Report, Shard, Verdict};
use crate::model::project::{load_system, Project};
use crate::report::verify::{render_human, write_scenarios, VerifyRun};
use crate::report::Format;
use crate::syntax::{Diagnostic, SourceMap};
use std::path::Path;

/// What the warning of a shard that holds no initial state says.
pub const EMPTY_SHARD: &str = "holds none of the initial states";

/// The options of `verify` beyond the search's own ([`VerifyOptions`]).
#[derive(Clone, Debug, Default)]
pub struct Bounds {
    /// `--max-states`, over `[bounds] max_states`.
    pub max_states: Option<u64>,
    /// `--max-depth`, over `[bounds] max_depth`.
    pub max_depth: Option<u64>,
    /// `--timeout`, in seconds.
    pub timeout: Option<f64>,
    /// `--deny warnings`: failing warnings (static warnings no run settled) are errors.
    pub deny_warnings: bool,
}

/// `verify PROJECT`: the report, and one scenario file per counterexample into
/// `scenarios` when given. `progress` is called now and then with the phase (`lint`,
/// `search`, `liveness`, `explanation:USER`), its states, depth and seconds.
pub fn command(
    project: &Path,
    bounds: &Bounds,
    opts: &VerifyOptions,
    scenarios: Option<&Path>,
    style: &Style,
    progress: impl FnMut(&str, usize, u32, f64),
) -> Output {
    let mut run = run(project, bounds, opts, progress);
    if bounds.deny_warnings {
        deny_warnings(&mut run.report);
    }
    if let Some(dir) = scenarios {
        if let Err(e) = write_scenarios(&run.report, dir) {
            return Output::refused(format!(
                "error: cannot write scenarios into `{}`: {e}\n",
                dir.display()
            ));
        }
    }
    let command = if opts.sample.is_some() {
        "simulate"
    } else {
        "verify"
    };
    let text = match (style.ci, style.format) {
        _ if style.html && run.diagnostics.is_empty() => {
            crate::report::html::render(&run.report, &run.tree, command)
        }
        (Some(ci), _) => ci.render(&run.report, command),
        (None, Format::Json) => {
            serde_json::to_string_pretty(&run.report).unwrap_or_default() + "\n"
        }
        (None, Format::Human) => render_human(&run, style.detail, style.color),
    };
    Output::report(text, run.report.verdict.exit_code())
}

/// `--deny warnings`, as rustc's `-D warnings`: a failing warning is an error, and fails
/// the verdict.
fn deny_warnings(report: &mut Report) {
    for f in &mut report.findings {
        if f.status == crate::findings::Status::Fail
            && f.severity == crate::syntax::Severity::Warning
        {
            f.severity = crate::syntax::Severity::Error;
        }
    }
    if crate::findings::verdict_of(&report.findings) == Verdict::Fail {
        report.verdict = Verdict::Fail;
    }
}

/// The limits of a project's search: the manifest's `[bounds]`, overridden by options.
pub fn limits(project: &Project, bounds: &Bounds) -> Limits {
    Limits {
        max_states: bounds
            .max_states
            .unwrap_or(project.manifest.bounds.max_states),
        max_depth: bounds
            .max_depth
            .unwrap_or(project.manifest.bounds.max_depth),
        timeout: bounds.timeout,
    }
}

/// Runs `lint` within the limits' `--timeout` (lint begins no check past it) and returns
/// its findings with the limits left for the search (the time lint did not use).
fn lint_within(
    mut lim: Limits,
    lint: impl FnOnce(&crate::smt::LintOptions) -> Vec<crate::smt::LintFinding>,
) -> (Vec<Finding>, Limits, f64) {
    let started = std::time::Instant::now();
    let deadline = lim
        .timeout
        .and_then(|t| std::time::Duration::try_from_secs_f64(t).ok())
        .and_then(|d| started.checked_add(d));
    let opts = crate::smt::LintOptions {
        deadline,
        ..Default::default()
    };
    let findings = lint(&opts).into_iter().map(|l| l.finding).collect();
    let seconds = started.elapsed().as_secs_f64();
    lim.timeout = lim.timeout.map(|t| (t - seconds).max(0.0));
    (findings, lim, seconds)
}

/// The whole run's time in the statistics (loading and every phase), with lint's phase
/// first: the verdict line and `stats.seconds` say what the user waited for.
fn whole_run(mut run: VerifyRun, started: std::time::Instant, lint: f64) -> VerifyRun {
    if let Some(st) = &mut run.report.stats {
        st.phases.insert(
            0,
            crate::findings::Phase {
                name: "lint".into(),
                seconds: lint,
                states: None,
                beside: Vec::new(),
            },
        );
        st.seconds = started.elapsed().as_secs_f64();
        let states = st.states + st.liveness_states.unwrap_or(0);
        st.states_per_second = if st.seconds > 0.0 {
            states as f64 / st.seconds
        } else {
            0.0
        };
    }
    run
}

/// Loads, lints and verifies a project.
pub fn run(
    path: &Path,
    bounds: &Bounds,
    opts: &VerifyOptions,
    progress: impl FnMut(&str, usize, u32, f64),
) -> VerifyRun {
    let started = std::time::Instant::now();
    let name = path.display().to_string();
    let mut projects = match load_system(path) {
        Ok(p) => p,
        Err(e) => return input_failure(name, e.map, e.diagnostics),
    };
    if projects.len() > 1 {
        return run_system(name, projects, bounds, opts, progress, started);
    }
    let project = projects.remove(0);
    let bad = super::allow::check(&project);
    if !bad.is_empty() {
        return input_failure(name, project.map, bad);
    }
    // SPEC §2: verify runs lint first; its warnings are settled by the exploration.
    let mut progress = progress;
    progress("lint", 0, 0, 0.0);
    let (lint, lim, linted) =
        lint_within(limits(&project, bounds), |o| crate::smt::lint(&project, o));
    match verify_with(&project, lim, opts, &mut progress, &lint) {
        Err(diagnostics) => input_failure(name, project.map, diagnostics),
        Ok(v) => whole_run(report_of(name, project, v, opts), started, linted),
    }
}

/// Lints and verifies a project of several agents: each agent's plan library is linted
/// on its own (its warnings stay warnings: they are not settled against the runs yet),
/// then every interleaving is explored ([`crate::check::system`]).
fn run_system(
    name: String,
    projects: Vec<Project>,
    bounds: &Bounds,
    opts: &VerifyOptions,
    progress: impl FnMut(&str, usize, u32, f64),
    started: std::time::Instant,
) -> VerifyRun {
    let mut bad = super::allow::check(&projects[0]);
    if opts.shard.is_some() {
        bad.push(
            Diagnostic::error(
                "input",
                "a project of several agents is verified whole: `--shard` is not supported for it yet",
            )
            .in_file(projects[0].manifest.path.display().to_string()),
        );
    }
    if !bad.is_empty() {
        let map = projects.into_iter().next().expect("an agent").map;
        return input_failure(name, map, bad);
    }
    let mut progress = progress;
    progress("lint", 0, 0, 0.0);
    let (lint, lim, linted) = lint_within(limits(&projects[0], bounds), |o| {
        super::lint::lint_agents(&projects, o)
    });
    let mut result =
        crate::check::system::verify_system(&projects, lim, opts, &mut progress, lint.clone());
    // Partial-order reduction keeps every violation, not its shortest run: a violation
    // found is searched again over every interleaving, and that search's report stands
    // when it is complete.
    if let Ok(v) = &result {
        if reduced_violation(&v.findings, v.reduced_states) {
            let every = VerifyOptions {
                partial_order: false,
                ..*opts
            };
            if let Ok(full) =
                crate::check::system::verify_system(&projects, lim, &every, &mut progress, lint)
            {
                if full.stats.complete {
                    result = Ok(full);
                }
            }
        }
    }
    match result {
        Err(diagnostics) => {
            let map = projects.into_iter().next().expect("an agent").map;
            input_failure(name, map, diagnostics)
        }
        Ok(v) => {
            let project = projects.into_iter().next().expect("an agent");
            whole_run(report_of(name, project, v, opts), started, linted)
        }
    }
}

/// Whether a search that partial-order reduction cut (`reduced` states) found a
/// violation with a run: a run that may be longer than the shortest. The explanation
/// properties are checked on a search of their own, never reduced: their runs are
/// shortest.
fn reduced_violation(findings: &[Finding], reduced: usize) -> bool {
    reduced > 0
        && findings.iter().any(|f| {
            f.status == crate::findings::Status::Fail
                && f.counterexample.is_some()
                && !crate::check::explanation::CHECKS.contains(&f.check.as_str())
        })
}

/// The report of a verification.
fn report_of(
    name: String,
    project: Project,
    mut v: crate::check::Verification,
    opts: &VerifyOptions,
) -> VerifyRun {
    let unused = super::allow::apply(&project, &mut v.findings, |_| true);
    let mut report = Report::new(name, v.findings);
    report.warnings.extend(unused);
    if report.verdict == Verdict::Pass && !v.stats.complete {
        report.verdict = Verdict::Incomplete;
    }
    if let Some((index, count)) = opts.shard {
        report.shard = Some(Shard { index, count });
        if v.stats.initial_states == 0 {
            report.warnings.push(format!(
                "shard {index}/{count} {EMPTY_SHARD}: it checked nothing (merge it with the other shards)"
            ));
        }
    }
    report.stats = Some(v.stats);
    report.sources = crate::findings::sources_of(&project.map);
    report.warnings.extend(
        v.beyond
            .as_ref()
            .map(|b| format!("a run leaves the model, and the search does not follow it: {b}")),
    );
    if reduced_violation(&report.findings, v.reduced_states) {
        report.warnings.push("partial-order reduction left out interleavings, and the search over all of them stopped at a bound: a run shown may be longer than the shortest one (`--no-partial-order` searches every interleaving)".into());
    }
    report.warnings.extend(v.warnings);
    report.warnings.extend(v.symmetry_caveat.map(|r| format!("symmetry reduction treats the objects as interchangeable, but renaming {r} changes what the agent does in a reachable state (Jason perceives the effects of one action in an order that depends on the names): a run of a merged state may have been left out; `--no-symmetry` gives the exact verdict")));
    VerifyRun {
        report,
        tree: crate::report::html::PlanTree::of(&project),
        map: project.map,
        diagnostics: Vec::new(),
        bound: v.bound,
    }
}

fn input_failure(name: String, map: SourceMap, diagnostics: Vec<Diagnostic>) -> VerifyRun {
    let report = super::input_report(name, &map, &diagnostics);
    VerifyRun {
        report,
        map,
        diagnostics,
        bound: None,
        tree: Default::default(),
    }
}
