//! `bdi-check lint`: the static checks' report, for people (rustc-style diagnostics with
//! the plan's source and the state that shows the problem) and for machines (SPEC §3 JSON).

use super::verify::Detail;
use super::Format;
use crate::findings::{Report, Status, Verdict};
use crate::smt::LintFinding;
use crate::syntax::{Diagnostic, Severity, SourceMap};

/// The outcome of `lint` on one project.
pub struct LintRun {
    /// The report (verdict and every finding, passed ones too).
    pub report: Report,
    /// The files read, for excerpts.
    pub map: SourceMap,
    /// Input errors, when the project did not load.
    pub diagnostics: Vec<Diagnostic>,
    /// The findings with their labels, in report order.
    pub findings: Vec<LintFinding>,
    /// The goal-plan tree, for the HTML page (empty when the project did not load).
    pub tree: super::html::PlanTree,
}

/// The run in the requested format: `(stdout, stderr)`. Input errors go to stderr in human
/// format and are `input` findings in JSON.
pub fn render(run: &LintRun, format: Format, detail: Detail, color: bool) -> (String, String) {
    match format {
        Format::Json => (
            serde_json::to_string_pretty(&run.report)
                .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
                + "\n",
            String::new(),
        ),
        Format::Human => {
            let err = super::diagnostics(&run.diagnostics, &run.map, color);
            (render_human(run, detail, color), err)
        }
    }
}

/// Failing and undecided findings as diagnostics with the source excerpt and the state,
/// passed ones as one line each with `-v`, then the summary line.
pub fn render_human(run: &LintRun, detail: Detail, color: bool) -> String {
    let mut out = String::new();
    if detail != Detail::Quiet {
        let verbose = detail == Detail::Verbose;
        let mut shown: Vec<&LintFinding> = run
            .findings
            .iter()
            .filter(|f| verbose || super::verify::rank(&f.finding) < 2)
            .collect();
        // Errors first, then warnings; notes and passes only with `-v`.
        shown.sort_by_key(|f| super::verify::rank(&f.finding));
        for f in shown {
            match f.finding.status {
                Status::Pass if detail == Detail::Verbose => {
                    let p = &f.finding;
                    match &p.location {
                        Some(l) => {
                            out.push_str(&format!("{l}: passed[{}]: {}\n", p.check, p.message))
                        }
                        None => out.push_str(&format!("passed[{}]: {}\n", p.check, p.message)),
                    }
                }
                Status::Pass => {}
                _ => {
                    out.push_str(&render_finding(f, &run.map, color));
                    out.push('\n');
                }
            }
        }
        if !verbose {
            let hidden = run
                .findings
                .iter()
                .map(|f| &f.finding)
                .filter(|f| super::verify::rank(f) == 2);
            out.push_str(&super::verify::hidden_notes(hidden));
        }
        for w in &run.report.warnings {
            out.push_str(&format!("warning: {w}\n"));
        }
    }
    out.push_str(&super::verify::paint_verdict(
        &summary(&run.report),
        run.report.verdict,
        color,
    ));
    out
}

/// One finding as rustc prints a diagnostic, with its counterexample state under it.
pub fn render_finding(f: &LintFinding, map: &SourceMap, color: bool) -> String {
    let p = &f.finding;
    let prefix = match (&p.suppressed, p.status) {
        (Some(why), _) => format!("suppressed by [[allow]] ({why}): "),
        (None, Status::Unknown) => "undecided: ".into(),
        (None, _) => String::new(),
    };
    let d = Diagnostic {
        severity: if p.suppressed.is_some() {
            Severity::Note
        } else {
            p.severity
        },
        code: p.check.clone(),
        message: format!("{prefix}{}", p.message),
        span: p.span,
        label: (!f.label.is_empty()).then(|| f.label.clone()),
        secondary: f
            .secondary
            .iter()
            .map(|(span, text)| crate::syntax::diagnostic::Label {
                span: *span,
                text: text.clone(),
            })
            .collect(),
        help: None,
        file: p.location.as_ref().map(|l| l.file.clone()),
    };
    let mut out = d.render(map, color);
    if let Some(c) = &p.counterexample {
        out.push_str(&format!("  state: {}\n", c.initial.join(", ")));
        if !c.requests.is_empty() {
            out.push_str(&format!("  request: {}\n", c.requests.join(", ")));
        }
    }
    out
}

/// The closing line: counts by severity, checks passed, and the verdict.
pub fn summary(r: &Report) -> String {
    let count = |s: Severity| {
        r.findings
            .iter()
            .filter(|f| f.status == Status::Fail && f.severity == s && f.suppressed.is_none())
            .count()
    };
    let allowed = r.findings.iter().filter(|f| f.suppressed.is_some()).count();
    let plural =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    let undecided = r
        .findings
        .iter()
        .filter(|f| f.status == Status::Unknown)
        .count();
    let passed = r
        .findings
        .iter()
        .filter(|f| f.status == Status::Pass)
        .count();
    if r.verdict == Verdict::Error {
        let n = r.findings.iter().filter(|f| f.check == "input").count();
        return format!(
            "lint {}: {}: the input is malformed\n",
            r.project,
            plural(n, "error", "errors")
        );
    }
    let verdict = match r.verdict {
        Verdict::Pass => "pass",
        Verdict::Fail => "fail",
        Verdict::Incomplete => "incomplete",
        Verdict::Error => "error",
    };
    let allowed = if allowed > 0 {
        format!(", {allowed} suppressed")
    } else {
        String::new()
    };
    format!(
        "lint {}: {}, {}, {}, {} undecided{allowed}; {} passed: {verdict}\n",
        r.project,
        plural(count(Severity::Error), "error", "errors"),
        plural(count(Severity::Warning), "warning", "warnings"),
        plural(count(Severity::Note), "note", "notes"),
        undecided,
        plural(passed, "check", "checks"),
    )
}
