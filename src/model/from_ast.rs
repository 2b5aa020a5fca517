//! From the syntax tree to model terms.
//!
//! Terms of the AST (literals, variables, numbers, strings, lists) become [`Term`]s. Each `_`
//! becomes a new anonymous variable (`_1`, `_2`, ...): use one [`Converter`] for everything
//! that must not share anonymous variables (a whole agent, or at least a whole plan, whose
//! trigger, context and body are converted separately).
//!
//! Jason evaluates arithmetic when a term is used, so a ground arithmetic expression
//! (`-1`, `2*3`, `10 div 4`) is the number it evaluates to, computed here with Jason's
//! operators (`/` on doubles, `div` on Java `int`s, `mod` as Java's `%` on doubles, `**` as
//! `Math.pow`). Everything else is not a term of the model and is an error the caller
//! reports at the expression's span ([`ConvertError`]): arithmetic with variables
//! (evaluated at run time), relational and logical formulas, and constructs the model does
//! not cover (namespaces other than `default`, variables with `~` or annotations, annotation
//! lists with a tail, plan terms). Arithmetic functions such as `math.abs(-3)` are kept as
//! literals, not evaluated.

use super::term::{Num, Term, Var};
use crate::syntax::ast::{ArithOp, Expr, ExprKind, ListExpr, Literal, NamespaceKind, UnaryOp};
use crate::syntax::Span;
use std::fmt;

/// Why an expression is not a term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConvertErrorKind {
    /// A relational or logical formula, or a plan term: meaningful, but not a term.
    NotATerm,
    /// Arithmetic with variables: evaluated when the plan runs, so not a term here.
    NonConstantArith,
    /// Ground arithmetic that has no finite value (division by zero, overflow).
    ArithError,
    /// A construct the model does not support (namespaces, annotated variables, ...).
    Unsupported,
}

/// An expression that cannot be converted, with where it is and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConvertError {
    /// The offending (sub)expression.
    pub span: Span,
    /// What kind of problem it is, for callers that treat some kinds specially.
    pub kind: ConvertErrorKind,
    /// A message for the user.
    pub message: String,
}

impl ConvertError {
    fn new(span: Span, kind: ConvertErrorKind, message: impl Into<String>) -> ConvertError {
        ConvertError {
            span,
            kind,
            message: message.into(),
        }
    }
}

impl fmt::Display for ConvertError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ConvertError {}

/// Converts expressions to terms, numbering anonymous variables across all its calls.
#[derive(Clone, Debug, Default)]
pub struct Converter {
    /// The number of anonymous variables created so far.
    anon: u32,
    /// Whether arithmetic with variables is kept as an operator structure (`+(N, 1)`),
    /// to be evaluated when the plan runs, instead of refused.
    keep_arith: bool,
}

impl Converter {
    /// A converter whose first anonymous variable will be `_1`.
    pub fn new() -> Converter {
        Converter::default()
    }

    /// A converter for plan bodies: arithmetic with variables, anywhere in a term, is
    /// kept as a structure whose functor is the operator (`!count(N - 1)`).
    pub fn for_plans() -> Converter {
        Converter {
            keep_arith: true,
            ..Converter::default()
        }
    }

    /// A new anonymous variable, as for one `_` of the source.
    pub fn fresh_anonymous(&mut self) -> Var {
        self.anon += 1;
        Var::anonymous(self.anon)
    }

