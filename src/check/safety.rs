//! The checks one reached state decides: invariants, `always` and `reachable` properties
//! (SPEC §3), and deadlock; each violation comes with the shortest run to its state.

use super::checker::Checker;
use super::search::bit;
use crate::findings::{Finding, Status};
use crate::model::cond::Cond;
use crate::syntax::Span;

/// A compiled state property.
pub(super) struct Prop {
    pub(super) name: String,
    pub(super) kind: crate::syntax::manifest::PropertyKind,
    pub(super) cond: Cond,
    pub(super) span: Span,
}

impl Checker<'_> {
    pub(super) fn safety(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let n = self.graph.len();
        let facts = self.facts;
        for (j, (name, _)) in self.project.invariants.iter().enumerate() {
            let span = self
                .project
                .manifest
                .invariants
                .iter()
                .find(|i| &i.name.value == name)
                .map_or(Span::default(), |i| i.formula.span);
            match facts.first_fails[j] {
                Some(i) => out.push(self.reached(
                    "invariant",
                    name,
                    span,
                    Status::Fail,
                    format!(
                        "invariant `{name}` is violated after {} steps",
                        self.graph.depth(i)
                    ),
                    i,
                )),
                None => out.push(self.finding(
                    "invariant",
                    name,
                    span,
                    self.held(),
                    format!("invariant `{name}` holds in all {n} reached states"),
                )),
            }
        }
        use crate::syntax::manifest::PropertyKind;
        let base = self.project.invariants.len();
        for (j, p) in props.iter().enumerate() {
            match p.kind {
                PropertyKind::Always => match facts.first_fails[base + j] {
                    Some(i) => out.push(self.reached(
                        "property",
                        &p.name,
                        p.span,
                        Status::Fail,
                        format!(
                            "`{}` does not always hold: it is false after {} steps",
                            p.name,
                            self.graph.depth(i)
                        ),
                        i,
                    )),
                    None => out.push(self.finding(
                        "property",
                        &p.name,
                        p.span,
                        self.held(),
                        format!("`{}` holds in all {n} reached states", p.name),
                    )),
                },
                PropertyKind::Reachable => match facts.first_holds[base + j] {
                    Some(i) => out.push(self.reached(
                        "property",
                        &p.name,
                        p.span,
                        Status::Pass,
                        format!(
                            "`{}` is reached after {} steps (witness run attached)",
                            p.name,
                            self.graph.depth(i)
                        ),
                        i,
                    )),
                    None => {
                        let status = if self.graph.complete() {
                            Status::Fail
                        } else {
                            Status::Unknown
                        };
                        out.push(self.finding(
                            "property",
                            &p.name,
                            p.span,
                            status,
                            format!("`{}` is never reached", p.name),
                        ));
                    }
                },
                PropertyKind::Eventually | PropertyKind::Ltl => {}
            }
        }
        // Deadlock: a state with nothing to do that is not a finished run: an intention in a
        // `.wait` that nothing will wake.
        let stuck = (0..n as u32).find(|&i| {
            self.graph.successors(i).is_some_and(|e| e.is_empty()) && !bit(&facts.idle, i)
        });
        let span = self.project.manifest.agent.plans.written.span;
        match stuck {
            Some(i) => out.push(self.reached(
                "deadlock",
                "agent",
                span,
                Status::Fail,
                "the agent is stuck: no step is possible, but it is not done".into(),
                i,
            )),
            None => out.push(self.finding(
                "deadlock",
                "agent",
                span,
                self.held(),
                "no reachable state is stuck".into(),
            )),
        }
    }
}
