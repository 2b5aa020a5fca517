//! Pass 1, collecting names: every mental note, goal, rule, test goal and called action is
//! declared in order of first appearance before any clause is read, so a name may be used
//! before the place that defines it (as in Jason) and the tables' indices are stable.

use super::diagnostics::{count, goal_place, plural_or};
use super::{Checker, GoalInfo, PredInfo, RuleInfo};
use crate::syntax::ast::*;
use crate::syntax::manifest::Manifest;
use crate::syntax::{Diagnostic, Span};

impl Checker<'_> {
    // ----- pass 1: declarations ---------------------------------------------------------------

    /// Finds mental notes, goals, rules, test goals and called actions, in order of first
    /// appearance, then the manifest's requests.
    pub(super) fn declare(&mut self, items: &[&Item], manifest: &Manifest) {
        for item in items {
            match item {
                Item::Belief(b) => self.declare_note(&b.literal, b.literal.span),
                Item::Rule(r) => {
                    let key = (r.head.functor.clone(), r.head.args.len());
                    if !self.rule_ids.contains_key(&key) {
                        self.rule_ids.insert(key, self.rules.len());
                        self.rules.push(RuleInfo {
                            name: r.head.functor.clone(),
                            arity: r.head.args.len(),
                            span: r.head.span,
                        });
                    }
                }
                Item::InitialGoal(g) => {
                    self.declare_goal(&g.literal, g.literal.span, false);
                }
                Item::Plan(p) => self.declare_plan(p, false),
                Item::Directive(_) => {}
            }
        }
        for f in &manifest.requests.goals {
            let ExprKind::Literal(l) = &f.expr.kind else {
                continue;
            };
            let key = (l.functor.clone(), l.args.len());
            if self.goal_ids.contains_key(&key) {
                continue;
            }
            let others: Vec<&GoalInfo> =
                self.goals.iter().filter(|g| g.name == l.functor).collect();
            if let Some(g) = others.first() {
                let arities: Vec<String> = others.iter().map(|g| g.arity.to_string()).collect();
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "the goal `{}` takes {}, but this request gives it {}",
                        l.functor,
                        plural_or(&arities, "argument"),
                        count(l.args.len(), "argument"),
                    ),
                )
                .with_label(f.expr.span, "wrong number of arguments")
                .with_secondary(g.plan_span.unwrap_or(g.span), goal_place(g));
                self.diags.push(d);
                continue;
            }
            self.declare_goal(l, f.expr.span, false);
        }
    }

    /// A plan of the agent, or (`term`) a plan term a step adds (its body as written).
    fn declare_plan(&mut self, p: &Plan, term: bool) {
        if let ExprKind::Literal(l) = &p.trigger.literal.kind {
            match p.trigger.kind {
                TriggerKind::Achieve => {
                    let is_plan = p.trigger.op == TriggerOp::Add;
                    self.declare_goal(l, p.trigger.span, is_plan);
                }
                TriggerKind::Test => {
                    self.test_goals.insert(l.functor.clone());
                }
                TriggerKind::Belief => {}
            }
        }
        let body = if term { p.body.clone() } else { p.jason_body() };
        if let Some(b) = &body {
            self.declare_body(b);
        }
        for sp in &p.sub_plans {
            self.declare_plan(sp, term);
        }
    }

    fn declare_body(&mut self, b: &Body) {
        for s in &b.steps {
            match &s.kind {
                StepKind::Action(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        if !l.is_internal_action() {
                            self.called.insert(l.functor.clone());
                        } else if l.functor == ".add_plan" {
                            for p in l.args.first().map(added_plans).unwrap_or_default() {
                                self.declare_plan(p, true);
                            }
                        } else if let Some((ilf, content)) = message(l) {
                            // What a message tells, untells or asks is a belief of its
                            // receiver (and an answer, of its sender); what it asks to
                            // achieve or drop, a goal.
                            if ilf == "tellHow" {
                                let told = crate::model::know_how::told_plans(content);
                                for (_, p) in told.iter().flatten() {
                                    self.declare_plan(p, true);
                                }
                            }
                            if let ExprKind::Literal(c) = &content.kind {
                                match ilf {
                                    "tell" | "untell" | "askOne" | "askAll"
                                        if !c.is_internal_action() =>
                                    {
                                        self.declare_note(c, content.span)
                                    }
                                    "achieve" | "unachieve" if !c.is_internal_action() => {
                                        self.declare_goal(c, content.span, false)
                                    }
                                    _ => {}
                                }
                            }
                        }
                    }
                }
                StepKind::AddBel(e) | StepKind::AddBelEnd(e)
                    if matches!(e.kind, ExprKind::PlanTerm(_)) =>
                {
                    for p in added_plans(e) {
                        self.declare_plan(p, true);
                    }
                }
                StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        self.declare_goal(l, e.span, false);
                    }
                }
                StepKind::AddBel(e)
                | StepKind::AddBelEnd(e)
                | StepKind::AddBelNewFocus(e)
                | StepKind::DelAddBel(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        if !l.is_internal_action() {
                            self.declare_note(l, e.span);
                        }
                    }
                }
                StepKind::If {
                    branches,
                    else_body,
                } => {
                    for (_, b) in branches {
                        self.declare_body(b);
                    }
                    if let Some(b) = else_body {
                        self.declare_body(b);
                    }
                }
                StepKind::While { body, .. } | StepKind::For { body, .. } => {
                    self.declare_body(body)
                }
                StepKind::Fork { branches, .. } => {
                    for b in branches {
                        self.declare_body(b);
                    }
                }
                StepKind::Group(b) => self.declare_body(b),
                StepKind::Test(_)
                | StepKind::DelBel(_)
                | StepKind::DelBelNewFocus(_)
                | StepKind::Constraint(_) => {}
            }
        }
    }

    fn declare_note(&mut self, l: &Literal, span: Span) {
        let name = l.belief_name();
        if self.pred_ids.contains_key(name.as_ref())
            || (l.negated
                && self
                    .pred_ids
                    .get(&l.functor)
                    .is_some_and(|&p| self.preds[p].env))
        {
            return; // a PDDL predicate or its `~` (refused later), or a known note
        }
        self.pred_ids.insert(name.to_string(), self.preds.len());
        self.preds.push(PredInfo {
            name: name.into_owned(),
            env: false,
            span,
            arity: l.args.len(),
        });
    }

    fn declare_goal(&mut self, l: &Literal, span: Span, is_plan: bool) {
        let key = (l.functor.clone(), l.args.len());
        let id = match self.goal_ids.get(&key) {
            Some(&id) => id,
            None => {
                self.goal_ids.insert(key, self.goals.len());
                self.goals.push(GoalInfo {
                    name: l.functor.clone(),
                    arity: l.args.len(),
                    span,
                    plan_span: None,
                });
                self.goals.len() - 1
            }
        };
        if is_plan && self.goals[id].plan_span.is_none() {
            self.goals[id].plan_span = Some(span);
        }
    }
}

/// The plans of plan terms that `.add_plan`'s first argument (or `+{P}`) holds: one, or
/// those of a list.
pub(super) fn added_plans(e: &Expr) -> Vec<&Plan> {
    match &e.kind {
        ExprKind::PlanTerm(t) => match &t.kind {
            PlanTermKind::Plan(p) => vec![p],
            _ => Vec::new(),
        },
        ExprKind::List(l) => l.elems.iter().flat_map(added_plans).collect(),
        _ => Vec::new(),
    }
}

/// The performative (written out) and the content of `.send(R, Ilf, Content)` or
/// `.broadcast(Ilf, Content)`.
fn message(l: &Literal) -> Option<(&str, &Expr)> {
    let (ilf, content) = match (l.functor.as_str(), l.args.as_slice()) {
        (".send", [_, ilf, content, ..]) => (ilf, content),
        (".broadcast", [ilf, content]) => (ilf, content),
        _ => return None,
    };
    match &ilf.kind {
        ExprKind::Literal(p) if p.args.is_empty() => Some((p.functor.as_str(), content)),
        _ => None,
    }
}
