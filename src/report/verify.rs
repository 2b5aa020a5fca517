//! `bdi-check verify`: the report of the model checker, for people (counterexamples told
//! as numbered stories) and for machines (SPEC §3 JSON), and scenario files.

use super::{Counterexample, Finding, Report, Stats, Status, StepKindTag, Verdict};
use crate::check::explore::{Bound, Limits};
use crate::check::{verify_with, VerifyOptions};
use crate::model::project::{load_project, Project};
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
}

/// The limits of a project's search: the manifest's `[bounds]`, overridden by options.
pub fn limits(
    project: &Project,
    max_states: Option<u64>,
    max_depth: Option<u64>,
    timeout: Option<f64>,
) -> Limits {
    Limits {
        max_states: max_states.unwrap_or(project.manifest.bounds.max_states),
        max_depth: max_depth.unwrap_or(project.manifest.bounds.max_depth),
        timeout,
    }
}

/// Loads and verifies a project with the default [`VerifyOptions`].
pub fn run(
    path: &Path,
    max_states: Option<u64>,
    max_depth: Option<u64>,
    timeout: Option<f64>,
    progress: impl FnMut(usize, u32, f64),
) -> VerifyRun {
    let opts = VerifyOptions::default();
    run_with(path, max_states, max_depth, timeout, &opts, progress)
}

/// Loads and verifies a project.
pub fn run_with(
    path: &Path,
    max_states: Option<u64>,
    max_depth: Option<u64>,
    timeout: Option<f64>,
    opts: &VerifyOptions,
    progress: impl FnMut(usize, u32, f64),
) -> VerifyRun {
    let name = path.display().to_string();
    let project = match load_project(path) {
        Ok(p) => p,
        Err(e) => return input_failure(name, e.map, e.diagnostics),
    };
    let lim = limits(&project, max_states, max_depth, timeout);
    // SPEC §2: verify runs lint first; its warnings are settled by the exploration.
    let lint: Vec<Finding> = crate::smt::lint(&project, &crate::smt::LintOptions::default())
        .into_iter()
        .map(|l| l.finding)
        .collect();
    match verify_with(&project, lim, opts, progress, &lint) {
        Err(diagnostics) => input_failure(name, project.map, diagnostics),
        Ok(v) => {
            let mut report = Report::new(name, v.findings);
            if report.verdict == Verdict::Pass && !v.stats.complete {
                report.verdict = Verdict::Incomplete;
            }
            report.stats = Some(v.stats);
            report.warnings.extend(v.symmetry_caveat.map(|r| format!("symmetry reduction treats the objects as interchangeable, but renaming {r} changes what the agent does in a reachable state (Jason perceives the effects of one action in an order that depends on the names): a run of a merged state may have been left out; `--no-symmetry` gives the exact verdict")));
            VerifyRun {
                report,
                map: project.map,
                diagnostics: Vec::new(),
                bound: v.bound,
            }
        }
    }
}

fn input_failure(name: String, map: SourceMap, diagnostics: Vec<Diagnostic>) -> VerifyRun {
    let findings: Vec<Finding> = diagnostics
        .iter()
        .map(|d| Finding::from_input_diagnostic(d, &map))
        .collect();
    let mut report = Report::new(name, findings);
    report.verdict = Verdict::Error;
    VerifyRun {
        report,
        map,
        diagnostics,
        bound: None,
    }
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
    if detail != Detail::Quiet {
        for d in &run.diagnostics {
            out.push_str(&d.render(&run.map, color));
            out.push('\n');
        }
        if run.diagnostics.is_empty() {
            for f in &r.findings {
                let shown = f.status != Status::Pass || detail == Detail::Verbose;
                if !shown {
                    continue;
                }
                out.push_str(&render_finding(f, &run.map, color));
                out.push('\n');
            }
        }
        if let Some(s) = &r.stats {
            for w in &r.warnings {
                out.push_str(&format!("warning: {w}\n"));
            }
            out.push_str(&render_stats(s, run.bound));
        }
    }
    out.push_str(&summary(r));
    out
}

