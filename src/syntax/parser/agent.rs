//! The productions of a whole file: its items (directives, initial goals, beliefs and rules,
//! plans), plan labels and triggers.

use super::term::non_empty;
use super::{PResult, Parser};
use crate::syntax::ast::*;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::lexer::Tok;
use crate::syntax::source::Span;

impl<'t> Parser<'t> {
    pub(super) fn items_until_eof(&mut self) -> Vec<Item> {
        let mut items = Vec::new();
        while self.peek() != &Tok::Eof && !self.too_many_errors() {
            let start = self.pos;
            match self.item() {
                Ok(item) => items.push(item),
                Err(()) => self.recover(start),
            }
        }
        items
    }

    /// `agent_component`: a directive, belief or rule, initial goal, or plan.
    fn item(&mut self) -> PResult<Item> {
        match self.peek() {
            Tok::LBrace => self.directive().map(Item::Directive),
            Tok::Bang => self.initial_goal().map(Item::InitialGoal),
            Tok::At | Tok::Plus | Tok::Minus | Tok::Caret => self.plan(true).map(Item::Plan),
            _ => self.belief_or_rule(),
        }
    }

    /// `directive`: `{ name(args)[annots] }` or `{ begin name(args) } items { end }`.
    fn directive(&mut self) -> PResult<Directive> {
        let start = self.start();
        self.expect(&Tok::LBrace, "`{`")?;
        let is_block = self.eat(&Tok::Begin);
        let (name, args, annots) = self.directive_arguments()?;
        self.expect(&Tok::RBrace, "`}` to close the directive")?;
        let block = if is_block {
            let mut items = Vec::new();
            loop {
                if self.peek() == &Tok::LBrace && self.peek_at(1) == &Tok::End {
                    self.bump();
                    self.bump();
                    self.expect(&Tok::RBrace, "`}` after `{ end`")?;
                    break;
                }
                if self.peek() == &Tok::Eof || self.too_many_errors() {
                    let span = Span::new(self.file, start as usize, start as usize + 1);
                    return self.error(
                        Diagnostic::syntax(
                            span,
                            format!("`{{ begin {name} }}` is never closed"),
                            "this block has no `{ end }`",
                        )
                        .with_help("close the block with `{ end }`"),
                    );
                }
                let item_start = self.pos;
                match self.nested(|p| p.item()) {
                    Ok(item) => items.push(item),
                    Err(()) => self.recover(item_start),
                }
            }
            Some(items)
        } else {
            None
        };
        Ok(Directive {
            name,
            args,
            annots,
            block,
            span: self.span_from(start),
        })
    }

    /// `directive_arguments`: `ATOM [( terms )] [list]`.
    fn directive_arguments(&mut self) -> PResult<(String, Vec<Expr>, Option<ListExpr>)> {
        let name = match self.peek().clone() {
            Tok::Atom(a) => {
                self.bump();
                a
            }
            _ => return self.error_expected("a directive name such as `include`"),
        };
        let args = if self.eat(&Tok::LParen) {
            let args = self.terms()?;
            self.expect(&Tok::RParen, "`)` to close the directive's arguments")?;
            args
        } else {
            Vec::new()
        };
        let annots = self.opt_annots()?;
        Ok((name, args, annots))
    }

    /// `initial_goal`: `! literal .`
    fn initial_goal(&mut self) -> PResult<InitialGoal> {
        let start = self.start();
        self.expect(&Tok::Bang, "`!`")?;
        let lit = self.literal()?;
        let literal = match lit.kind {
            ExprKind::Literal(l) => l,
            _ => {
                return self.error_at(lit.span, "a variable cannot be an initial goal", "variable")
            }
        };
        self.expect(&Tok::Dot, "`.` to end the initial goal")?;
        Ok(InitialGoal {
            literal,
            span: self.span_from(start),
        })
    }

