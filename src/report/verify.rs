//! `bdi-check verify`: the report of the model checker, for people (counterexamples told
//! as numbered stories) and for machines (SPEC §3 JSON), and scenario files.

use crate::check::explore::Bound;
use crate::findings::{
    Counterexample, Finding, Report, Stats, Status, StepKindTag, TraceStep, Verdict,
};
use crate::syntax::{Diagnostic, Severity, SourceMap};
use std::path::Path;

/// The outcome of `verify` on one project.
pub struct VerifyRun {
    /// The report.
    pub report: Report,
    /// The files read, for excerpts.
    pub map: SourceMap,
    /// Input errors, when the project did not load.
    pub diagnostics: Vec<Diagnostic>,
    /// The bound that cut the search short, if any.
    pub bound: Option<Bound>,
    /// The goal-plan tree, for the HTML page (empty when the project did not load).
    pub tree: super::html::PlanTree,
}

/// What the human output shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Detail {
    /// The verdict line only (`-q`).
    Quiet,
    /// Failures with their counterexamples, then the summary.
    Normal,
    /// Every check, passed ones too (`-v`).
    Verbose,
}

/// The probability that two of `n` distinct states share a 64-bit fingerprint.
pub fn collision_probability(n: usize) -> f64 {
    let n = n as f64;
    (n * n / 2f64.powi(65)).min(1.0)
}

/// The human report: failing findings with excerpts and counterexample stories, then the
/// statistics and the verdict line.
pub fn render_human(run: &VerifyRun, detail: Detail, color: bool) -> String {
    let mut out = String::new();
    let r = &run.report;
    // Bad input is always shown, even with `-q`: the verdict alone does not say what to fix.
    out.push_str(&super::diagnostics(&run.diagnostics, &run.map, color));
    if detail != Detail::Quiet {
        if run.diagnostics.is_empty() {
            let verbose = detail == Detail::Verbose;
            let mut shown: Vec<&Finding> = r
                .findings
                .iter()
                .filter(|f| verbose || rank(f) < 2)
                .collect();
            // Errors first, then warnings; notes and passes only with `-v`.
            shown.sort_by_key(|f| rank(f));
            for f in shown {
                out.push_str(&render_finding(f, &run.map, color));
                out.push('\n');
            }
            if !verbose {
                out.push_str(&hidden_notes(r.findings.iter().filter(|f| rank(f) == 2)));
            }
        }
        if let Some(s) = &r.stats {
            for w in &r.warnings {
                out.push_str(&format!("warning: {w}\n"));
            }
            out.push_str(&render_stats(s, run.bound, detail == Detail::Verbose));
        }
    }
    out.push_str(&paint_verdict(&summary(r), r.verdict, color));
    out
}

/// The verdict line in its colour (green pass, yellow incomplete, red fail or error), when
/// colour is on.
pub fn paint_verdict(line: &str, verdict: Verdict, color: bool) -> String {
    let c = match verdict {
        Verdict::Pass => anstyle::AnsiColor::Green,
        Verdict::Incomplete => anstyle::AnsiColor::Yellow,
        Verdict::Fail | Verdict::Error => anstyle::AnsiColor::Red,
    };
    let text = crate::syntax::diagnostic::bold(line.trim_end_matches('\n'), c, color);
    format!("{text}\n")
}

/// Where a finding goes in the human report: 0 failing errors, 1 failing warnings and
/// undecided checks, 2 notes, 3 passes.
pub fn rank(f: &Finding) -> u8 {
    if f.suppressed.is_some() {
        return 2;
    }
    match (f.status, f.severity) {
        (Status::Fail, Severity::Error) => 0,
        (Status::Fail, Severity::Warning) | (Status::Unknown, _) => 1,
        (Status::Fail, Severity::Note) => 2,
        (Status::Pass, _) => 3,
    }
}

