//! `bdi-check explain`: run one scenario with the explanations each user gets, or list
//! every distinct explanation the runs give (rendered by [`crate::report::explain`]).

use super::{Output, Style};
use crate::check::explanation::{Explained, ExplainedState, Step};
use crate::check::explore::fingerprint;
use crate::check::model::Model;
use crate::check::run::resolve_scenario;
use crate::check::trace::Builder;
use crate::explain::agent::{self, Explainer, User};
use crate::findings::{Finding, Report, StepKindTag, Tool, TraceStep};
use crate::model::atoms::AtomSet;
use crate::model::project::{load_project, Project};
use crate::report::explain::{
    render_catalogue, render_html, render_human, render_json, Catalogue, Entry, ExplainRun, Given,
    LoadFailure, Scenario, Trace,
};
use crate::report::Format;
use crate::semantics::{Note, Semantics, State};
use crate::syntax::manifest::load_scenario;
use crate::syntax::{Diagnostic, SourceMap};
use std::collections::HashSet;
use std::path::Path;

/// `explain PROJECT [--scenario FILE] [--user U]`.
pub fn command(
    project: &Path,
    scenario: Option<&Path>,
    user: Option<&str>,
    style: &Style,
) -> Output {
    if let Some(refused) = style.ci.and_then(|_| style.refuse_ci_format("explain")) {
        return refused;
    }
    let Some(sc) = scenario else {
        if let Some(refused) = style.refuse_html("explain without --scenario") {
            return refused;
        }
        return match catalogue(project, user) {
            Ok(Catalogue { entries, note, .. }) => {
                let text = match style.format {
                    Format::Json => {
                        let v = serde_json::json!({
                            "tool": Tool::default(),
                            "project": project.display().to_string(),
                            "verdict": "pass",
                            "findings": [],
                            "explanations": entries,
                            "note": note,
                        });
                        serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"
                    }
                    Format::Human => render_catalogue(
                        &entries,
                        note.as_deref(),
                        style.detail == crate::report::verify::Detail::Quiet,
                    ),
                };
                Output::report(text, 0)
            }
            Err((map, errs)) => {
                Output::refused(crate::report::diagnostics(&errs, &map, style.stderr_color))
            }
        };
    };
    let run = run(project, sc, user);
    if !run.diagnostics.is_empty() {
        if style.format == Format::Json {
            let findings: Vec<_> = run
                .diagnostics
                .iter()
                .map(|d| Finding::from_input_diagnostic(d, &run.map))
                .collect();
            let r = Report::new(project.display().to_string(), findings);
            return Output::report(
                serde_json::to_string_pretty(&r).unwrap_or_default() + "\n",
                2,
            );
        }
        return Output::refused(render_human(&run, style.stderr_color));
    }
    let text = match style.format {
        _ if style.html => render_html(&run),
        Format::Json => render_json(&run),
        Format::Human => render_human(&run, style.color),
    };
    Output {
        report: Some(text),
        stderr: run
            .report
            .warnings
            .iter()
            .map(|w| format!("warning: {w}\n"))
            .collect(),
        code: 0,
    }
}

/// Runs a scenario of a project and explains it for every user (or only `only`).
pub fn run(project: &Path, scenario: &Path, only: Option<&str>) -> ExplainRun {
    let name = project.display().to_string();
    let fail = |map: SourceMap, diagnostics: Vec<Diagnostic>| ExplainRun {
        report: Report::new(name.clone(), Vec::new()),
        trace: None,
        given: Vec::new(),
        map,
        diagnostics,
        tree: Default::default(),
    };
    let mut p = match load_project(project) {
        Ok(p) => p,
        Err(e) => return fail(e.map, e.diagnostics),
    };
    let sc = match load_scenario(scenario, &mut p.map) {
        Ok(s) => s,
        Err(d) => return fail(p.map, d),
    };
    let sem = match Semantics::new(&p) {
        Ok(s) => s,
        Err(d) => return fail(p.map.clone(), d),
    };
    let (beliefs, requests, mut errors) = match resolve_scenario(&p, &sem, &sc) {
        Ok((b, r)) => (b, r, Vec::new()),
        Err(d) => (AtomSet::empty(p.atoms.len()), Vec::new(), d),
    };
    let users = match agent::users(&p, only) {
        Ok(u) => u,
        Err(d) => {
            errors.extend(d);
            Vec::new()
        }
    };
    if !errors.is_empty() {
        return fail(p.map.clone(), errors);
    }
    let (trace, given) = execute(&p, &sem, &beliefs, &requests, &users);
    let mut report = Report::new(name.clone(), Vec::new());
    let max = p.manifest.requests.max as usize;
    if requests.len() > max {
        report.warnings.push(format!(
            "the scenario makes {} requests, more than `[requests] max` ({max}): `verify` does not cover this run",
            requests.len()
        ));
    }
    report.explanations = given
        .iter()
        .map(|g| serde_json::to_value(g).unwrap_or_default())
        .collect();
    ExplainRun {
        report,
        trace: Some(trace),
        given,
        map: p.map.clone(),
        diagnostics: Vec::new(),
        tree: crate::report::html::PlanTree::of(&p),
    }
}

