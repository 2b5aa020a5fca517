//! Pass 2 over the `.asl`: every initial belief, rule, initial goal and plan becomes a clause
//! of typed positions; plan bodies are walked step by step, and calls of actions and goals
//! are checked against their signatures.

use super::diagnostics::{count, given, goal_place, plural_or, suggest};
use super::{Checker, Clause, GoalInfo, Role, Scope, Sig, UndefinedAction, Usage};
use crate::syntax::ast::*;
use crate::syntax::{Diagnostic, Span};

impl Checker<'_> {
    // ----- pass 2: clauses and structural checks ----------------------------------------------

    pub(super) fn collect_agent(&mut self, items: &[&Item]) {
        for item in items {
            match item {
                Item::Belief(b) => {
                    let mut cl = Clause::default();
                    let l = &b.literal;
                    if let Some(&p) = self.pred_ids.get(&l.functor) {
                        if self.preds[p].env {
                            let d = Diagnostic::error(
                                "input",
                                format!(
                                    "the initial belief `{}` is about the environment predicate `{}`, whose atoms start as the manifest's `[initial]` section says",
                                    self.map.slice(l.span),
                                    l.functor
                                ),
                            )
                            .with_label(l.span, "environment atom")
                            .with_secondary(self.preds[p].span, "declared in PDDL here")
                            .with_help("move it to `facts` (or `vary`) in `[initial]` of bdi-check.toml");
                            self.diags.push(d);
                            continue;
                        }
                    }
                    self.belief_literal(&mut cl, l, Usage::Add, Scope::Agent);
                    self.clauses.push(cl);
                }
                Item::Rule(r) => {
                    let mut cl = Clause::default();
                    let h = &r.head;
                    if let Some(&p) = self.pred_ids.get(&h.functor) {
                        if self.preds[p].env {
                            let d = Diagnostic::error(
                                "input",
                                format!(
                                    "the rule defines `{}`, an environment predicate: environment atoms change only through actions in this model",
                                    h.functor
                                ),
                            )
                            .with_label(h.span, "rule head")
                            .with_secondary(self.preds[p].span, "declared in PDDL here")
                            .with_help("give the rule a name of its own");
                            self.diags.push(d);
                        }
                    }
                    if let Some(&id) = self.rule_ids.get(&(h.functor.clone(), h.args.len())) {
                        for (i, a) in h.args.iter().enumerate() {
                            self.loose_arg(
                                &mut cl,
                                a,
                                Sig::Rule(id),
                                i,
                                Role::Define,
                                Scope::Agent,
                            );
                        }
                    }
                    self.formula(&mut cl, &r.body, Scope::Agent, Usage::Query);
                    self.clauses.push(cl);
                }
                Item::InitialGoal(g) => {
                    let mut cl = Clause::default();
                    self.goal_literal(&mut cl, &g.literal, Role::Use, Scope::Agent);
                    self.clauses.push(cl);
                }
                Item::Plan(p) => self.plan(p, false),
                Item::Directive(_) => {}
            }
        }
    }

    /// A plan of the agent, or (`term`) a plan term a step adds (its body as written): a
    /// clause of its own (an added plan shares no variable with the plan that adds it).
    pub(super) fn plan(&mut self, p: &Plan, term: bool) {
        let mut cl = Clause::default();
        let t = &p.trigger;
        match (&t.literal.kind, t.kind) {
            (ExprKind::Literal(l), TriggerKind::Achieve) => {
                let role = if t.op == TriggerOp::Add {
                    Role::Define
                } else {
                    Role::Use
                };
                self.goal_literal(&mut cl, l, role, Scope::Agent);
            }
            (ExprKind::Literal(l), TriggerKind::Test) => {
                for a in &l.args {
                    self.term(&mut cl, a, Scope::Agent);
                }
            }
            (ExprKind::Literal(l), TriggerKind::Belief) => {
                self.belief_literal(&mut cl, l, Usage::Trigger, Scope::Agent);
            }
            (_, _) => {
                self.diags.push(
                    Diagnostic::error(
                        "input",
                        "a plan whose trigger is a variable is not supported by bdi-check",
                    )
                    .with_label(t.literal.span, "variable trigger")
                    .with_help("write one plan per goal or belief"),
                );
            }
        }
        if let Some(c) = &p.context {
            self.formula(&mut cl, c, Scope::Agent, Usage::Query);
        }
        if let Some(c) = &p.goal_condition {
            self.formula(&mut cl, c, Scope::Agent, Usage::Query);
        }
        let body = if term { p.body.clone() } else { p.jason_body() };
        if let Some(b) = &body {
            self.body(&mut cl, b);
        }
        self.clauses.push(cl);
        for sp in &p.sub_plans {
            self.plan(sp, term);
        }
    }

    fn body(&mut self, cl: &mut Clause, b: &Body) {
        for s in &b.steps {
            self.step(cl, s);
        }
    }

    fn step(&mut self, cl: &mut Clause, s: &Step) {
        match &s.kind {
            StepKind::Action(e) => match &e.kind {
                ExprKind::Literal(l) if l.is_internal_action() => {
                    self.internal(cl, l, Scope::Agent)
                }
                ExprKind::Literal(l) => self.body_action(cl, l),
                _ => self.unsupported(e.span, "an action held in a variable", "variable action"),
            },
            StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => match &e.kind {
                ExprKind::Literal(l) => self.goal_literal(cl, l, Role::Use, Scope::Agent),
                _ => self.unsupported(e.span, "a goal held in a variable", "variable goal"),
            },
            StepKind::Test(e) => self.formula(cl, e, Scope::Agent, Usage::Test),
            // `+{P}`, `+>{P}`: `.add_plan`; `-{P}`: `.remove_plan`, which reads its label only.
            StepKind::AddBel(e) | StepKind::AddBelEnd(e)
                if matches!(e.kind, ExprKind::PlanTerm(_)) =>
            {
                for p in super::declare::added_plans(e) {
                    self.plan(p, true);
                }
            }
            StepKind::DelBel(e) if matches!(e.kind, ExprKind::PlanTerm(_)) => {}
            StepKind::AddBel(e) | StepKind::AddBelEnd(e) | StepKind::AddBelNewFocus(e) => {
                self.update(cl, e, Usage::Add)
            }
            StepKind::DelAddBel(e) => self.update(cl, e, Usage::Replace),
            StepKind::DelBel(e) | StepKind::DelBelNewFocus(e) => self.update(cl, e, Usage::Del),
            StepKind::Constraint(e) => self.formula(cl, e, Scope::Agent, Usage::Query),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    self.formula(cl, c, Scope::Agent, Usage::Query);
                    self.body(cl, b);
                }
                if let Some(b) = else_body {
                    self.body(cl, b);
                }
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                self.formula(cl, cond, Scope::Agent, Usage::Query);
                self.body(cl, body);
            }
            StepKind::Fork { branches, .. } => {
                for b in branches {
                    self.body(cl, b);
                }
            }
            StepKind::Group(b) => self.body(cl, b),
        }
    }

    pub(super) fn unsupported(&mut self, span: Span, what: &str, label: &str) {
        self.diags.push(
            Diagnostic::error("input", format!("{what} is not supported by bdi-check"))
                .with_label(span, label),
        );
    }

    /// `+b`, `-b`, `-+b`, ... in a body.
    fn update(&mut self, cl: &mut Clause, e: &Expr, usage: Usage) {
        match &e.kind {
            ExprKind::Literal(l) => self.belief_literal(cl, l, usage, Scope::Agent),
            // `step` takes `+{P}`, `+>{P}` and `-{P}`, the only places the parser allows a
            // plan term in (AS2JavaParser.jj, `body_formula`).
            ExprKind::PlanTerm(_) => {}
            _ => self.unsupported(e.span, "a belief update held in a variable", "variable"),
        }
    }

    /// A non-internal action in a body: PDDL, `emitted_by`, or undefined.
    fn body_action(&mut self, cl: &mut Clause, l: &Literal) {
        if let Some(&a) = self.action_ids.get(&l.functor) {
            self.action_args(cl, l, a);
        } else {
            if self.emitted_by.as_deref() != Some(l.functor.as_str()) {
                self.undefined.push(UndefinedAction {
                    name: l.functor.clone(),
                    arity: l.args.len(),
                    span: l.span,
                });
            }
            for a in &l.args {
                self.term(cl, a, Scope::Agent);
            }
        }
    }

    /// The arguments of a call of PDDL action `a`, after an arity check.
    pub(super) fn action_args(&mut self, cl: &mut Clause, l: &Literal, a: usize) {
        // The `?agent` parameter is the acting agent's, not written.
        let actor = self.actions[a].actor;
        let want = self.actions[a].params.len() - usize::from(actor.is_some());
        if l.args.len() != want {
            let d = Diagnostic::error(
                "input",
                format!(
                    "the action `{}` takes {}, but {} given",
                    l.functor,
                    count(want, "argument"),
                    given(l.args.len())
                ),
            )
            .with_label(l.span, format!("expected {}", count(want, "argument")))
            .with_secondary(self.actions[a].decl, "declared in PDDL here");
            let d = if actor.is_some() {
                d.with_help(
                    "its `?agent` parameter is the agent that does it, which a plan does not write",
                )
            } else {
                d
            };
            self.diags.push(d);
            return;
        }
        for (i, x) in l.args.iter().enumerate() {
            let param = match actor {
                Some(p) if i >= p => i + 1,
                _ => i,
            };
            self.strict_arg(cl, x, Sig::Action(a), param, Role::Use);
        }
    }

    /// A goal `g(args)` (trigger, subgoal, initial goal, request): its arguments are typed by
    /// the goal's parameters.
    pub(super) fn goal_literal(&mut self, cl: &mut Clause, l: &Literal, role: Role, scope: Scope) {
        if let Some(&g) = self.goal_ids.get(&(l.functor.clone(), l.args.len())) {
            for (i, a) in l.args.iter().enumerate() {
                self.loose_arg(cl, a, Sig::Goal(g), i, role, scope);
            }
        }
    }

    /// A reference to a goal that must be known: `.desire(g)`, a pair's `!g`, a phrase `!g`.
    pub(super) fn known_goal(&mut self, cl: &mut Clause, l: &Literal, span: Span, scope: Scope) {
        if self
            .goal_ids
            .contains_key(&(l.functor.clone(), l.args.len()))
        {
            self.goal_literal(cl, l, Role::Use, scope);
            return;
        }
        let others: Vec<&GoalInfo> = self.goals.iter().filter(|g| g.name == l.functor).collect();
        let d = if let Some(g) = others.first() {
            let arities: Vec<String> = others.iter().map(|g| g.arity.to_string()).collect();
            Diagnostic::error(
                "input",
                format!(
                    "the goal `{}` takes {}, but {} given",
                    l.functor,
                    plural_or(&arities, "argument"),
                    given(l.args.len())
                ),
            )
            .with_label(span, "wrong number of arguments")
            .with_secondary(g.plan_span.unwrap_or(g.span), goal_place(g))
        } else {
            let names: Vec<&str> = self.goals.iter().map(|g| g.name.as_str()).collect();
            let hint = suggest(&l.functor, names)
                .map(|s| format!("; did you mean `{s}`?"))
                .unwrap_or_default();
            Diagnostic::error("input", format!("unknown goal `{}`{hint}", l.functor))
                .with_label(span, "no plan, subgoal or request has this goal")
        };
        self.diags.push(d);
    }
}