/// The line that says how many notes and suppressed findings `-v` would show.
pub fn hidden_notes<'f>(hidden: impl Iterator<Item = &'f Finding>) -> String {
    let (allowed, notes): (Vec<&Finding>, Vec<&Finding>) =
        hidden.partition(|f| f.suppressed.is_some());
    let plural = |n: usize, one: &str| format!("{n} {one}{}", if n == 1 { "" } else { "s" });
    let what = match (notes.len(), allowed.len()) {
        (0, 0) => return String::new(),
        (n, 0) => plural(n, "note"),
        (0, a) => format!("{} suppressed by [[allow]]", plural(a, "finding")),
        (n, a) => format!(
            "{} and {} suppressed by [[allow]]",
            plural(n, "note"),
            plural(a, "finding")
        ),
    };
    format!("{what} not shown (`-v` shows them)\n")
}

fn render_finding(f: &Finding, map: &SourceMap, color: bool) -> String {
    // An undecided check is not a failure: it reads as a warning, never as an error.
    let severity = match (f.status, f.severity) {
        (Status::Pass, _) => Severity::Note,
        (Status::Unknown, Severity::Error) => Severity::Warning,
        (_, s) => s,
    };
    let status = match (f.status, &f.suppressed) {
        (Status::Fail, None) => String::new(),
        (Status::Fail, Some(why)) => format!("suppressed by [[allow]] ({why}): "),
        (Status::Pass, _) => "passed: ".into(),
        (Status::Unknown, _) => "undecided: ".into(),
    };
    let severity = if f.suppressed.is_some() {
        Severity::Note
    } else {
        severity
    };
    let d = Diagnostic {
        severity,
        code: f.check.clone(),
        message: format!("{status}{}", f.message),
        span: f.span,
        label: None,
        secondary: Vec::new(),
        help: None,
        file: f.location.as_ref().map(|l| l.file.clone()),
    };
    let mut out = if f.status == Status::Pass {
        // Passed checks: one line each.
        match &f.location {
            Some(l) => format!("{l}: {}[{}]: {}{}\n", severity, f.check, status, f.message),
            None => format!("{}[{}]: {}{}\n", severity, f.check, status, f.message),
        }
    } else {
        d.render(map, color)
    };
    if f.status == Status::Fail {
        if let Some(c) = &f.counterexample {
            if f.severity == Severity::Note {
                // No run reaches it: the state is lint's example, not a run's end.
                out.push_str(&format!(
                    "  a state where this holds, which no run reaches: {}\n",
                    c.initial.join(", ")
                ));
            } else {
                out.push_str(&render_counterexample(c));
            }
        }
    }
    out
}

/// A counterexample as a numbered story.
pub fn render_counterexample(c: &Counterexample) -> String {
    let mut out = String::new();
    out.push_str(&format!("  counterexample ({} steps)\n", c.steps.len()));
    out.push_str(&format!("    initially: {}\n", c.initial.join(", ")));
    if !c.requests.is_empty() {
        out.push_str(&format!("    requests:  {}\n", c.requests.join(", ")));
    }
    for (i, s) in c.steps.iter().enumerate() {
        if c.loop_start == Some(i) {
            out.push_str("    -- from here the run repeats forever --\n");
        }
        out.push_str(&render_step(i + 1, s));
    }
    out
}

/// Step `n` of a run, on its line (and its belief changes on the next).
pub fn render_step(n: usize, s: &TraceStep) -> String {
    let kind = match s.kind {
        StepKindTag::Explanation => "explain",
        k => k.name(),
    };
    let mut line = match &s.agent {
        Some(agent) => format!("    {:>3}. {agent}: {kind:<8} {}", n, s.text),
        None => format!("    {:>3}. {kind:<8} {}", n, s.text),
    };
    if let Some(p) = &s.plan {
        line.push_str(&format!("  ({p})"));
    }
    if let Some(n) = s.intention {
        line.push_str(&format!("  [intention {n}]"));
    }
    let changes = s.changes();
    if !changes.is_empty() {
        line.push_str(&format!("\n           beliefs: {}", changes.join(" ")));
    }
    line.push('\n');
    line
}