fn execute(
    p: &Project,
    sem: &Semantics,
    beliefs: &AtomSet,
    requests: &[u8],
    users: &[User],
) -> (Trace, Vec<Given>) {
    let ex = Explainer::new(p, sem);
    // Each user's view of the run is the model whose explanations `verify` checks.
    let models: Vec<Explained> = users
        .iter()
        .map(|u| Explained::new(sem, &ex, u, None))
        .collect();
    let mut state: State = sem.initial_state(beliefs);
    let mut views: Vec<ExplainedState> = models.iter().map(|m| m.start(state.clone())).collect();
    let mut builder = Builder::new(p, sem);
    let mut steps: Vec<TraceStep> = Vec::new();
    let mut given = Vec::new();
    let mut next_request = 0usize;
    let mut seen = HashSet::from([fingerprint(&state)]);
    let mut outcome = "bound";
    for _ in 0..p.manifest.bounds.max_depth {
        let succ = sem.successors(&state);
        let request = requests.get(next_request).and_then(|r| {
            succ.iter().position(
                |t| matches!(t.notes.first(), Some(Note::Request { index }) if index == r),
            )
        });
        let pick = request.or_else(|| {
            succ.iter()
                .position(|t| !matches!(t.notes.first(), Some(Note::Request { .. })))
        });
        let Some(k) = pick else {
            outcome = "done";
            break;
        };
        if request.is_some() {
            next_request += 1;
        }
        // The same transition as each user sees it (successors come in the agent's order).
        let seen_by: Vec<Step> = models
            .iter()
            .zip(&mut views)
            .map(|(m, v)| {
                let (step, next) = m.next_states(v).swap_remove(k);
                *v = next;
                step
            })
            .collect();
        let t = &succ[k];
        for (i, note) in t.notes.iter().enumerate() {
            for (u, step) in users.iter().zip(&seen_by) {
                let Some(g) = step.given_at(i) else { continue };
                let text = g.text(&ex);
                steps.push(TraceStep {
                    kind: StepKindTag::Explanation,
                    text: format!("to {}: {text}", u.name),
                    intention: None,
                    plan: None,
                    added: Vec::new(),
                    removed: Vec::new(),
                    explanation: Some(text.clone()),
                    agent: None,
                });
                given.push(Given {
                    user: u.name.clone(),
                    action: g.action.to_string(),
                    after: g.after.as_ref().map(|o| o.to_string()),
                    context: g.content.context.iter().map(|l| l.to_string()).collect(),
                    actions: g.content.actions.iter().map(|a| a.to_string()).collect(),
                    text,
                });
            }
            match note {
                Note::ActionFailed { .. } => outcome = "action-failure",
                Note::GoalFailed { .. } => outcome = "goal-failure",
                _ => {}
            }
            let before = builder.steps().len();
            builder.push(vec![note.clone()]);
            steps.extend(builder.steps()[before..].iter().cloned());
        }
        state = t.next.clone();
        if outcome != "bound" {
            break;
        }
        if !seen.insert(fingerprint(&state)) {
            outcome = "livelock";
            break;
        }
    }
    let trace = Trace {
        initial: beliefs
            .iter()
            .map(|a| p.atoms.display(a, &p.universe))
            .collect(),
        requests: requests
            .iter()
            .map(|r| sem.requests[*r as usize].to_string())
            .collect(),
        steps,
        outcome,
    };
    (trace, given)
}

/// The catalogue: every distinct explanation that the runs of the project give, per user,
/// each with the first scenario (in initial-state order, then shorter request sequences
/// first) that produces it.
///
/// Runs are enumerated as scenarios: every initial state with every sequence of distinct
/// requests up to `[requests] max`, each request arriving as soon as `arrival` allows and
/// the reasoning cycle choosing as `plan_selection` does first. With `arrival = "idle"` and
/// `plan_selection = "first"` (the kitchen's settings) these are all the runs there are;
/// otherwise the runs where requests arrive at other moments, or another applicable plan is
/// chosen, are not covered, and the catalogue says so in `note`.
pub fn catalogue(project: &Path, only: Option<&str>) -> Result<Catalogue, LoadFailure> {
    let p = load_project(project).map_err(|e| (e.map, e.diagnostics))?;
    let sem = Semantics::new(&p).map_err(|d| (p.map.clone(), d))?;
    let users = agent::users(&p, only).map_err(|d| (p.map.clone(), d))?;
    let n = sem.requests.len();
    let max = (p.manifest.requests.max as usize).min(n);
    // Every sequence of distinct request indices of length 1..=max, shortest first.
    let mut sequences: Vec<Vec<u8>> = vec![Vec::new()];
    let mut frontier: Vec<Vec<u8>> = vec![Vec::new()];
    for _ in 0..max {
        let mut next = Vec::new();
        for seq in &frontier {
            for r in 0..n as u8 {
                if !seq.contains(&r) {
                    let mut s = seq.clone();
                    s.push(r);
                    next.push(s);
                }
            }
        }
        sequences.extend(next.iter().cloned());
        frontier = next;
    }
    let mut entries: Vec<Entry> = Vec::new();
    for beliefs in p.initial.states() {
        for seq in &sequences {
            let (trace, given) = execute(&p, &sem, beliefs, seq, &users);
            for g in given {
                if !entries.iter().any(|e| e.given == g) {
                    entries.push(Entry {
                        given: g,
                        scenario: Scenario {
                            initial: trace.initial.clone(),
                            requests: trace.requests.clone(),
                        },
                    });
                }
            }
        }
    }
    entries.sort_by(|a, b| a.given.user.cmp(&b.given.user));
    let m = &p.manifest;
    let note = (m.requests.arrival == crate::syntax::manifest::Arrival::Any
        || m.bounds.plan_selection == crate::syntax::manifest::PlanSelection::Any)
        .then(|| {
            "requests arrive as soon as allowed and the first applicable plan is chosen: runs with other timings or choices are not in this catalogue".to_string()
        });
    Ok(Catalogue {
        entries,
        note,
        map: p.map.clone(),
    })
}
