//! Pass 2 over the manifest: facts, `vary`, constraints, invariants, properties, requests,
//! `emitted_by`, phrases and expected pairs become clauses checked against the same
//! vocabulary as the plans.

use super::diagnostics::suggest;
use super::{Checker, Clause, Role, Scope, Usage};
use crate::syntax::ast::*;
use crate::syntax::manifest::{Formula, Manifest, StepFormula};
use crate::syntax::{Diagnostic, Span};

impl Checker<'_> {
    // ----- the manifest -----------------------------------------------------------------------

    pub(super) fn collect_manifest(&mut self, m: &Manifest) {
        for f in &m.initial.facts {
            let mut cl = Clause::default();
            if let ExprKind::Literal(l) = &f.expr.kind {
                self.belief_literal(
                    &mut cl,
                    l,
                    Usage::Fact,
                    Scope::Manifest { properties: false },
                );
            }
            self.clauses.push(cl);
        }
        for v in &m.initial.vary {
            if !self.pred_ids.contains_key(&v.value) {
                let hint = suggest(&v.value, self.preds.iter().map(|p| p.name.as_str()))
                    .map(|s| format!("; did you mean `{s}`?"))
                    .unwrap_or_default();
                self.diags.push(
                    Diagnostic::error("input", format!("unknown predicate `{}`{hint}", v.value))
                        .with_label(v.span, "not a predicate")
                        .with_help("`vary` names PDDL predicates or mental notes"),
                );
            }
        }
        let no_props = Scope::Manifest { properties: false };
        for f in &m.initial.constraints {
            self.manifest_formula(f, no_props);
        }
        for inv in &m.invariants {
            self.manifest_formula(&inv.formula, no_props);
        }
        // The state formulas of a property, but those with a modality other than
        // `.intend`/`.desire` (not predicates: `model::property` checks them as it compiles
        // them). The parts of an `ltl` formula share their variables, so a variable is not
        // required to be typed in each part.
        for p in &m.properties {
            let scope = Scope::Manifest { properties: true };
            let plain = |e: &&crate::syntax::ast::Expr| !crate::model::property::uses_modality(e);
            match &p.ltl {
                None if plain(&&p.formula.expr) => self.manifest_formula(&p.formula, scope),
                None => {}
                Some(l) => {
                    for e in l.states().into_iter().filter(plain) {
                        let f = Formula {
                            text: p.formula.text.clone(),
                            span: e.span,
                            expr: e.clone(),
                        };
                        self.formula_part(&f, scope);
                    }
                }
            }
        }
        for f in &m.requests.goals {
            let mut cl = Clause::default();
            if let ExprKind::Literal(l) = &f.expr.kind {
                self.goal_literal(&mut cl, l, Role::Use, no_props);
            }
            self.clauses.push(cl);
        }
        if let Some(x) = &m.explanation {
            if let Some(e) = &x.emitted_by {
                if !self.called.contains(&e.value) {
                    let mut names: Vec<&str> = self.called.iter().map(String::as_str).collect();
                    names.sort_unstable();
                    let hint = suggest(&e.value, names)
                        .map(|s| format!("; did you mean `{s}`?"))
                        .unwrap_or_default();
                    self.diags.push(
                        Diagnostic::error(
                            "input",
                            format!("no plan calls the action `{}`{hint}", e.value),
                        )
                        .with_label(e.span, "`emitted_by` names an action the plans call"),
                    );
                }
            }
            for p in &x.phrases {
                let mut cl = Clause::default();
                self.phrase(&mut cl, &p.pattern);
                self.clauses.push(cl);
            }
            for u in &x.users {
                for pair in &u.expected {
                    let mut cl = Clause {
                        free_check: true,
                        ..Clause::default()
                    };
                    self.observed(&mut cl, &pair.before);
                    self.observed(&mut cl, &pair.after);
                    self.clauses.push(cl);
                }
            }
        }
    }

    fn manifest_formula(&mut self, f: &Formula, scope: Scope) {
        let mut cl = Clause {
            free_check: true,
            ..Clause::default()
        };
        named_vars(&f.expr, &mut cl.vars);
        self.formula(&mut cl, &f.expr, scope, Usage::Query);
        self.clauses.push(cl);
    }

    /// A part of a formula whose variables other parts may type.
    fn formula_part(&mut self, f: &Formula, scope: Scope) {
        let mut cl = Clause::default();
        named_vars(&f.expr, &mut cl.vars);
        self.formula(&mut cl, &f.expr, scope, Usage::Query);
        self.clauses.push(cl);
    }

    /// One side of an expected pair: `!g(args)` or a PDDL action.
    fn observed(&mut self, cl: &mut Clause, s: &StepFormula) {
        let scope = Scope::Manifest { properties: false };
        match &s.step.kind {
            StepKind::Achieve(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    named_vars(e, &mut cl.vars);
                    self.known_goal(cl, l, e.span, scope);
                }
            }
            StepKind::Action(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    named_vars(e, &mut cl.vars);
                    if let Some(&a) = self.action_ids.get(&l.functor) {
                        self.action_args(cl, l, a);
                    } else {
                        self.unknown_action(
                            l,
                            "an expected pair names PDDL actions and requests `!g`",
                        );
                    }
                }
            }
            _ => {}
        }
    }

    fn unknown_action(&mut self, l: &Literal, help: &str) {
        let hint = suggest(&l.functor, self.actions.iter().map(|a| a.name.as_str()))
            .map(|s| format!("; did you mean `{s}`?"))
            .unwrap_or_default();
        self.diags.push(
            Diagnostic::error(
                "input",
                format!("`{}` is not an action of the PDDL domain{hint}", l.functor),
            )
            .with_label(l.span, "unknown action")
            .with_help(help.to_string()),
        );
    }

    /// A phrase pattern: a predicate, an action or a request.
    fn phrase(&mut self, cl: &mut Clause, s: &StepFormula) {
        let scope = Scope::Manifest { properties: false };
        match &s.step.kind {
            StepKind::Achieve(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    self.known_goal(cl, l, e.span, scope);
                }
            }
            StepKind::Action(e) => {
                let ExprKind::Literal(l) = &e.kind else {
                    return;
                };
                if self.pred_ids.contains_key(&l.functor) {
                    self.belief_literal(cl, l, Usage::Pattern, scope);
                } else if let Some(&a) = self.action_ids.get(&l.functor) {
                    self.action_args(cl, l, a);
                } else {
                    let names = self
                        .preds
                        .iter()
                        .map(|p| p.name.as_str())
                        .chain(self.actions.iter().map(|a| a.name.as_str()));
                    let hint = suggest(&l.functor, names)
                        .map(|s| format!("; did you mean `{s}`?"))
                        .unwrap_or_default();
                    self.diags.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "`{}` is neither a predicate nor a PDDL action{hint}",
                                l.functor
                            ),
                        )
                        .with_label(l.span, "unknown name")
                        .with_help("a phrase pattern is an atom `p(X)`, an action `a(X)` or a request `!g(X)`"),
                    );
                }
            }
            _ => {}
        }
    }
}

/// Every named variable (not `_`, not `_X`) of an expression, with its span, in order.
fn named_vars(e: &Expr, out: &mut Vec<(String, Span)>) {
    let list = |l: &ListExpr, out: &mut Vec<(String, Span)>| {
        l.elems.iter().for_each(|a| named_vars(a, out));
        if let Some(t) = &l.tail {
            named_vars(t, out);
        }
    };
    match &e.kind {
        ExprKind::Literal(l) => l.args.iter().for_each(|a| named_vars(a, out)),
        ExprKind::Var(v) => {
            if !v.name.starts_with('_') {
                out.push((v.name.clone(), e.span));
            }
        }
        ExprKind::List(l) => list(l, out),
        ExprKind::Unary(_, a) | ExprKind::Not(a) => named_vars(a, out),
        ExprKind::Arith(_, a, b)
        | ExprKind::Rel(_, a, b)
        | ExprKind::And(a, b)
        | ExprKind::Or(a, b) => {
            named_vars(a, out);
            named_vars(b, out);
        }
        ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) | ExprKind::PlanTerm(_) => {}
    }
}
