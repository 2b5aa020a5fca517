//! Literals and terms: namespaces, arguments, annotations and lists.

use super::{PResult, Parser};
use crate::syntax::ast::*;
use crate::syntax::lexer::Tok;

impl<'t> Parser<'t> {
    pub(super) fn starts_literal(&self) -> bool {
        matches!(
            self.peek(),
            Tok::Atom(_)
                | Tok::Begin
                | Tok::End
                | Tok::Var(_)
                | Tok::UnnamedVar(_)
                | Tok::Tilde
                | Tok::NsSep
                | Tok::True
                | Tok::False
        )
    }

    /// `literal`: `[ns::] [~] (pred | var) | true | false`.
    pub(super) fn literal(&mut self) -> PResult<Expr> {
        let start = self.start();
        if matches!(self.peek(), Tok::True | Tok::False) {
            let t = self.bump();
            let functor = if t.tok == Tok::True { "true" } else { "false" };
            return Ok(Expr {
                kind: ExprKind::Literal(Literal {
                    namespace: None,
                    negated: false,
                    functor: functor.into(),
                    args: Vec::new(),
                    annots: None,
                    span: t.span,
                }),
                span: t.span,
            });
        }
        let namespace = self.opt_namespace()?;
        let negated = self.eat(&Tok::Tilde);
        match self.peek().clone() {
            Tok::Var(name) | Tok::UnnamedVar(name) => {
                self.bump();
                let annots = self.opt_annots()?;
                let span = self.span_from(start);
                Ok(Expr {
                    kind: ExprKind::Var(Var {
                        namespace,
                        negated,
                        name,
                        annots,
                        span,
                    }),
                    span,
                })
            }
            Tok::Atom(_) | Tok::Begin | Tok::End => {
                let functor = match self.bump().tok {
                    Tok::Atom(a) => a,
                    Tok::Begin => "begin".into(),
                    _ => "end".into(),
                };
                let args = if self.eat(&Tok::LParen) {
                    let args = self.terms()?;
                    self.expect(&Tok::RParen, "`,` or `)` in the argument list")?;
                    args
                } else {
                    Vec::new()
                };
                let annots = self.opt_annots()?;
                let span = self.span_from(start);
                let lit = Literal {
                    namespace,
                    negated,
                    functor,
                    args,
                    annots,
                    span,
                };
                if lit.is_internal_action() && (lit.negated || lit.annots.is_some()) {
                    return self.error_at(
                        span,
                        format!(
                            "internal action `{}` cannot be negated or annotated",
                            lit.functor
                        ),
                        "internal action",
                    );
                }
                Ok(Expr {
                    kind: ExprKind::Literal(lit),
                    span,
                })
            }
            _ => self.error_expected("a literal"),
        }
    }

    /// `namespace`: `[ATOM | var] ::` (only when `::` follows).
    fn opt_namespace(&mut self) -> PResult<Option<Namespace>> {
        let start = self.start();
        let kind = match (self.peek().clone(), self.peek_at(1)) {
            (Tok::NsSep, _) => {
                self.bump();
                NamespaceKind::Current
            }
            (Tok::Atom(a), Tok::NsSep) => {
                self.bump();
                self.bump();
                NamespaceKind::Named(a)
            }
            (Tok::Var(v) | Tok::UnnamedVar(v), Tok::NsSep) => {
                self.bump();
                self.bump();
                NamespaceKind::Var(v)
            }
            _ => return Ok(None),
        };
        Ok(Some(Namespace {
            kind,
            span: self.span_from(start),
        }))
    }

    /// `terms`: `term (, term)*`, each a `log_expr`.
    pub(super) fn terms(&mut self) -> PResult<Vec<Expr>> {
        let mut v = vec![self.log_expr()?];
        while self.eat(&Tok::Comma) {
            v.push(self.log_expr()?);
        }
        Ok(v)
    }

    /// Optional annotations: a list right after a literal or variable.
    pub(super) fn opt_annots(&mut self) -> PResult<Option<ListExpr>> {
        if self.peek() == &Tok::LBracket {
            let l = self.list()?;
            Ok(non_empty(l))
        } else {
            Ok(None)
        }
    }

    pub(super) fn list_expr(&mut self) -> PResult<Expr> {
        let l = self.list()?;
        let span = l.span;
        Ok(Expr {
            kind: ExprKind::List(l),
            span,
        })
    }

    /// `list`: `[ [elem (, elem)*] [| (VAR | _ | list)] ]`.
    pub(super) fn list(&mut self) -> PResult<ListExpr> {
        self.nested(|p| {
            let start = p.start();
            p.expect(&Tok::LBracket, "`[`")?;
            let mut elems = Vec::new();
            if !matches!(p.peek(), Tok::RBracket | Tok::Bar) {
                elems.push(p.list_elem()?);
                while p.eat(&Tok::Comma) {
                    elems.push(p.list_elem()?);
                }
            }
            let tail = if p.eat(&Tok::Bar) {
                let t = match p.peek().clone() {
                    Tok::Var(name) | Tok::UnnamedVar(name) => {
                        let span = p.bump().span;
                        Expr {
                            kind: ExprKind::Var(Var {
                                namespace: None,
                                negated: false,
                                name,
                                annots: None,
                                span,
                            }),
                            span,
                        }
                    }
                    Tok::LBracket => p.list_expr()?,
                    _ => return p.error_expected("a variable or a list after `|`"),
                };
                Some(Box::new(t))
            } else {
                None
            };
            p.expect(&Tok::RBracket, "`,`, `|` or `]` in the list")?;
            Ok(ListExpr {
                elems,
                tail,
                span: p.span_from(start),
            })
        })
    }

    /// `term_in_list`: `list | arithm_expr | string | rule_plan_term`.
    fn list_elem(&mut self) -> PResult<Expr> {
        match self.peek() {
            Tok::LBracket => self.list_expr(),
            Tok::Str(_) => Ok(self.string()),
            Tok::LBrace => self.plan_term(),
            _ => self.arith_expr(),
        }
    }
}

/// `p[]` is `p`: an empty annotation list (with no tail) is no list.
pub(super) fn non_empty(l: ListExpr) -> Option<ListExpr> {
    (!l.elems.is_empty() || l.tail.is_some()).then_some(l)
}