fn render_finding(f: &Finding, map: &SourceMap, color: bool) -> String {
    // An undecided check is not a failure: it reads as a warning, never as an error.
    let severity = match (f.status, f.severity) {
        (Status::Pass, _) => Severity::Note,
        (Status::Unknown, Severity::Error) => Severity::Warning,
        (_, s) => s,
    };
    let status = match f.status {
        Status::Fail => "",
        Status::Pass => "passed: ",
        Status::Unknown => "undecided: ",
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
            out.push_str(&render_counterexample(c));
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
        let kind = match s.kind {
            StepKindTag::Request => "request",
            StepKindTag::Event => "event",
            StepKindTag::Plan => "plan",
            StepKindTag::Action => "action",
            StepKindTag::Belief => "belief",
            StepKindTag::Internal => "internal",
            StepKindTag::Explanation => "explain",
        };
        let mut line = format!("    {:>3}. {kind:<8} {}", i + 1, s.text);
        if let Some(p) = &s.plan {
            line.push_str(&format!("  ({p})"));
        }
        if let Some(n) = s.intention {
            line.push_str(&format!("  [intention {n}]"));
        }
        let changes: Vec<String> = s
            .added
            .iter()
            .map(|a| format!("+{a}"))
            .chain(s.removed.iter().map(|a| format!("-{a}")))
            .collect();
        if !changes.is_empty() {
            line.push_str(&format!("\n           beliefs: {}", changes.join(" ")));
        }
        out.push_str(&line);
        out.push('\n');
    }
    out
}

