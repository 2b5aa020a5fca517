//! Logical and arithmetic expressions, one function per precedence level of Jason's grammar,
//! with long operator chains bounded in depth.

use super::{PResult, Parser, MAX_DEPTH};
use crate::syntax::ast::*;
use crate::syntax::lexer::Tok;

impl<'t> Parser<'t> {
    /// `log_expr`: `log_expr_trm [| log_expr]`.
    pub(super) fn log_expr(&mut self) -> PResult<Expr> {
        self.nested(|p| {
            let start = p.start();
            let lhs = p.log_trm()?;
            if p.eat(&Tok::Bar) {
                let rhs = p.log_expr()?;
                Ok(Expr {
                    kind: ExprKind::Or(Box::new(lhs), Box::new(rhs)),
                    span: p.span_from(start),
                })
            } else {
                Ok(lhs)
            }
        })
    }

    /// `log_expr_trm`: `log_expr_factor [& log_expr_trm]`.
    fn log_trm(&mut self) -> PResult<Expr> {
        let start = self.start();
        let lhs = self.log_factor()?;
        if self.eat(&Tok::Amp) {
            let rhs = self.nested(|p| p.log_trm())?;
            Ok(Expr {
                kind: ExprKind::And(Box::new(lhs), Box::new(rhs)),
                span: self.span_from(start),
            })
        } else {
            Ok(lhs)
        }
    }

    /// `log_expr_factor`: `[not] rel_expr`.
    fn log_factor(&mut self) -> PResult<Expr> {
        let start = self.start();
        if self.eat(&Tok::Not) {
            let e = self.rel_expr()?;
            Ok(Expr {
                kind: ExprKind::Not(Box::new(e)),
                span: self.span_from(start),
            })
        } else {
            self.rel_expr()
        }
    }

    /// `rel_expr`: `operand [relop operand]`.
    fn rel_expr(&mut self) -> PResult<Expr> {
        let start = self.start();
        let lhs = self.rel_operand()?;
        let op = match self.peek() {
            Tok::Lt => RelOp::Lt,
            Tok::Le => RelOp::Le,
            Tok::Gt => RelOp::Gt,
            Tok::Ge => RelOp::Ge,
            Tok::EqEq => RelOp::Eq,
            Tok::NotEqEq => RelOp::Ne,
            Tok::Eq => RelOp::Unify,
            Tok::Univ => RelOp::Univ,
            _ => return Ok(lhs),
        };
        self.bump();
        let rhs = self.rel_operand()?;
        Ok(Expr {
            kind: ExprKind::Rel(op, Box::new(lhs), Box::new(rhs)),
            span: self.span_from(start),
        })
    }

    /// An operand of a relation: `arithm_expr | string | list | rule_plan_term`.
    fn rel_operand(&mut self) -> PResult<Expr> {
        match self.peek() {
            Tok::Str(_) => Ok(self.string()),
            Tok::LBracket => self.list_expr(),
            Tok::LBrace => self.plan_term(),
            _ => self.arith_expr(),
        }
    }

    pub(super) fn string(&mut self) -> Expr {
        let t = self.bump();
        let s = match t.tok {
            Tok::Str(s) => s,
            _ => String::new(),
        };
        Expr {
            kind: ExprKind::Str(s),
            span: t.span,
        }
    }

    /// `arithm_expr`: terms joined by `+` and `-`, left-associative.
    pub(super) fn arith_expr(&mut self) -> PResult<Expr> {
        let saved = self.depth;
        let r = self.arith_expr_chain();
        self.depth = saved;
        r
    }

    /// Each link of a left-associative chain nests the tree one level deeper, so it counts
    /// against the nesting bound like a parenthesis does.
    fn deepen(&mut self) -> PResult<()> {
        if self.depth >= MAX_DEPTH {
            let span = self.span_here();
            return self.error_at(
                span,
                format!("expression nested deeper than {MAX_DEPTH} levels"),
                "too deeply nested",
            );
        }
        self.depth += 1;
        Ok(())
    }

    fn arith_expr_chain(&mut self) -> PResult<Expr> {
        let start = self.start();
        let mut lhs = self.arith_trm()?;
        loop {
            let op = match self.peek() {
                Tok::Plus => ArithOp::Add,
                Tok::Minus => ArithOp::Sub,
                _ => return Ok(lhs),
            };
            self.bump();
            self.deepen()?;
            let rhs = self.arith_trm()?;
            lhs = Expr {
                kind: ExprKind::Arith(op, Box::new(lhs), Box::new(rhs)),
                span: self.span_from(start),
            };
        }
    }

    /// `arithm_expr_trm`: factors joined by `* / div mod`, left-associative.
    fn arith_trm(&mut self) -> PResult<Expr> {
        let saved = self.depth;
        let r = self.arith_trm_chain();
        self.depth = saved;
        r
    }

    fn arith_trm_chain(&mut self) -> PResult<Expr> {
        let start = self.start();
        let mut lhs = self.arith_factor()?;
        loop {
            let op = match self.peek() {
                Tok::Star => ArithOp::Mul,
                Tok::Slash => ArithOp::Div,
                Tok::Div => ArithOp::IntDiv,
                Tok::Mod => ArithOp::Mod,
                _ => return Ok(lhs),
            };
            self.bump();
            self.deepen()?;
            let rhs = self.arith_factor()?;
            lhs = Expr {
                kind: ExprKind::Arith(op, Box::new(lhs), Box::new(rhs)),
                span: self.span_from(start),
            };
        }
    }

    /// `arithm_expr_factor`: `simple [** factor]`, right-associative.
    fn arith_factor(&mut self) -> PResult<Expr> {
        let start = self.start();
        let lhs = self.arith_simple()?;
        if self.eat(&Tok::Pow) {
            let rhs = self.nested(|p| p.arith_factor())?;
            Ok(Expr {
                kind: ExprKind::Arith(ArithOp::Pow, Box::new(lhs), Box::new(rhs)),
                span: self.span_from(start),
            })
        } else {
            Ok(lhs)
        }
    }

    /// `arithm_expr_simple`: `[+|-] (NUMBER | ( log_expr ) | function)`.
    fn arith_simple(&mut self) -> PResult<Expr> {
        let start = self.start();
        let sign = match self.peek() {
            Tok::Minus => Some(UnaryOp::Neg),
            Tok::Plus => Some(UnaryOp::Plus),
            _ => None,
        };
        if sign.is_some() {
            self.bump();
        }
        let e = match self.peek().clone() {
            Tok::Int(n) => Expr {
                kind: ExprKind::Int(n),
                span: self.bump().span,
            },
            Tok::Float(x) => Expr {
                kind: ExprKind::Float(x),
                span: self.bump().span,
            },
            Tok::LParen => {
                let open = self.bump().span.start;
                let mut e = self.log_expr()?;
                self.expect(&Tok::RParen, "`)`")?;
                // The parentheses belong to the expression's extent.
                e.span = self.span_from(open);
                e
            }
            _ if self.starts_literal() => self.literal()?,
            _ => return self.error_expected("a term"),
        };
        Ok(match sign {
            Some(op) => Expr {
                kind: ExprKind::Unary(op, Box::new(e)),
                span: self.span_from(start),
            },
            None => e,
        })
    }
}