    /// The term an expression denotes; see the module documentation for what is refused.
    pub fn term(&mut self, e: &Expr) -> Result<Term, ConvertError> {
        match &e.kind {
            ExprKind::Literal(l) => self.literal(l),
            ExprKind::Var(v) => {
                if v.namespace.is_some() || v.negated || v.annots.is_some() {
                    return Err(ConvertError::new(
                        e.span,
                        ConvertErrorKind::Unsupported,
                        format!(
                            "variable `{}` with a namespace, `~` or annotations is not supported",
                            v.name
                        ),
                    ));
                }
                Ok(self.var(&v.name))
            }
            ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Unary(..) | ExprKind::Arith(..) => {
                match self.number(e) {
                    Err(err)
                        if self.keep_arith && err.kind == ConvertErrorKind::NonConstantArith =>
                    {
                        match &e.kind {
                            ExprKind::Arith(op, a, b) => Ok(Term::structure(
                                op.symbol(),
                                vec![self.term(a)?, self.term(b)?],
                            )),
                            ExprKind::Unary(crate::syntax::ast::UnaryOp::Neg, a) => {
                                Ok(Term::structure("-", vec![self.term(a)?]))
                            }
                            ExprKind::Unary(_, a) => self.term(a),
                            _ => Err(err),
                        }
                    }
                    r => r.map(Term::Num),
                }
            }
            ExprKind::Str(s) => Ok(Term::string(s)),
            ExprKind::List(l) => self.list(l),
            ExprKind::Rel(op, ..) => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::NotATerm,
                format!(
                    "a relational expression (`{}`) is a formula, not a term",
                    op.symbol()
                ),
            )),
            ExprKind::Not(_) | ExprKind::And(..) | ExprKind::Or(..) => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::NotATerm,
                "a logical formula (`not`, `&`, `|`) is not a term",
            )),
            ExprKind::PlanTerm(_) => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::Unsupported,
                "plan terms `{ ... }` are not supported by the model",
            )),
        }
    }

    /// The term of a literal: `[~]functor(args)[annots]`, an atom when it has none of them.
    pub fn literal(&mut self, l: &Literal) -> Result<Term, ConvertError> {
        match &l.namespace {
            None => {}
            // Jason's default namespace prints and behaves as no namespace.
            Some(ns) if ns.kind == NamespaceKind::Named("default".into()) => {}
            Some(ns) => {
                return Err(ConvertError::new(
                    ns.span,
                    ConvertErrorKind::Unsupported,
                    "namespaces are not supported by the model",
                ))
            }
        }
        let args = l
            .args
            .iter()
            .map(|a| self.term(a))
            .collect::<Result<Vec<_>, _>>()?;
        let annots = match &l.annots {
            None => Vec::new(),
            Some(list) => {
                if let Some(tail) = &list.tail {
                    return Err(ConvertError::new(
                        tail.span,
                        ConvertErrorKind::Unsupported,
                        "an annotation list with a tail (`[a|T]`) is not supported",
                    ));
                }
                list.elems
                    .iter()
                    .map(|a| self.term(a))
                    .collect::<Result<Vec<_>, _>>()?
            }
        };
        Ok(Term::literal(&l.functor, l.negated, args, annots))
    }

    /// The term of a list `[e1,...,en|tail]`.
    pub fn list(&mut self, l: &ListExpr) -> Result<Term, ConvertError> {
        let elems = l
            .elems
            .iter()
            .map(|e| self.term(e))
            .collect::<Result<Vec<_>, _>>()?;
        let tail = match &l.tail {
            None => Term::Nil,
            Some(t) => self.term(t)?,
        };
        Ok(Term::list_with_tail(elems, tail))
    }

    fn var(&mut self, name: &str) -> Term {
        if name == "_" {
            Term::Var(self.fresh_anonymous())
        } else {
            Term::var(name)
        }
    }

    /// The value of a ground arithmetic expression.
    fn number(&mut self, e: &Expr) -> Result<Num, ConvertError> {
        let v = self.eval(e)?;
        match Num::new(v) {
            Some(n) if v.is_finite() => Ok(n),
            _ => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::ArithError,
                "this arithmetic expression has no finite value",
            )),
        }
    }

    fn eval(&mut self, e: &Expr) -> Result<f64, ConvertError> {
        let arith_error = |msg: &str| ConvertError::new(e.span, ConvertErrorKind::ArithError, msg);
        match &e.kind {
            ExprKind::Int(i) => Ok(*i as f64),
            ExprKind::Float(x) => Ok(*x),
            ExprKind::Unary(UnaryOp::Neg, x) => Ok(-self.eval(x)?),
            ExprKind::Unary(UnaryOp::Plus, x) => self.eval(x),
            ExprKind::Arith(op, x, y) => {
                let (x, y) = (self.eval(x)?, self.eval(y)?);
                match crate::model::arith::apply(op.symbol(), &[x, y]) {
                    Some(Ok(v)) => Ok(v),
                    Some(Err(crate::model::arith::ArithError::DivisionByZero)) => {
                        Err(arith_error("integer division by zero"))
                    }
                    Some(Err(_)) if y == 0.0 => Err(arith_error(match op {
                        ArithOp::Mod => "modulo by zero",
                        _ => "division by zero",
                    })),
                    _ => Err(arith_error(
                        "this arithmetic expression has no finite value",
                    )),
                }
            }
            ExprKind::Var(_) => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::NonConstantArith,
                "arithmetic with variables is evaluated when the plan runs; it is not a term",
            )),
            _ => Err(ConvertError::new(
                e.span,
                ConvertErrorKind::NonConstantArith,
                "only numbers can be operands of arithmetic in a term",
            )),
        }
    }
}