fn render_stats(s: &Stats, bound: Option<Bound>) -> String {
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
    if let Some(b) = bound {
        let why = match b {
            Bound::States => "the state bound (`--max-states`, `[bounds] max_states`) was reached",
            Bound::Depth => "the depth bound (`--max-depth`, `[bounds] max_depth`) was reached",
            Bound::Time => "the time limit (`--timeout`) was reached",
            Bound::Memory => "the memory bound (nine tenths of the memory available) was reached",
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
        .count();
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

/// Merges the JSON reports of the shards of one project (`verify --shard K/N`) into one
/// report, as a JSON value. Every check holds on all runs only if it holds in every shard,
/// and is reached if some shard reaches it; per finding id:
///
/// * a passing finding with a run (a `reachable` witness) in some shard wins;
/// * else a failing one with a run (a violation, or a lint warning some run reaches): of
///   those, the one with the shortest run, then the first report given;
/// * else the findings agree up to their counts: a failing one wins, then an undecided one,
///   then the first;
/// * a `<check>:all` finding (no place fails the check) goes when a shard found a place
///   that fails it, and so does an explanation property's `<check>:<user>` finding when a
///   shard found a place (`<check>:<user>:<file>:<line>`) where it fails for that user.
///
/// Statistics add up (states reached by several shards count once per shard), the depth
/// and seconds are the largest, and the search is complete when every shard's was. Fails
/// with a message when a report cannot be read or the reports are of different projects.
pub fn merge(reports: &[serde_json::Value]) -> Result<serde_json::Value, String> {
    use serde_json::{json, Value};
    let Some(first) = reports.first() else {
        return Err("merge needs at least one report".into());
    };
    let project = first.get("project").cloned().unwrap_or(Value::Null);
    let mut order: Vec<String> = Vec::new();
    let mut by_id: std::collections::HashMap<String, Vec<&Value>> = Default::default();
    let (mut initial, mut states, mut transitions) = (0u64, 0u64, 0u64);
    let (mut depth, mut seconds, mut complete) = (0u64, 0f64, true);
    for (n, r) in reports.iter().enumerate() {
        let findings = r
            .get("findings")
            .and_then(Value::as_array)
            .ok_or_else(|| format!("report {} has no `findings` array", n + 1))?;
        if r.get("project") != Some(&project) {
            return Err(format!(
                "report {} is of project {}, report 1 of {}: merge the shards of one project",
                n + 1,
                r.get("project").unwrap_or(&Value::Null),
                project
            ));
        }
        for f in findings {
            let id = f
                .get("id")
                .and_then(Value::as_str)
                .ok_or_else(|| format!("a finding of report {} has no `id`", n + 1))?;
            if !by_id.contains_key(id) {
                order.push(id.to_string());
            }
            by_id.entry(id.to_string()).or_default().push(f);
        }
        if let Some(st) = r.get("stats") {
            let num = |k: &str| st.get(k).and_then(Value::as_u64).unwrap_or(0);
            initial += num("initial_states");
            states += num("states");
            transitions += num("transitions");
            depth = depth.max(num("depth"));
            seconds = seconds.max(st.get("seconds").and_then(Value::as_f64).unwrap_or(0.0));
            complete &= st.get("complete").and_then(Value::as_bool).unwrap_or(false);
        } else {
            complete = false;
        }
    }
    let status = |f: &Value| {
        f.get("status")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string()
    };
    let run_len = |f: &Value| {
        f.get("counterexample")
            .and_then(|c| c.get("steps"))
            .and_then(Value::as_array)
            .map(|s| s.len())
    };
    // A lint warning one shard settles as reached (an error) beats the same warning
    // another shard settles as unreached (a note).
    let rank = |f: &Value| match f.get("severity").and_then(Value::as_str) {
        Some("error") => 0,
        Some("warning") => 1,
        _ => 2,
    };
    let mut findings = Vec::new();
    for id in &order {
        let all = &by_id[id];
        let with_run = |st: &str| {
            all.iter()
                .filter(|f| status(f) == st && run_len(f).is_some())
                .min_by_key(|f| (rank(f), run_len(f)))
                .copied()
        };
        let chosen = with_run("pass")
            .or_else(|| with_run("fail"))
            .or_else(|| all.iter().find(|f| status(f) == "fail").copied())
            .or_else(|| all.iter().find(|f| status(f) == "unknown").copied())
            .unwrap_or(all[0]);
        findings.push(chosen.clone());
    }
    // `<check>:all` says that no place failed the check: not so when a shard found one.
    let check_of = |f: &Value| {
        f.get("check")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string()
    };
    let failing: std::collections::HashSet<String> = findings
        .iter()
        .filter(|f| status(f) == "fail")
        .map(check_of)
        .collect();
    let failing_ids: Vec<String> = findings
        .iter()
        .filter(|f| status(f) == "fail")
        .filter_map(|f| f.get("id").and_then(Value::as_str).map(str::to_string))
        .collect();
    findings.retain(|f| {
        let id = f.get("id").and_then(Value::as_str).unwrap_or("");
        let prefix = format!("{id}:");
        status(f) == "fail"
            || !((id.ends_with(":all") && failing.contains(&check_of(f)))
                || failing_ids.iter().any(|x| x.starts_with(&prefix)))
    });
    let failed = |f: &Value, check: Option<&str>| {
        f.get("severity").and_then(Value::as_str) == Some("error")
            && status(f) == "fail"
            && check.is_none_or(|c| f.get("check").and_then(Value::as_str) == Some(c))
    };
    let verdict = if findings.iter().any(|f| failed(f, Some("input"))) {
        "error"
    } else if findings.iter().any(|f| failed(f, None)) {
        "fail"
    } else if !complete || findings.iter().any(|f| status(f) == "unknown") {
        "incomplete"
    } else {
        "pass"
    };
    let mut warnings: Vec<Value> = Vec::new();
    for w in reports
        .iter()
        .filter_map(|r| r.get("warnings")?.as_array())
        .flatten()
    {
        if !warnings.contains(w) {
            warnings.push(w.clone());
        }
    }
    let mut out = first.clone();
    out["verdict"] = json!(verdict);
    out["findings"] = Value::Array(findings);
    if let Some(o) = out.as_object_mut() {
        o.remove("warnings");
        if !warnings.is_empty() {
            o.insert("warnings".into(), Value::Array(warnings));
        }
    }
    out["stats"] = json!({
        "initial_states": initial,
        "states": states,
        "transitions": transitions,
        "depth": depth,
        "seconds": seconds,
        "states_per_second": if seconds > 0.0 { states as f64 / seconds } else { 0.0 },
        "complete": complete,
    });
    Ok(out)
}
