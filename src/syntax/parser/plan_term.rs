//! Plan terms `{ ... }`: a plan, a trigger, a rule or a body, told apart as Jason's
//! `rule_plan_term` does, and memoised by position since speculative parses revisit them.

use super::{PResult, Parser, MAX_ERRORS};
use crate::syntax::ast::*;
use crate::syntax::lexer::Tok;

impl<'t> Parser<'t> {
    /// Whether `{` opens a plan or trigger (Jason's `LOOKAHEAD(2)` in `rule_plan_term`).
    fn plan_term_starts_trigger(&self) -> bool {
        match self.peek() {
            Tok::At => true,
            Tok::Plus | Tok::Minus | Tok::Caret => matches!(
                self.peek_at(1),
                Tok::Bang
                    | Tok::Question
                    | Tok::Atom(_)
                    | Tok::Begin
                    | Tok::End
                    | Tok::Var(_)
                    | Tok::UnnamedVar(_)
                    | Tok::Tilde
                    | Tok::NsSep
                    | Tok::True
                    | Tok::False
            ),
            _ => false,
        }
    }

    /// `rule_plan_term`: `{ plan }`, `{ trigger }`, `{ body }`, `{ head :- body }`.
    ///
    /// A plan term parses the same wherever it is met, so its result (errors included) is
    /// remembered by position; speculative parses of enclosing groups then cost nothing twice.
    pub(super) fn plan_term(&mut self) -> PResult<Expr> {
        let at = self.pos;
        if let Some((r, pos, end, errs)) = self.plan_terms.get(&at).cloned() {
            self.pos = pos;
            self.prev_end = end;
            for e in errs {
                if self.errors.len() < MAX_ERRORS {
                    self.errors.push(e);
                }
            }
            return r;
        }
        let first_error = self.errors.len();
        let r = self.plan_term_uncached();
        let errs = self.errors.get(first_error..).unwrap_or_default().to_vec();
        self.plan_terms
            .insert(at, (r.clone(), self.pos, self.prev_end, errs));
        r
    }

    fn plan_term_uncached(&mut self) -> PResult<Expr> {
        self.nested(|p| {
            let start = p.start();
            p.expect(&Tok::LBrace, "`{`")?;
            let kind = if p.plan_term_starts_trigger() {
                let plan_start = p.start();
                let label = if p.peek() == &Tok::At {
                    Some(p.label(true)?)
                } else {
                    None
                };
                let trigger = p.trigger()?;
                let context = if p.eat(&Tok::Colon) {
                    Some(p.log_expr()?)
                } else {
                    None
                };
                // Jason: `;` may follow only a plain belief trigger (the term is then a
                // body); `<-` always makes a plan.
                let may_be_body = label.is_none()
                    && context.is_none()
                    && trigger.kind == TriggerKind::Belief
                    && trigger.op != TriggerOp::GoalState;
                let mut arrow = false;
                let body = if p.peek() == &Tok::Semi {
                    if !may_be_body {
                        let span = p.span_here();
                        return p.error_at(
                            span,
                            "wrong place for `;`: a plan term with a label, a context or a goal trigger separates its body with `<-`",
                            "expected `<-`",
                        );
                    }
                    p.bump();
                    if p.peek() == &Tok::RBrace {
                        None
                    } else {
                        Some(p.plan_body()?)
                    }
                } else if p.eat(&Tok::LeftArrow) {
                    arrow = true;
                    Some(p.plan_body()?)
                } else {
                    None
                };
                let only_body = may_be_body && !arrow;
                if only_body {
                    // Jason: `{ +b; c }` is the body `+b; c`.
                    let first = Step {
                        span: trigger.span,
                        kind: if trigger.op == TriggerOp::Add {
                            StepKind::AddBel(trigger.literal)
                        } else {
                            StepKind::DelBel(trigger.literal)
                        },
                    };
                    let mut steps = vec![first];
                    if let Some(b) = body {
                        steps.extend(b.steps);
                    }
                    PlanTermKind::Body(Body {
                        steps,
                        span: p.span_from(plan_start),
                    })
                } else if label.is_none() && context.is_none() && body.is_none() {
                    PlanTermKind::Trigger(trigger)
                } else {
                    PlanTermKind::Plan(Plan {
                        label,
                        trigger,
                        context,
                        goal_condition: None,
                        body,
                        sub_plans: Vec::new(),
                        span: p.span_from(plan_start),
                    })
                }
            } else if p.peek() == &Tok::RBrace {
                let here = p.span_here().shrink_to_start();
                PlanTermKind::Body(Body {
                    steps: Vec::new(),
                    span: here,
                })
            } else {
                let body = p.plan_body()?;
                if p.peek() == &Tok::RuleSep {
                    let sep = p.bump().span;
                    let rule_body = p.log_expr()?;
                    let mut steps = body.steps;
                    let head = match (steps.len(), steps.pop()) {
                        (
                            1,
                            Some(Step {
                                kind:
                                    StepKind::Action(Expr {
                                        kind: ExprKind::Literal(l),
                                        ..
                                    }),
                                ..
                            }),
                        ) => l,
                        _ => {
                            return p.error_at(
                                sep,
                                "a rule in braces needs a single literal before `:-`",
                                "wrong place for a rule",
                            )
                        }
                    };
                    PlanTermKind::Rule(Rule {
                        head,
                        body: rule_body,
                        span: p.span_from(body.span.start),
                    })
                } else {
                    PlanTermKind::Body(body)
                }
            };
            p.expect(&Tok::RBrace, "`}` to close the plan term")?;
            let span = p.span_from(start);
            Ok(Expr {
                kind: ExprKind::PlanTerm(Box::new(PlanTerm { kind, span })),
                span,
            })
        })
    }
}
