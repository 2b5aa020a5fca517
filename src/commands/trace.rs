//! `bdi-check trace REPORT.json --finding ID`: a counterexample step by step with the
//! agent's whole state after each transition (beliefs, events, intention stacks with their
//! bindings, each user's expected successors), the way SPIN's `-t -p` and TLC's trace
//! explorer let users probe a run. The run is replayed on the project as it is now, as
//! `replay` does, and the exit code is `replay`'s.

use super::replay::{walk, Walk};
use super::{Output, Style};
use crate::check::explanation::{Explained, ExplainedState};
use crate::check::model::Model;
use crate::check::trace::Builder;
use crate::explain::agent::{users, Explainer};
use crate::findings::{ExpectedView, Trace, TracedTransition};
use crate::model::project::Project;
use crate::report::Format;
use crate::semantics::Semantics;
use std::path::Path;

/// `trace REPORT --finding ID`: exit 1 while the run still reaches its violation, 0 once
/// it does not, 2 on bad input (as `replay`).
pub fn command(report: &Path, finding: &str, style: &Style) -> Output {
    if let Some(refused) = style.refuse_ci_format("trace") {
        return refused;
    }
    match walk(report, finding, build) {
        Err((map, errs)) => {
            Output::refused(crate::report::diagnostics(&errs, &map, style.stderr_color))
        }
        Ok((trace, notice)) => {
            let text = match style.format {
                Format::Json => crate::report::trace::render_json(&trace),
                Format::Human => crate::report::trace::render_human(&trace, style.color),
            };
            let mut out = Output::report(text, i32::from(trace.reached));
            out.stderr = notice;
            out
        }
    }
}

/// The trace of a replayed run: the state after each transition, and each user's `N`
/// as Algorithm 1 updates it along the same run.
fn build(project: &Project, sem: &Semantics, w: &Walk) -> Trace {
    let mut b = Builder::new(project, sem);
    // A project without `[explanation]` has no users: no expected successors to show.
    let users = users(project, None).unwrap_or_default();
    let ex = Explainer::new(project, sem);
    let models: Vec<Explained> = users
        .iter()
        .map(|u| Explained::new(sem, &ex, u, None))
        .collect();
    let mut views: Vec<Option<ExplainedState>> = models
        .iter()
        .map(|m| m.init_states().into_iter().find(|s| s.state == w.initial))
        .collect();
    let expected = |views: &[Option<ExplainedState>]| -> Vec<ExpectedView> {
        users
            .iter()
            .zip(views.iter().zip(&models))
            .filter_map(|(u, (v, m))| {
                let n = m.expected(v.as_ref()?);
                Some(ExpectedView {
                    user: u.name.clone(),
                    patterns: n.initial().len(),
                    learned: n.learned().iter().map(ToString::to_string).collect(),
                })
            })
            .collect()
    };
    let mut initial = b.state_view(&w.initial);
    initial.expected = expected(&views);
    let mut transitions = Vec::new();
    for t in &w.walked {
        let before = b.steps().len();
        b.push(t.notes.clone());
        let steps = b.steps()[before..].to_vec();
        // The user's view follows the agent's transition: the one with the same notes to
        // the same state (Algorithm 1 is a function of them).
        for (m, v) in models.iter().zip(views.iter_mut()) {
            *v = v.take().and_then(|s| {
                m.next_states(&s)
                    .into_iter()
                    .find(|(step, n)| step.notes == t.notes && n.state == t.state)
                    .map(|(_, n)| n)
            });
        }
        let mut state = b.state_view(&t.state);
        state.expected = expected(&views);
        transitions.push(TracedTransition { steps, state });
    }
    Trace {
        finding: w.id.to_string(),
        check: w.check.to_string(),
        message: w.message.to_string(),
        initial,
        transitions,
        reached: w.result.reached,
        outcome: w.result.detail.clone(),
    }
}
