//! `bdi-check parse`: load files, report every error, and outline what they hold.
//!
//! The human output summarises each file (beliefs, rules, initial goals, plans grouped by
//! trigger); `--format json` gives the outline of every plan (trigger, context and body steps
//! as Jason text, with locations) and the input findings of SPEC §3.

use super::domain::{render_domain, render_project, DomainOutline, ProjectOutline};
use super::Format;
use crate::findings::{Finding, Tool, Verdict};
use crate::syntax::{Diagnostic, Location, SourceMap};
use serde::Serialize;

/// The result of parsing some files: their outlines and every diagnostic.
pub struct ParseRun {
    /// Every file read, so that diagnostics render with excerpts.
    pub map: SourceMap,
    /// Every error met, in file order.
    pub diagnostics: Vec<Diagnostic>,
    /// The JSON-serialisable report.
    pub report: ParseReport,
}

/// The report of `bdi-check parse --format json`.
#[derive(Clone, Debug, Serialize)]
pub struct ParseReport {
    /// The tool.
    pub tool: Tool,
    /// `parse`.
    pub command: &'static str,
    /// `pass` when every file parsed, `error` otherwise.
    pub verdict: Verdict,
    /// One outline per file named on the command line that parsed.
    pub files: Vec<FileReport>,
    /// One `input` finding per error.
    pub findings: Vec<Finding>,
}

/// The outline of one file named on the command line, by kind.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum FileReport {
    /// An AgentSpeak file.
    Agent(FileOutline),
    /// A PDDL domain.
    Domain(DomainOutline),
    /// A manifest: the whole project, grounded.
    Project(ProjectOutline),
}

/// What one agent file (with its includes) holds.
#[derive(Clone, Debug, Serialize)]
pub struct FileOutline {
    /// The file as named on the command line.
    pub file: String,
    /// Files brought in by `include`, in the order met.
    pub includes: Vec<String>,
    /// Initial beliefs.
    pub beliefs: Vec<Entry>,
    /// Rules.
    pub rules: Vec<Entry>,
    /// Initial goals.
    pub initial_goals: Vec<Entry>,
    /// Plans, in source order.
    pub plans: Vec<PlanOutline>,
}

/// A belief, rule or goal as Jason text, with its place.
#[derive(Clone, Debug, Serialize)]
pub struct Entry {
    /// Jason text.
    pub text: String,
    /// Where it is.
    pub location: Location,
}

/// A plan's outline.
#[derive(Clone, Debug, Serialize)]
pub struct PlanOutline {
    /// `@label`, if any.
    pub label: Option<String>,
    /// The trigger, e.g. `+!storeCup(C)`.
    pub trigger: String,
    /// The context, if any.
    pub context: Option<String>,
    /// Each body step as Jason text.
    pub body: Vec<String>,
    /// Where the plan starts.
    pub location: Location,
}

/// The run written in the requested format: `(stdout, stderr)`.
pub fn render(run: &ParseRun, format: Format, color: bool) -> (String, String) {
    match format {
        Format::Json => {
            let json = serde_json::to_string_pretty(&run.report)
                .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
            (json + "\n", String::new())
        }
        Format::Human => (render_summary(&run.report), render_diagnostics(run, color)),
    }
}

/// Every diagnostic with its excerpt, as rustc prints them.
pub fn render_diagnostics(run: &ParseRun, color: bool) -> String {
    super::diagnostics(&run.diagnostics, &run.map, color)
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn render_summary(r: &ParseReport) -> String {
    let mut out = String::new();
    for f in &r.files {
        match f {
            FileReport::Agent(a) => out.push_str(&render_agent(a)),
            FileReport::Domain(d) => out.push_str(&render_domain(d)),
            FileReport::Project(p) => out.push_str(&render_project(p)),
        }
    }
    let errors = r.findings.len();
    out.push_str(&match errors {
        0 => format!(
            "parsed {}: no errors\n",
            plural(r.files.len(), "file", "files")
        ),
        n => format!("{}: the input is malformed\n", plural(n, "error", "errors")),
    });
    out
}

/// Human text for one agent file.
fn render_agent(f: &FileOutline) -> String {
    let mut out = String::new();
    // Plans grouped by trigger, in order of first appearance (an index per trigger keeps a
    // library of many triggers linear).
    let mut triggers: Vec<(&str, Vec<&PlanOutline>)> = Vec::new();
    let mut index: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for p in &f.plans {
        match index.get(p.trigger.as_str()) {
            Some(&i) => triggers[i].1.push(p),
            None => {
                index.insert(&p.trigger, triggers.len());
                triggers.push((&p.trigger, vec![p]));
            }
        }
    }
    out.push_str(&format!(
        "{}: {}, {}, {}, {} for {}\n",
        f.file,
        plural(f.beliefs.len(), "belief", "beliefs"),
        plural(f.rules.len(), "rule", "rules"),
        plural(f.initial_goals.len(), "initial goal", "initial goals"),
        plural(f.plans.len(), "plan", "plans"),
        plural(triggers.len(), "trigger", "triggers"),
    ));
    if !f.includes.is_empty() {
        out.push_str(&format!("  includes       {}\n", f.includes.join(", ")));
    }
    let list = |entries: &[Entry]| {
        entries
            .iter()
            .map(|e| e.text.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    if !f.beliefs.is_empty() {
        out.push_str(&format!("  beliefs        {}\n", list(&f.beliefs)));
    }
    for r in &f.rules {
        out.push_str(&format!("  rule           {}\n", r.text));
    }
    if !f.initial_goals.is_empty() {
        out.push_str(&format!("  initial goals  {}\n", list(&f.initial_goals)));
    }
    if !triggers.is_empty() {
        out.push_str("  plans by trigger\n");
        let width = triggers.iter().map(|(t, _)| t.len()).max().unwrap_or(0);
        for (t, plans) in &triggers {
            let places: Vec<String> = plans
                .iter()
                .map(|p| format!("{}:{}", p.location.file, p.location.line))
                .collect();
            out.push_str(&format!(
                "    {t:width$}  {}  {}\n",
                plural(plans.len(), "plan ", "plans"),
                places.join(", ")
            ));
        }
    }
    out
}
