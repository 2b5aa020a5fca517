//! `bdi-check explain PROJECT --scenario FILE [--user NAME]`: one run of the robot, told step
//! by step, with the explanation each user gets in place.
//!
//! The run is the scenario's initial state and requests (SPEC §2), executed with the
//! project's semantics: a request arrives as soon as the manifest's `arrival` allows, and
//! the reasoning cycle runs otherwise. At each executed environment action, Algorithm 1
//! decides, per user, whether the action surprises them ([`crate::explain::demand`]); when it
//! does, Algorithm 2 builds the explanation from the running intention's stack
//! ([`crate::explain::content()`]) and it is rendered as one sentence. Each user's view of the
//! run is [`Explained`](crate::check::explanation::Explained), the model whose explanations `verify` checks: what `explain` prints
//! is what was verified.

use crate::findings::{Report, TraceStep};
use crate::syntax::{Diagnostic, SourceMap};
use serde::Serialize;

/// A scenario's run, as `explain` reports it (SPEC §3 `trace`).
#[derive(Clone, Debug, Serialize)]
pub struct Trace {
    /// Every atom true at the start.
    pub initial: Vec<String>,
    /// The requests, in order.
    pub requests: Vec<String>,
    /// The run, explanations in place.
    pub steps: Vec<TraceStep>,
    /// `done`, `action-failure`, `goal-failure`, `livelock` or `bound`.
    pub outcome: &'static str,
}

/// One explanation given (SPEC §3 `explanations`).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Given {
    /// The user it is for.
    pub user: String,
    /// The surprising action.
    pub action: String,
    /// What the user saw just before (`!g` for a request), if anything.
    pub after: Option<String>,
    /// The hierarchical context `Γ`.
    pub context: Vec<String>,
    /// The actions up to the one that changes the context.
    pub actions: Vec<String>,
    /// The sentence.
    pub text: String,
}

/// The outcome of `explain --scenario`.
pub struct ExplainRun {
    /// The report (findings empty; `explanations` filled).
    pub report: Report,
    /// The run.
    pub trace: Option<Trace>,
    /// The explanations, in order.
    pub given: Vec<Given>,
    /// Files read, for diagnostics.
    pub map: SourceMap,
    /// Input errors.
    pub diagnostics: Vec<Diagnostic>,
    /// The goal-plan tree, for the HTML page (empty when the project did not load).
    pub tree: super::html::PlanTree,
}

/// The run as one HTML page, its explanations in place.
pub fn render_html(run: &ExplainRun) -> String {
    let Some(t) = &run.trace else {
        return String::new();
    };
    let c = crate::findings::Counterexample {
        initial: t.initial.clone(),
        requests: t.requests.clone(),
        steps: t.steps.clone(),
        loop_start: None,
    };
    super::html::render_explain(&run.report, &c, t.outcome, &run.tree)
}

/// The run as a numbered story with the explanations in place.
pub fn render_human(run: &ExplainRun, color: bool) -> String {
    let mut out = super::diagnostics(&run.diagnostics, &run.map, color);
    let Some(t) = &run.trace else { return out };
    let c = crate::findings::Counterexample {
        initial: t.initial.clone(),
        requests: t.requests.clone(),
        steps: t.steps.clone(),
        loop_start: None,
    };
    out.push_str(&crate::report::verify::render_counterexample(&c).replacen(
        "counterexample",
        "run",
        1,
    ));
    out.push_str(&format!(
        "outcome: {}; {} explanation{} given\n",
        t.outcome,
        run.given.len(),
        if run.given.len() == 1 { "" } else { "s" }
    ));
    out
}

/// The JSON report: SPEC §3's shape with `trace` and `explanations`.
pub fn render_json(run: &ExplainRun) -> String {
    let mut v = serde_json::to_value(&run.report).unwrap_or_default();
    if let (Some(obj), Some(t)) = (v.as_object_mut(), &run.trace) {
        obj.insert("trace".into(), serde_json::to_value(t).unwrap_or_default());
        obj.insert(
            "explanations".into(),
            serde_json::to_value(&run.given).unwrap_or_default(),
        );
    }
    serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"
}

/// The explanations every scenario gives, and a note when runs were left out.
pub struct Catalogue {
    /// Distinct explanations, per user, each with a scenario.
    pub entries: Vec<Entry>,
    /// What the catalogue does not cover, if anything.
    pub note: Option<String>,
    /// Files read.
    pub map: SourceMap,
}

/// Why a project could not be explained: the files read and the errors.
pub type LoadFailure = (SourceMap, Vec<Diagnostic>);

/// One entry of the catalogue: an explanation and a scenario that produces it.
#[derive(Clone, Debug, Serialize)]
pub struct Entry {
    /// The explanation.
    #[serde(flatten)]
    pub given: Given,
    /// A scenario (initial atoms and requests) whose run gives it.
    pub scenario: Scenario,
}

/// A scenario, as `--scenario` files hold it.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Scenario {
    /// Every atom true at the start.
    pub initial: Vec<String>,
    /// The requests, in order.
    pub requests: Vec<String>,
}

/// The catalogue for people: per user, each sentence with the action and a scenario
/// that gives it, as the lines of a scenario file (TOML, ready to paste). `quiet`: the
/// count per user only.
pub fn render_catalogue(entries: &[Entry], note: Option<&str>, quiet: bool) -> String {
    let mut out = String::new();
    let mut user = "";
    let toml = |v: &[String]| {
        v.iter()
            .map(|s| serde_json::to_string(s).unwrap_or_default())
            .collect::<Vec<_>>()
            .join(", ")
    };
    for e in entries {
        if e.given.user != user {
            user = &e.given.user;
            let count = entries.iter().filter(|x| x.given.user == user).count();
            out.push_str(&format!(
                "{user}: {count} distinct explanation{}\n",
                if count == 1 { "" } else { "s" }
            ));
        }
        if quiet {
            continue;
        }
        out.push_str(&format!(
            "  {} (after {})\n    \"{}\"\n    scenario:\n      initial = [{}]\n      requests = [{}]\n",
            e.given.action,
            e.given.after.as_deref().unwrap_or("the start"),
            e.given.text,
            toml(&e.scenario.initial),
            toml(&e.scenario.requests)
        ));
    }
    if let Some(n) = note {
        out.push_str(&format!("note: {n}\n"));
    }
    out
}
