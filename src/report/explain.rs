//! `bdi-check explain PROJECT --scenario FILE [--user NAME]`: one run of the robot, told step
//! by step, with the explanation each user gets in place.
//!
//! The run is the scenario's initial state and requests (SPEC §2), executed with the
//! project's semantics: a request arrives as soon as the manifest's `arrival` allows, and
//! the reasoning cycle runs otherwise. At each executed environment action, Algorithm 1
//! decides, per user, whether the action surprises them ([`crate::explain::demand`]); when it
//! does, Algorithm 2 builds the explanation from the running intention's stack
//! ([`crate::explain::content()`]) and it is rendered as one sentence. Each user's view of the
//! run is [`Explained`], the model whose explanations `verify` checks: what `explain` prints
//! is what was verified.

use crate::check::explanation::{Explained, ExplainedState, Step};
use crate::check::explore::fingerprint;
use crate::check::model::Model;
use crate::check::run::resolve_scenario;
use crate::check::trace::Builder;
use crate::explain::agent::{self, Explainer, User};
use crate::model::atoms::AtomSet;
use crate::model::project::{load_project, Project};
use crate::report::{Report, StepKindTag, TraceStep};
use crate::semantics::{Note, Semantics, State};
use crate::syntax::manifest::load_scenario;
use crate::syntax::{Diagnostic, SourceMap};
use serde::Serialize;
use std::collections::HashSet;
use std::path::Path;

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
                let Some(g) = &step.given[i] else { continue };
                steps.push(TraceStep {
                    kind: StepKindTag::Explanation,
                    text: format!("to {}: {}", u.name, g.text),
                    intention: None,
                    plan: None,
                    added: Vec::new(),
                    removed: Vec::new(),
                    explanation: Some(g.text.clone()),
                });
                given.push(Given {
                    user: u.name.clone(),
                    action: g.action.to_string(),
                    after: g.after.as_ref().map(|o| o.to_string()),
                    context: g.content.context.iter().map(|l| l.to_string()).collect(),
                    actions: g.content.actions.iter().map(|a| a.to_string()).collect(),
                    text: g.text.clone(),
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

/// The run as a numbered story with the explanations in place.
pub fn render_human(run: &ExplainRun, color: bool) -> String {
    let mut out = String::new();
    for d in &run.diagnostics {
        out.push_str(&d.render(&run.map, color));
        out.push('\n');
    }
    let Some(t) = &run.trace else { return out };
    let c = crate::report::Counterexample {
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
    for beliefs in &p.initial.states {
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

/// The catalogue for people: per user, each sentence with the action and a scenario.
pub fn render_catalogue(entries: &[Entry], note: Option<&str>) -> String {
    let mut out = String::new();
    let mut user = "";
    for e in entries {
        if e.given.user != user {
            user = &e.given.user;
            let count = entries.iter().filter(|x| x.given.user == user).count();
            out.push_str(&format!(
                "{user}: {count} distinct explanation{}\n",
                if count == 1 { "" } else { "s" }
            ));
        }
        out.push_str(&format!(
            "  {} (after {})\n    \"{}\"\n    scenario: initial = [{}], requests = [{}]\n",
            e.given.action,
            e.given.after.as_deref().unwrap_or("the start"),
            e.given.text,
            e.scenario.initial.join(", "),
            e.scenario.requests.join(", ")
        ));
    }
    if let Some(n) = note {
        out.push_str(&format!("note: {n}\n"));
    }
    out
}
