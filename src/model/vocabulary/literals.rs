//! Belief literals and typed arguments: a literal read or updated as a belief is resolved to
//! a PDDL predicate, a mental note or a rule (refusing what the model cannot represent), and
//! its arguments are recorded as typed occurrences for inference.

use super::diagnostics::{count, given, plural_or, suggest};
use super::{Arg, Checker, Clause, Occ, Role, RuleInfo, Scope, Sig, UndefinedAction, Usage};
use crate::syntax::ast::*;
use crate::syntax::Diagnostic;

impl Checker<'_> {
    /// A literal read as a belief: a PDDL predicate, a mental note or a rule.
    pub(super) fn belief_literal(
        &mut self,
        cl: &mut Clause,
        l: &Literal,
        usage: Usage,
        scope: Scope,
    ) {
        let belief_name = l.belief_name();
        let name = belief_name.as_ref();
        let arity = l.args.len();
        // `~p` of a PDDL predicate is checked (and refused) against `p` itself.
        let env_positive = l
            .negated
            .then(|| self.pred_ids.get(&l.functor).copied())
            .flatten()
            .filter(|&p| self.preds[p].env);
        if let Some(p) = env_positive.or_else(|| self.pred_ids.get(name).copied()) {
            let info = self.preds[p].clone();
            if info.env {
                if matches!(usage, Usage::Add | Usage::Replace | Usage::Del) {
                    let op = match usage {
                        Usage::Add => "add",
                        Usage::Replace => "replace",
                        _ => "delete",
                    };
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "a plan cannot {op} `{name}`: it is an environment predicate, whose atoms change only through actions and perception in this model"
                        ),
                    )
                    .with_label(l.span, "belief update on an environment atom")
                    .with_secondary(info.span, "declared in PDDL here")
                    .with_help("call a PDDL action whose effect changes it, or use a mental note with a name of its own");
                    self.diags.push(d);
                    return;
                }
                if l.negated {
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "strong negation `~{}` of an environment predicate: the environment is closed-world, an atom that is not true is false",
                            l.functor
                        ),
                    )
                    .with_label(l.span, "strong negation")
                    .with_help(format!("write `not {}`", self.map.slice(l.span).trim_start_matches('~')));
                    self.diags.push(d);
                    return;
                }
            }
            if arity != info.arity {
                let (kind, at) = if info.env {
                    ("declared in PDDL here", info.span)
                } else {
                    ("first added here", info.span)
                };
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "`{name}` takes {}, but {} given",
                        count(info.arity, "argument"),
                        given(arity)
                    ),
                )
                .with_label(
                    l.span,
                    format!("expected {}", count(info.arity, "argument")),
                )
                .with_secondary(at, kind);
                self.diags.push(d);
                return;
            }
            let role = if matches!(usage, Usage::Add | Usage::Replace) {
                Role::Define
            } else {
                Role::Use
            };
            for (i, a) in l.args.iter().enumerate() {
                self.strict_arg(cl, a, Sig::Pred(p), i, role);
            }
            return;
        }
        if matches!(usage, Usage::Query | Usage::Test | Usage::Trigger) {
            if let Some(&r) = self.rule_ids.get(&(name.to_string(), arity)) {
                for (i, a) in l.args.iter().enumerate() {
                    self.loose_arg(cl, a, Sig::Rule(r), i, Role::Use, scope);
                }
                return;
            }
            let others: Vec<&RuleInfo> = self.rules.iter().filter(|r| r.name == name).collect();
            if let Some(r) = others.first() {
                let arities: Vec<String> = others.iter().map(|r| r.arity.to_string()).collect();
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "the rule `{name}` takes {}, but {} given",
                        plural_or(&arities, "argument"),
                        given(arity)
                    ),
                )
                .with_label(l.span, "wrong number of arguments")
                .with_secondary(r.span, "the rule's head");
                self.diags.push(d);
                return;
            }
        }
        if usage == Usage::Test && self.test_goals.contains(name) {
            for a in &l.args {
                self.term(cl, a, scope);
            }
            return;
        }
        // Unknown. A test goal on it just fails in Jason: a lint finding.
        if usage == Usage::Test && scope == Scope::Agent {
            self.undefined_tests.push(UndefinedAction {
                name: name.to_string(),
                arity,
                span: l.span,
            });
            for a in &l.args {
                self.term(cl, a, scope);
            }
            return;
        }
        let mut names: Vec<&str> = self.preds.iter().map(|p| p.name.as_str()).collect();
        if usage != Usage::Fact {
            names.extend(self.rules.iter().map(|r| r.name.as_str()));
        }
        let hint = suggest(name, names.iter().copied())
            .map(|s| format!("; did you mean `{s}`?"))
            .unwrap_or_default();
        let what = match usage {
            Usage::Fact => "a fact must be an atom of a PDDL predicate or of a mental note",
            Usage::Del => "only PDDL predicates and mental notes (beliefs the plans add) can be deleted",
            _ => "known predicates are the PDDL domain's, the mental notes the plans add (`+b`) or the initial beliefs, and the heads of rules",
        };
        let d = Diagnostic::error("input", format!("unknown predicate `{name}`{hint}"))
            .with_label(l.span, "unknown predicate")
            .with_help(what);
        self.diags.push(d);
    }

    /// Records a variable or object argument as a typed occurrence (`_` is typed by
    /// nothing); returns false for any other argument.
    fn typed_arg(cl: &mut Clause, a: &Expr, sig: Sig, index: usize, role: Role) -> bool {
        let arg = match &a.kind {
            ExprKind::Var(v) if !v.negated && v.annots.is_none() => {
                if v.name == "_" {
                    return true;
                }
                Arg::Var(v.name.clone())
            }
            ExprKind::Literal(l) if is_atom(l) => Arg::Const(l.functor.clone()),
            _ => return false,
        };
        cl.occs.push(Occ {
            arg,
            span: a.span,
            sig,
            index,
            role,
        });
        true
    }

    /// An argument of a PDDL predicate, PDDL action or mental note: a variable or an object
    /// (an integer, with `[bounds] numbers`; arithmetic then too, untyped: it is checked
    /// against the numbers when it runs).
    pub(super) fn strict_arg(
        &mut self,
        cl: &mut Clause,
        a: &Expr,
        sig: Sig,
        index: usize,
        role: Role,
    ) {
        if self.numbers {
            let int = match &a.kind {
                ExprKind::Int(i) => Some(i.to_string()),
                ExprKind::Unary(crate::syntax::ast::UnaryOp::Neg, x) => match &x.kind {
                    ExprKind::Int(i) => Some(format!("-{i}")),
                    _ => None,
                },
                _ => None,
            };
            if let Some(name) = int {
                cl.occs.push(Occ {
                    arg: Arg::Const(name),
                    span: a.span,
                    sig,
                    index,
                    role,
                });
                return;
            }
            if matches!(a.kind, ExprKind::Arith(..) | ExprKind::Unary(..)) {
                self.term(cl, a, Scope::Agent);
                return;
            }
        }
        if !Self::typed_arg(cl, a, sig, index, role) {
            let what = match &a.kind {
                ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Unary(..) => "a number",
                ExprKind::Str(_) => "a string",
                ExprKind::List(_) => "a list",
                ExprKind::Arith(..) => "an arithmetic expression",
                _ => "a structured term",
            };
            let d = Diagnostic::error(
                "input",
                format!(
                    "{what} cannot be an argument of `{}`: the model's state is a set of ground atoms over objects, so arguments must be objects or variables",
                    self.sig_name(sig)
                ),
            )
            .with_label(a.span, format!("{what}, not an object"))
            .with_help(if what == "a number" || what == "an arithmetic expression" {
                "declare the integers mental notes may hold, such as `[bounds] numbers = [0, 10]`"
            } else {
                "strings, lists and structured terms are not supported as arguments of predicates, actions and mental notes"
            });
            self.diags.push(d);
        }
    }

    /// An argument of a goal or a rule: a variable or an object is typed; anything else is
    /// allowed and not typed.
    pub(super) fn loose_arg(
        &mut self,
        cl: &mut Clause,
        a: &Expr,
        sig: Sig,
        index: usize,
        role: Role,
        scope: Scope,
    ) {
        if !Self::typed_arg(cl, a, sig, index, role) {
            self.term(cl, a, scope);
        }
    }
}

/// Whether a literal is a plain atom that can name an object.
pub(super) fn is_atom(l: &Literal) -> bool {
    l.args.is_empty()
        && l.annots.is_none()
        && !l.negated
        && !l.is_internal_action()
        && !matches!(l.functor.as_str(), "true" | "false")
}
