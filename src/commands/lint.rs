//! `bdi-check lint`: load a project and run the static checks (rendered by
//! [`crate::report::lint`]).

use super::{Output, Style};
use crate::findings::{Report, Status};
use crate::model::project::{load_system, Project};
use crate::report::lint::{render, LintRun};
use crate::smt::{lint, LintFinding, LintOptions};
use crate::syntax::{Diagnostic, Severity, SourceMap};
use std::path::Path;

/// `lint PROJECT [--deny warnings]`.
pub fn command(project: &Path, deny_warnings: bool, style: &Style) -> Output {
    let run = run(project, &LintOptions::default(), deny_warnings);
    let (text, stderr) = match style.ci {
        _ if style.html && run.diagnostics.is_empty() => (
            crate::report::html::render(&run.report, &run.tree, "lint"),
            String::new(),
        ),
        Some(ci) => (ci.render(&run.report, "lint"), String::new()),
        None => render(&run, style.format, style.detail, style.color),
    };
    Output {
        report: Some(text),
        stderr,
        code: run.report.verdict.exit_code(),
    }
}

/// Loads and lints a project. With `deny_warnings`, a failing warning is an error (and
/// fails the verdict), as with rustc's `-D warnings`.
pub fn run(path: &Path, opts: &LintOptions, deny_warnings: bool) -> LintRun {
    let name = path.display().to_string();
    let projects = match load_system(path) {
        Ok(p) => p,
        Err(e) => return input_failure(name, e.map, e.diagnostics),
    };
    let mut findings = lint_agents(&projects, opts);
    let project = projects.into_iter().next().expect("an agent");
    let bad = super::allow::check(&project);
    if !bad.is_empty() {
        return input_failure(name, project.map, bad);
    }
    let unused = super::allow::apply(
        &project,
        findings.iter_mut().map(|f| &mut f.finding),
        |check| crate::smt::lint::CHECKS.contains(&check),
    );
    if deny_warnings {
        for f in &mut findings {
            if f.finding.severity == Severity::Warning && f.finding.status == Status::Fail {
                f.finding.severity = Severity::Error;
            }
        }
    }
    let mut report = Report::new(name, findings.iter().map(|f| f.finding.clone()).collect());
    report.warnings = unused;
    report.sources = crate::findings::sources_of(&project.map);
    LintRun {
        report,
        tree: crate::report::html::PlanTree::of(&project),
        map: project.map,
        diagnostics: Vec::new(),
        findings,
    }
}

/// The run of a project that is bad input: its diagnostics as `input` findings.
fn input_failure(name: String, map: SourceMap, diagnostics: Vec<Diagnostic>) -> LintRun {
    let report = super::input_report(name, &map, &diagnostics);
    LintRun {
        report,
        map,
        diagnostics,
        findings: Vec::new(),
        tree: Default::default(),
    }
}

/// Lints every agent's plan library (each file once, instances share it). The domain's
/// checks are the same for every agent and reported once; an action is unused only when
/// no agent calls it.
pub fn lint_agents(projects: &[Project], opts: &LintOptions) -> Vec<LintFinding> {
    let mut out: Vec<LintFinding> = Vec::new();
    let mut linted = Vec::new();
    for p in projects {
        if linted.contains(&&p.manifest.agent.plans.path) {
            continue;
        }
        linted.push(&p.manifest.agent.plans.path);
        // An invariant that names an agent's beliefs is not one lint can read of a plan
        // library alone: `verify` checks it.
        let n = crate::model::formula::agent_stride(&p.atoms) as u32;
        let of_agents = |c: &crate::model::cond::Cond| c.atoms().iter().any(|a| a.0 >= n);
        let filtered;
        let p = if p.invariants.iter().any(|(_, c)| of_agents(c)) {
            let mut q = p.clone();
            q.invariants.retain(|(_, c)| !of_agents(c));
            filtered = q;
            &filtered
        } else {
            p
        };
        for l in lint(p, opts) {
            let f = &l.finding;
            match out
                .iter_mut()
                .find(|g| g.finding.id == f.id && g.finding.check == f.check)
            {
                Some(g) if g.finding.check == "unused-action" && f.status == Status::Pass => *g = l,
                Some(_) => {}
                None => out.push(l),
            }
        }
    }
    out
}
