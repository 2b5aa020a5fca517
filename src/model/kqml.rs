//! The plans every Jason agent has for the messages it receives: Jason's `kqmlPlans.asl`,
//! which `Agent.loadKqmlPlans` puts at the end of every agent's plan library. The
//! reasoning cycle takes an `achieve` or a `tell` of a literal by a shortcut
//! (`TransitionSystem.applyProcMsg`); every other performative becomes the event
//! `+!kqml_received(Sender, Performative, Content, MsgId)`, and one of these plans
//! handles it, step by step, as any plan of the agent's own would be run.
//!
//! bdi-check's rendering ([`crate::syntax::source::KQML_PLANS`], the file
//! [`FileId::KQML`]) has Jason's triggers, labels, contexts and number of steps; where
//! Jason's plans use namespaces and the `kqml::` rules, it calls internal actions of
//! bdi-check's own (`.kqml_answer`, `.kqml_answers`, `.kqml_untell`, `.kqml_error`,
//! `.kqml_tell_how`, `.kqml_untell_how`, `.kqml_relevant_plans`), which
//! the reasoning cycle implements and an agent's own code cannot call.

use super::from_ast::Converter;
use super::plans::{convert_error, formula, BodyStep, Formula, Plan, Step, Trigger};
use crate::syntax::ast::{Expr, ExprKind, Item, StepKind};
use crate::syntax::source::KQML_PLANS;
use crate::syntax::{parse_agent, Diagnostic, FileId};
use std::sync::OnceLock;

/// The internal actions only these plans call.
pub const OWN_ACTIONS: &[&str] = &[
    ".kqml_answer",
    ".kqml_answers",
    ".kqml_untell",
    ".kqml_error",
    ".kqml_tell_how",
    ".kqml_untell_how",
    ".kqml_relevant_plans",
];

/// The plans, in Jason's order, each numbered from 0 (an agent's library gives them the
/// indices after its own plans).
pub fn plans() -> &'static [Plan] {
    static PLANS: OnceLock<Vec<Plan>> = OnceLock::new();
    PLANS.get_or_init(|| compile().unwrap_or_else(|d| panic!("bdi-check's kqml plans: {d:?}")))
}

fn compile() -> Result<Vec<Plan>, Vec<Diagnostic>> {
    let (ast, errors) = parse_agent(FileId::KQML, KQML_PLANS);
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut out = Vec::new();
    for item in &ast.items {
        let Item::Plan(p) = item else { continue };
        let mut c = Converter::for_plans();
        let ExprKind::Literal(l) = &p.trigger.literal.kind else {
            unreachable!("the triggers are literals")
        };
        let literal = c.literal(l).map_err(|e| vec![convert_error(e)])?;
        let context = match &p.context {
            Some(e) => formula(&mut c, e).map_err(|d| vec![d])?,
            None => Formula::True,
        };
        let mut body = Vec::new();
        for s in p.body.iter().flat_map(|b| b.steps.iter()) {
            let kind = match &s.kind {
                StepKind::Action(Expr {
                    kind: ExprKind::Literal(l),
                    ..
                }) => BodyStep::Internal(c.literal(l).map_err(|e| vec![convert_error(e)])?),
                // `?Query`: the query is the variable's value when the step runs.
                StepKind::Test(e) => BodyStep::Test(Formula::Literal(
                    c.term(e).map_err(|e| vec![convert_error(e)])?,
                )),
                _ => unreachable!("the kqml plans have internal actions and a test goal"),
            };
            body.push(Step { kind, span: s.span });
        }
        let label = p.label.as_ref();
        let atomic = label.is_some_and(super::plans::is_atomic_label);
        out.push(Plan {
            index: out.len(),
            label: label.and_then(|l| l.name.clone()),
            trigger: Trigger {
                op: p.trigger.op,
                kind: p.trigger.kind,
                literal,
            },
            context,
            body,
            span: p.span,
            context_span: p.context.as_ref().map(|e| e.span),
            atomic,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plans_compile_with_jasons_labels_and_steps() {
        let plans = plans();
        let labels: Vec<&str> = plans.iter().filter_map(|p| p.label.as_deref()).collect();
        assert_eq!(
            labels,
            [
                "kqmlReceivedUnTell",
                "kqmlReceivedUnAchieve",
                "kqmlReceivedAskOne1d",
                "kqmlReceivedAskOne1c",
                "kqmlReceivedAskOne2",
                "kqmlReceivedAskAll2",
                "kqmlReceivedTellHow",
                "kqmlReceivedUnTellHow",
                "kqmlReceivedAskHow",
                "kqmlError"
            ]
        );
        let steps: Vec<usize> = plans.iter().map(|p| p.body.len()).collect();
        assert_eq!(steps, [1, 1, 1, 4, 1, 2, 2, 1, 3, 1]);
        let atomic: Vec<bool> = plans.iter().map(|p| p.atomic).collect();
        assert_eq!(
            atomic,
            [true, true, false, false, false, false, false, false, false, false]
        );
        assert!(plans.iter().all(|p| p.span.file == FileId::KQML));
    }
}
