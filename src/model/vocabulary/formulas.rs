//! Formulas, terms and internal actions: what a context, a condition or a manifest formula
//! may contain, limited to the arithmetic functions and internal actions the model covers
//! (SPEC §4).

use super::diagnostics::{given, plural_or};
use super::literals::is_atom;
use super::{
    arithmetic_function, modelled_action, Checker, Clause, Scope, Usage, GOAL_ACTIONS,
    INTERNAL_ACTIONS,
};
use crate::syntax::ast::*;
use crate::syntax::{Diagnostic, Span};

impl Checker<'_> {
    /// A logical formula.
    pub(super) fn formula(&mut self, cl: &mut Clause, e: &Expr, scope: Scope, usage: Usage) {
        match &e.kind {
            ExprKind::Literal(l) if matches!(l.functor.as_str(), ".add_plan" | ".remove_plan") => {
                self.unsupported(
                    e.span,
                    "changing the plan library in a formula",
                    "not a body step",
                )
            }
            ExprKind::Literal(l) if l.is_internal_action() => self.internal(cl, l, scope),
            ExprKind::Literal(l)
                if l.args.is_empty()
                    && !l.negated
                    && matches!(l.functor.as_str(), "true" | "false") => {}
            ExprKind::Literal(l) => self.belief_literal(cl, l, usage, scope),
            ExprKind::Var(_) => {
                self.unsupported(e.span, "a formula held in a variable", "variable")
            }
            ExprKind::Not(x) => self.formula(cl, x, scope, usage),
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                self.formula(cl, a, scope, usage);
                self.formula(cl, b, scope, usage);
            }
            ExprKind::Rel(op, a, b) => {
                self.term(cl, a, scope);
                self.term(cl, b, scope);
                if matches!(scope, Scope::Manifest { .. }) {
                    if *op == RelOp::Univ {
                        self.unsupported(e.span, "`=..` in a manifest formula", "here");
                    }
                    for x in [a, b] {
                        if let ExprKind::Literal(l) = &x.kind {
                            if is_atom(l) {
                                self.object_exists(&l.functor, x.span);
                            }
                        }
                    }
                }
            }
            ExprKind::PlanTerm(_) => {
                self.unsupported(e.span, "a plan term in a formula", "plan term")
            }
            _ => self.term(cl, e, scope),
        }
    }

    /// Reports an atom that is not an object (in a manifest comparison).
    fn object_exists(&mut self, name: &str, span: Span) {
        if self.universe.object(name).is_none() {
            self.diags.push(self.not_an_object(name, span));
        }
    }

    /// A term that is in no typed position: checks the functions and formulas inside it.
    pub(super) fn term(&mut self, cl: &mut Clause, e: &Expr, scope: Scope) {
        match &e.kind {
            ExprKind::Literal(l) if l.is_internal_action() => self.function(cl, l, scope),
            ExprKind::Literal(l) => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
            ExprKind::List(le) => {
                for a in &le.elems {
                    self.term(cl, a, scope);
                }
                if let Some(t) = &le.tail {
                    self.term(cl, t, scope);
                }
            }
            ExprKind::Unary(_, a) | ExprKind::Not(a) => self.term(cl, a, scope),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                self.term(cl, a, scope);
                self.term(cl, b, scope);
            }
            ExprKind::Var(_)
            | ExprKind::Int(_)
            | ExprKind::Float(_)
            | ExprKind::Str(_)
            | ExprKind::PlanTerm(_) => {}
        }
    }

    /// The event of `.wait({+b})`: a belief read, or a goal (checked when some plan knows
    /// it; waiting for a goal no plan handles is not an error in Jason).
    fn trigger_literal(&mut self, cl: &mut Clause, kind: TriggerKind, e: &Expr, scope: Scope) {
        let ExprKind::Literal(l) = &e.kind else {
            return;
        };
        match kind {
            TriggerKind::Belief => self.belief_literal(cl, l, Usage::Query, scope),
            _ if self
                .goal_ids
                .contains_key(&(l.functor.clone(), l.args.len())) =>
            {
                self.known_goal(cl, l, e.span, scope)
            }
            _ => l.args.iter().for_each(|a| self.term(cl, a, scope)),
        }
    }

    /// A dotted functor in a term: an arithmetic function.
    fn function(&mut self, cl: &mut Clause, l: &Literal, scope: Scope) {
        let name = l.functor.as_str();
        match (name, l.args.len()) {
            (".count", 1) => self.count_query(cl, &l.args[0], scope),
            (".length", 1) => self.term(cl, &l.args[0], scope),
            _ if arithmetic_function(name) => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
            _ => {
                let d = Diagnostic::error(
                    "input",
                    format!("`{name}` is not an arithmetic function modelled by bdi-check"),
                )
                .with_label(l.span, "in an expression")
                .with_help(
                    "functions: `.count(Query)`, `.length(List)` and `math.abs`, `math.max`, ... (Jason's `math` library, except `math.random`)",
                );
                self.diags.push(d);
            }
        }
    }

    fn count_query(&mut self, cl: &mut Clause, q: &Expr, scope: Scope) {
        if matches!(scope, Scope::Manifest { .. }) && !matches!(q.kind, ExprKind::Literal(_)) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    "the query of `.count` must be a literal such as `cupAt(C, _)`",
                )
                .with_label(q.span, "not a literal"),
            );
            return;
        }
        self.formula(cl, q, scope, Usage::Query);
    }

    /// An internal action as a body step or a formula.
    pub(super) fn internal(&mut self, cl: &mut Clause, l: &Literal, scope: Scope) {
        let name = l.functor.as_str();
        let n = l.args.len();
        if name.starts_with("math.") && arithmetic_function(name) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!("`{name}` is an arithmetic function, not an internal action"),
                )
                .with_label(l.span, "function")
                .with_help(format!(
                    "use it inside an expression, such as `X = {name}(Y)`"
                )),
            );
            return;
        }
        if !modelled_action(name) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!("internal action `{name}` is not modelled by bdi-check"),
                )
                .with_label(l.span, "unmodelled internal action")
                .with_help(format!(
                    "bdi-check models {}",
                    INTERNAL_ACTIONS
                        .iter()
                        .copied()
                        .chain(crate::model::internal::PURE.iter().map(|(n, _)| *n))
                        .map(|a| format!("`{a}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            );
            return;
        }
        if let Scope::Manifest { properties } = scope {
            let ok = name == ".count" || (properties && matches!(name, ".intend" | ".desire"));
            if !ok {
                let only = if matches!(name, ".intend" | ".desire") {
                    format!("`{name}` can only be used in a `[[property]]`")
                } else {
                    format!(
                        "`{name}` cannot be used in a manifest formula (only `.count`, and `.intend`/`.desire` in properties)"
                    )
                };
                self.diags
                    .push(Diagnostic::error("input", only).with_label(l.span, "here"));
                return;
            }
        }
        let pure = crate::model::internal::PURE
            .iter()
            .find(|(n, _)| *n == name);
        let arities: &[usize] = match name {
            ".print" | ".println" => &[],
            ".count" => &[2],
            ".findall" => &[3],
            ".drop_intention" => &[0, 1],
            ".add_plan" => &[1, 2, 3],
            ".remove_plan" => &[1, 2],
            ".send" => &[3, 4, 5],
            ".broadcast" => &[2],
            ".fail" => &[0],
            // The third (the time waited) is refused where the step is compiled.
            ".wait" => &[1, 2, 3],
            ".random" => &[1, 2, 3],
            _ if pure.is_some() => pure.map_or(&[], |(_, a)| a),
            _ => &[1],
        };
        if !arities.is_empty() && !arities.contains(&n) {
            let want: Vec<String> = arities.iter().map(|a| a.to_string()).collect();
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!(
                        "`{name}` takes {}, but {} given",
                        plural_or(&want, "argument"),
                        given(n)
                    ),
                )
                .with_label(l.span, "wrong number of arguments"),
            );
            return;
        }
        match name {
            ".count" => {
                self.count_query(cl, &l.args[0], scope);
                let out = &l.args[1];
                match &out.kind {
                    ExprKind::Var(v) => {
                        cl.counted.insert(v.name.clone());
                    }
                    ExprKind::Int(_) => {}
                    _ if matches!(scope, Scope::Manifest { .. }) => self.diags.push(
                        Diagnostic::error(
                            "input",
                            "the count of `.count(Query, N)` must be an integer or a variable",
                        )
                        .with_label(out.span, "expected an integer or a variable"),
                    ),
                    _ => self.term(cl, out, scope),
                }
            }
            ".findall" => {
                self.term(cl, &l.args[0], scope);
                self.formula(cl, &l.args[1], scope, Usage::Query);
                self.term(cl, &l.args[2], scope);
            }
            ".wait" => {
                for a in &l.args {
                    match &a.kind {
                        ExprKind::PlanTerm(pt) => {
                            if let Some((_, kind, e)) = crate::model::plans::wait_trigger(&pt.kind)
                            {
                                self.trigger_literal(cl, kind, e, scope)
                            }
                        }
                        ExprKind::Literal(_)
                        | ExprKind::Not(_)
                        | ExprKind::And(..)
                        | ExprKind::Or(..)
                        | ExprKind::Rel(..) => self.formula(cl, a, scope, Usage::Query),
                        _ => self.term(cl, a, scope),
                    }
                }
            }
            ".random" => {
                // `.random(List, X)` picks an element; `.random(X)` and `.random(X, N)` a
                // number in [0, 1), from the values the manifest lists.
                if !matches!(l.args[0].kind, ExprKind::List(_)) && !self.random {
                    self.diags.push(
                        Diagnostic::error(
                            "input",
                            "`.random(X)` gives any number in [0, 1): the model needs the values to check",
                        )
                        .with_label(l.span, "a random number")
                        .with_help("list them in the manifest: `[bounds] random = [0.0, 0.5, 0.9]`"),
                    );
                }
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
            ".abolish" => match &l.args[0].kind {
                // `.abolish(b)` deletes every belief that unifies with `b`.
                ExprKind::Literal(b) if !b.is_internal_action() => {
                    self.belief_literal(cl, b, Usage::Del, scope)
                }
                _ => self.diags.push(
                    Diagnostic::error("input", "`.abolish` expects a belief such as `seen(_)`")
                        .with_label(l.args[0].span, "not a belief literal"),
                ),
            },
            // The added plans are clauses of their own; the other arguments, and the labels
            // of `.remove_plan`, are read when the plans are compiled (`model::library`).
            ".add_plan" => {
                for p in super::declare::added_plans(&l.args[0]) {
                    self.plan(p, true);
                }
            }
            ".remove_plan" => {}
            ".send" | ".broadcast" => self.message(cl, l, scope),
            _ if GOAL_ACTIONS.contains(&name) => {
                if let Some(g) = l.args.first() {
                    match &g.kind {
                        ExprKind::Literal(gl) if !gl.is_internal_action() => {
                            self.known_goal(cl, gl, g.span, scope)
                        }
                        ExprKind::Var(_) if scope == Scope::Agent => {}
                        _ => self.diags.push(
                            Diagnostic::error(
                                "input",
                                format!("`{name}` expects a goal such as `storeCup(C)`"),
                            )
                            .with_label(g.span, "not a goal"),
                        ),
                    }
                }
            }
            _ => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
        }
    }

    /// `.send(Receiver, Performative, Content)` and `.broadcast(Performative, Content)`:
    /// the performatives bdi-check models, with their content checked as the step they
    /// stand for (`achieve g` as `!g`, `tell b` as `+b`, `untell b` as `-b`, `askOne b` as
    /// a query); an ask may have an answer variable and a timeout
    /// (`.send(R, askOne, b, Answer, Timeout)`). The other performatives are refused where
    /// written.
    fn message(&mut self, cl: &mut Clause, l: &Literal, scope: Scope) {
        let send = l.functor == ".send";
        let (ilf, content) = if send {
            (&l.args[1], &l.args[2])
        } else {
            (&l.args[0], &l.args[1])
        };
        if send {
            match &l.args[0].kind {
                ExprKind::Literal(r) if r.args.is_empty() && !r.is_internal_action() => {}
                ExprKind::Var(_) => {}
                _ => {
                    self.unsupported(
                        l.args[0].span,
                        "a receiver that is not an agent's name or a variable (a list, a string)",
                        "receiver",
                    );
                    return;
                }
            }
        }
        let performative = match &ilf.kind {
            ExprKind::Literal(p) if p.args.is_empty() && p.annots.is_none() => p.functor.as_str(),
            _ => {
                self.unsupported(
                    ilf.span,
                    "a performative that is not written out",
                    "performative",
                );
                return;
            }
        };
        let extra = if send { l.args.len() - 3 } else { 0 };
        fn literal(e: &Expr) -> Option<&Literal> {
            match &e.kind {
                ExprKind::Literal(b) if !b.is_internal_action() => Some(b),
                _ => None,
            }
        }
        match performative {
            "achieve" | "unachieve" if extra == 0 => match literal(content) {
                Some(g) => self.goal_literal(cl, g, super::Role::Use, scope),
                None => self.unsupported(
                    content.span,
                    &format!("`{performative}` of something other than a goal literal (a list, a variable)"),
                    "content",
                ),
            },
            "achieve" | "unachieve" => self.unsupported(
                l.span,
                &format!("`.send` of `{performative}` with a fourth or fifth argument"),
                "extra arguments",
            ),
            "tell" | "untell" if extra == 0 => match literal(content) {
                Some(b) => {
                    let usage = if performative == "tell" {
                        Usage::Add
                    } else {
                        Usage::Del
                    };
                    self.belief_literal(cl, b, usage, scope)
                }
                None => self.unsupported(
                    content.span,
                    &format!("`{performative}` of something other than a belief literal (a list, a variable)"),
                    "content",
                ),
            },
            "tell" | "untell" => self.unsupported(
                l.span,
                &format!("`.send` of `{performative}` in reply to a message (`in_reply_to`)"),
                "extra argument",
            ),
            "askOne" | "askAll" => {
                match literal(content) {
                    Some(b) => self.belief_literal(cl, b, Usage::Query, scope),
                    None => self.unsupported(
                        content.span,
                        &format!("`{performative}` of something other than a belief literal (a list, a variable)"),
                        "content",
                    ),
                }
                // The answer, and the timeout.
                for a in l.args.iter().skip(3) {
                    self.term(cl, a, scope);
                }
                if let Some(t) = l.args.get(4) {
                    if !matches!(t.kind, ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Var(_)) {
                        self.diags.push(
                            Diagnostic::error(
                                "input",
                                "the timeout of `.send` must be a number of milliseconds",
                            )
                            .with_label(t.span, "not a number"),
                        );
                    }
                }
            }
            // The told plans are clauses of their own; the labels and triggers are read
            // with the messages (`model::know_how`).
            "tellHow" if extra <= 1 => match crate::model::know_how::told_plans(content) {
                Ok(plans) => plans.iter().for_each(|(_, p)| self.plan(p, true)),
                Err(d) => self.diags.push(d),
            },
            "untellHow" if extra == 0 => {
                if let Err(d) = crate::model::know_how::untold_labels(content) {
                    self.diags.push(d);
                }
            }
            "askHow" if extra <= 1 => {
                if let Err(d) = crate::model::know_how::asked_trigger(content) {
                    self.diags.push(d);
                }
            }
            "tellHow" | "untellHow" | "askHow" => self.unsupported(
                l.span,
                &format!("`.send` of `{performative}` with these arguments"),
                "extra arguments",
            ),
            "signal" => self.unsupported(
                ilf.span,
                "the performative `signal` (bdi-check models achieve, tell, untell, unachieve, askOne, askAll, tellHow, untellHow and askHow)",
                "performative",
            ),
            other => self.diags.push(
                Diagnostic::error(
                    "input",
                    format!("the performative `{other}` is none of Jason's, and bdi-check does not model it"),
                )
                .with_label(ilf.span, "performative")
                .with_help("kqmlPlans.asl has no plan for it, so a receiver reports a communication error, unless the project's own `+!kqml_received` plans handle it; Jason's performatives: tell, untell, achieve, unachieve, askOne, askAll, tellHow, untellHow, askHow"),
            ),
        }
    }
}