/// The term of one expression, with a converter of its own (anonymous variables numbered
/// from `_1`); see [`Converter`] to convert several expressions that must not share them.
pub fn term_from_expr(e: &Expr) -> Result<Term, ConvertError> {
    Converter::new().term(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::{parse_expr, FileId};

    fn conv(src: &str) -> Result<Term, ConvertError> {
        let e = parse_expr(FileId(0), src).unwrap_or_else(|d| panic!("{src}: {d:?}"));
        term_from_expr(&e)
    }

    fn show(src: &str) -> String {
        conv(src)
            .unwrap_or_else(|e| panic!("{src}: {e}"))
            .to_string()
    }

    #[test]
    fn literals_print_back() {
        assert_eq!(show("cupAt(cup1, table)"), "cupAt(cup1,table)");
        assert_eq!(show("~at( home )"), "~at(home)");
        assert_eq!(show("p(a)[x, source(self)]"), "p(a)[source(self),x]");
        assert_eq!(show(".print(\"hi\", X)"), ".print(\"hi\",X)");
        assert_eq!(show("'a b'(c)"), "'a b'(c)");
        assert_eq!(show("true"), "true");
        assert_eq!(show("default::p(a)"), "p(a)");
    }

    #[test]
    fn lists_and_strings() {
        assert_eq!(show("[a, b | T]"), "[a,b|T]");
        assert_eq!(show("[a, [b, c]]"), "[a,[b,c]]");
        assert_eq!(show("[]"), "[]");
        assert_eq!(show("[H|[b]]"), "[H,b]");
        assert_eq!(show("\"say \\\"hi\\\"\""), "\"say \\\"hi\\\"\"");
    }

    #[test]
    fn numbers_and_constant_arithmetic() {
        assert_eq!(show("p(-2)"), "p(-2)");
        assert_eq!(show("p(1.5, 3.0, -0.0)"), "p(1.5,3,0)");
        assert_eq!(show("2 * 3 + 1"), "7");
        assert_eq!(show("7 / 2"), "3.5");
        assert_eq!(show("7 div 2"), "3");
        assert_eq!(show("-7 div 2"), "-3");
        assert_eq!(show("-7 mod 3"), "-1");
        assert_eq!(show("2 ** 10"), "1024");
        assert_eq!(show("p(+(3))"), "p(3)");
    }

    #[test]
    fn anonymous_variables_are_fresh() {
        let t = conv("p(_, _, _X, X)").unwrap();
        assert_eq!(t.to_string(), "p(_1,_2,_X,X)");
        assert_eq!(t.vars().len(), 4);
        let mut c = Converter::new();
        let e = parse_expr(FileId(0), "q(_)").unwrap();
        let first = c.term(&e).unwrap();
        let second = c.term(&e).unwrap();
        assert_ne!(first, second);
        assert_eq!(second.to_string(), "q(_2)");
        // A variable the programmer named `_1` is not the anonymous `_1`.
        let t = conv("p(_, _1)").unwrap();
        assert_eq!(t.vars().len(), 2);
    }

    #[test]
    fn errors_carry_span_and_kind() {
        let src = "p(X + 1)";
        let err = conv(src).unwrap_err();
        assert_eq!(err.kind, ConvertErrorKind::NonConstantArith);
        assert_eq!(&src[err.span.start as usize..err.span.end as usize], "X");
        let err = conv("p(1 / 0)").unwrap_err();
        assert_eq!(err.kind, ConvertErrorKind::ArithError);
        assert_eq!(err.span.start, 2);
        assert_eq!(err.span.end, 7);
        assert_eq!(
            conv("p(1 div 0)").unwrap_err().kind,
            ConvertErrorKind::ArithError
        );
        assert_eq!(
            conv("p(3 mod 0)").unwrap_err().kind,
            ConvertErrorKind::ArithError
        );
        assert_eq!(
            conv("p(10.0 ** 400)").unwrap_err().kind,
            ConvertErrorKind::ArithError
        );
        assert_eq!(conv("X > 1").unwrap_err().kind, ConvertErrorKind::NotATerm);
        assert_eq!(conv("a & b").unwrap_err().kind, ConvertErrorKind::NotATerm);
        assert_eq!(conv("not a").unwrap_err().kind, ConvertErrorKind::NotATerm);
        assert_eq!(
            conv("ns::p").unwrap_err().kind,
            ConvertErrorKind::Unsupported
        );
        assert_eq!(
            conv("p[a|T]").unwrap_err().kind,
            ConvertErrorKind::Unsupported
        );
        assert_eq!(
            conv("p(~X)").unwrap_err().kind,
            ConvertErrorKind::Unsupported
        );
        assert_eq!(
            conv("p(a + b)").unwrap_err().kind,
            ConvertErrorKind::NonConstantArith
        );
    }
}
