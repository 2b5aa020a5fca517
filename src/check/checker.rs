//! The view every post-search check shares (the project, the explored graph, the recorded
//! facts), and how a check turns what it found into a finding with its run.

use super::explore::Graph;
use super::failures::Failure;
use super::model::Agent;
use super::search::{Conditions, Facts};
use super::trace;
use crate::findings::{Counterexample, Finding, Status};
use crate::model::project::Project;
use crate::semantics::Note;
use crate::syntax::{Severity, Span};

pub(super) struct Checker<'a> {
    pub(super) project: &'a Project,
    pub(super) agent: &'a Agent<'a>,
    pub(super) graph: &'a Graph,
    pub(super) facts: &'a Facts,
    pub(super) conditions: &'a Conditions<'a>,
}

/// Whether a transition's notes show the same failure as `want` (the same place; under
/// symmetry the goal may be a renaming of the one seen in exploration).
fn same_failure(want: &Note, notes: &[Note]) -> bool {
    notes.iter().any(|n| match (want, n) {
        (Note::ActionFailed { span: a, .. }, Note::ActionFailed { span: b, .. }) => a == b,
        (Note::GoalFailed { span: a, .. }, Note::GoalFailed { span: b, .. }) => a == b,
        (Note::NoApplicablePlan(a), Note::NoApplicablePlan(b)) => {
            a.literal.functor() == b.literal.functor() && a.literal.arity() == b.literal.arity()
        }
        _ => false,
    })
}

impl Checker<'_> {
    pub(super) fn location(&self, span: Span) -> crate::syntax::Location {
        self.project.map.location(span)
    }

    pub(super) fn finding(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
    ) -> Finding {
        dynamic_finding(check, name, (span, self.location(span)), status, message)
    }

    /// Undecided when the search was cut short, passed otherwise.
    pub(super) fn held(&self) -> Status {
        if self.graph.complete() {
            Status::Pass
        } else {
            Status::Unknown
        }
    }

    pub(super) fn counterexample(
        &self,
        path: &[u32],
        extra: Option<&Failure>,
        cycle: &[u32],
    ) -> Counterexample {
        let want = |notes: &Vec<Note>| extra.is_some_and(|f| same_failure(&f.note, notes));
        let extra = extra.map(|f| trace::Extra {
            src: f.src,
            k: f.k,
            fp: f.fp,
            want: &want,
        });
        trace::counterexample(self.project, self.agent, self.graph, path, extra, cycle)
    }

    /// A finding for a state reached by a shortest run, with that run.
    pub(super) fn reached(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
        at: u32,
    ) -> Finding {
        let mut f = self.finding(check, name, span, status, message);
        f.counterexample = Some(self.counterexample(&self.graph.path_to(at), None, &[]));
        f
    }
}

/// A finding of a dynamic check at `span` (located at `location`), an error unless the
/// caller says otherwise. An undecided check states only what the explored part shows.
pub(super) fn dynamic_finding(
    check: &str,
    name: &str,
    (span, location): (Span, crate::syntax::Location),
    status: Status,
    message: String,
) -> Finding {
    let message = if status == Status::Unknown {
        format!(
            "{message}, as far as the search went: it was cut short before every state was reached"
        )
    } else {
        message
    };
    Finding {
        id: format!("{check}:{name}"),
        check: check.into(),
        severity: Severity::Error,
        status,
        message,
        location: Some(location),
        counterexample: None,
        span: Some(span),
        related: Vec::new(),
        suppressed: None,
    }
}