    /// `belief`: `literal [:- log_expr] .`
    fn belief_or_rule(&mut self) -> PResult<Item> {
        let start = self.start();
        if !self.starts_literal() {
            return self.error_expected("a belief, rule, initial goal, plan or directive");
        }
        let lit = self.literal()?;
        let head = match lit.kind {
            ExprKind::Literal(l) => l,
            _ => return self.error_at(lit.span, "a variable cannot be a belief", "variable"),
        };
        if self.eat(&Tok::RuleSep) {
            let body = self.log_expr()?;
            self.expect(&Tok::Dot, "`.` to end the rule")?;
            Ok(Item::Rule(Rule {
                head,
                body,
                span: self.span_from(start),
            }))
        } else {
            if self.peek() != &Tok::Dot {
                return self.error_expected("`.` to end the belief, or `:-` to start a rule");
            }
            self.bump();
            Ok(Item::Belief(Belief {
                literal: head,
                span: self.span_from(start),
            }))
        }
    }

    /// `plan`: `[@label] trigger [: ctx] [<: cond] [<- body] . [{ plans }]`.
    fn plan(&mut self, top_level: bool) -> PResult<Plan> {
        let start = self.start();
        let label = if self.peek() == &Tok::At {
            Some(self.label(false)?)
        } else {
            None
        };
        let trigger = self.trigger()?;
        let context = if self.eat(&Tok::Colon) {
            Some(self.log_expr()?)
        } else {
            None
        };
        let goal_condition = if self.eat(&Tok::GoalCond) {
            Some(self.log_expr()?)
        } else {
            None
        };
        let body = if self.eat(&Tok::LeftArrow) {
            Some(self.plan_body()?)
        } else {
            None
        };
        if self.peek() != &Tok::Dot {
            let what = match (&context, &body) {
                (_, Some(_)) => "`;` or `.` to end the plan",
                (Some(_), None) => "`<-` or `.` after the plan's context",
                (None, None) => "`:`, `<-` or `.` after the trigger",
            };
            return self.error_expected(what);
        }
        self.bump();
        let mut sub_plans = Vec::new();
        if top_level
            && self.peek() == &Tok::LBrace
            && matches!(
                self.peek_at(1),
                Tok::At | Tok::Plus | Tok::Minus | Tok::Caret
            )
        {
            self.bump();
            while self.peek() != &Tok::RBrace {
                if self.peek() == &Tok::Eof {
                    return self.error_expected("`}` to close the sub-plans");
                }
                sub_plans.push(self.nested(|p| p.plan(true))?);
            }
            self.bump();
        }
        Ok(Plan {
            label,
            trigger,
            context,
            goal_condition,
            body,
            sub_plans,
            span: self.span_from(start),
        })
    }

    /// `plan_annotation` (and `plan_term_annotation` when `allow_var`).
    pub(super) fn label(&mut self, allow_var: bool) -> PResult<Label> {
        let start = self.start();
        self.expect(&Tok::At, "`@`")?;
        let name = match self.peek().clone() {
            Tok::Atom(a) => Some(a),
            Tok::Begin => Some("begin".to_string()),
            Tok::End => Some("end".to_string()),
            Tok::Var(v) | Tok::UnnamedVar(v) if allow_var => Some(v),
            Tok::LBracket => None,
            _ => return self.error_expected("a plan label name or `[`"),
        };
        if name.is_some() {
            self.bump();
        }
        let annots = if name.is_none() {
            let l = self.list()?;
            non_empty(l)
        } else {
            self.opt_annots()?
        };
        Ok(Label {
            name,
            annots,
            span: self.span_from(start),
        })
    }

    /// `trigger`: `(+|-|^) [!|?] literal`.
    pub(super) fn trigger(&mut self) -> PResult<Trigger> {
        let start = self.start();
        let op = match self.peek() {
            Tok::Plus => TriggerOp::Add,
            Tok::Minus => TriggerOp::Del,
            Tok::Caret => TriggerOp::GoalState,
            _ => return self.error_expected("a trigger (`+`, `-` or `^`)"),
        };
        self.bump();
        let kind = match self.peek() {
            Tok::Bang => {
                self.bump();
                TriggerKind::Achieve
            }
            Tok::Question => {
                self.bump();
                TriggerKind::Test
            }
            _ => TriggerKind::Belief,
        };
        if !self.starts_literal() {
            return self.error_expected("the trigger's literal");
        }
        let literal = self.literal()?;
        Ok(Trigger {
            op,
            kind,
            literal,
            span: self.span_from(start),
        })
    }
}