fn render_stats(s: &Stats, bound: Option<Bound>, verbose: bool) -> String {
    let mut out = format!(
        "explored {} states ({} initial), {} transitions, depth {}, in {:.2}s ({:.0} states/s); fingerprint collision probability {:.1e}\n",
        s.states,
        s.initial_states,
        s.transitions,
        s.depth,
        s.seconds,
        s.states_per_second,
        collision_probability(s.states)
    );
    if verbose && !s.phases.is_empty() {
        let phases: Vec<String> = s
            .phases
            .iter()
            .map(|p| {
                let mut notes: Vec<String> =
                    p.states.iter().map(|n| format!("{n} states")).collect();
                if !p.beside.is_empty() {
                    notes.push(format!("beside {}", p.beside.join(" and ")));
                }
                match notes.is_empty() {
                    true => format!("{} {:.2}s", p.name, p.seconds),
                    false => format!("{} {:.2}s ({})", p.name, p.seconds, notes.join(", ")),
                }
            })
            .collect();
        out.push_str(&format!("phases: {}\n", phases.join(", ")));
    }
    if let Some(n) = s.liveness_states {
        out.push_str(&format!(
            "the checks of runs that go on for ever searched every interleaving again: {n} states\n"
        ));
    }
    if let Some(b) = bound {
        let why = match b {
            Bound::States => "the state bound (`--max-states`, `[bounds] max_states`) was reached",
            Bound::Depth => "the depth bound (`--max-depth`, `[bounds] max_depth`) was reached",
            Bound::Time => "the time limit (`--timeout`) was reached",
            Bound::Memory => "the memory bound (nine tenths of the memory available) was reached",
            Bound::Beyond => "a run leaves the finite model (the warning above says where and why: a belief with a number outside `[bounds] numbers` or a free variable, or a step bdi-check refuses at run time); widen `[bounds] numbers` if it is a number",
            Bound::Initial => "the project has more initial states than `[bounds] max_states` (or 1 GiB of them) allows: the search started from the first ones only; constrain `[initial]`, vary fewer atoms, or raise `[bounds] max_states`",
            Bound::Sampled => "only random runs were followed (`simulate --runs`); run `verify` to explore every state",
        };
        out.push_str(&format!("the search is incomplete: {why}\n"));
    }
    out
}

/// The closing verdict line.
pub fn summary(r: &Report) -> String {
    let failed = r
        .findings
        .iter()
        .filter(|f| f.status == Status::Fail && f.severity == Severity::Error)
        .filter(|f| f.suppressed.is_none())
        .count();
    let allowed = r.findings.iter().filter(|f| f.suppressed.is_some()).count();
    let unknown = r
        .findings
        .iter()
        .filter(|f| f.status == Status::Unknown)
        .count();
    let verdict = match r.verdict {
        Verdict::Pass => "pass",
        Verdict::Fail => "fail",
        Verdict::Incomplete => "incomplete",
        Verdict::Error => "error",
    };
    let mut line = format!(
        "verdict: {verdict} ({} checks, {failed} failed",
        r.findings.len()
    );
    if unknown > 0 {
        line.push_str(&format!(", {unknown} undecided"));
    }
    if allowed > 0 {
        line.push_str(&format!(", {allowed} suppressed"));
    }
    if let Some(s) = &r.stats {
        line.push_str(&format!(", {} states, {:.2}s", s.states, s.seconds));
    }
    line.push_str(")\n");
    line
}

/// Writes each failing finding's counterexample as a scenario file in `dir`; returns the
/// paths written.
pub fn write_scenarios(r: &Report, dir: &Path) -> std::io::Result<Vec<std::path::PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    // Unreached static warnings (notes) describe no real run: they get no scenario.
    for f in r
        .findings
        .iter()
        .filter(|f| f.status == Status::Fail && f.severity != Severity::Note)
    {
        let Some(c) = &f.counterexample else { continue };
        let file: String =
            f.id.chars()
                .map(|ch| {
                    if ch.is_ascii_alphanumeric() || ch == '-' {
                        ch
                    } else {
                        '_'
                    }
                })
                .collect();
        let path = dir.join(format!("{file}.toml"));
        let quote = |v: &[String]| {
            v.iter()
                .map(|s| serde_json::to_string(s).unwrap_or_default())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let text = format!(
            "# {}: {}\n# A run of {} (SPEC §2 scenario): every atom true at the start, and the requests.\ninitial = [{}]\nrequests = [{}]\n",
            f.id,
            f.message.replace('\n', " "),
            r.project,
            quote(&c.initial),
            quote(&c.requests)
        );
        std::fs::write(&path, text)?;
        written.push(path);
    }
    Ok(written)
}
