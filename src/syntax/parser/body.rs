//! Plan bodies: statements (`if`, `while`, `for`), forks (`|&|`, `|||`) and body formulas,
//! whose prefix (`!`, `?`, `+`, `-+`, ...) decides what kind of step they are.

use super::{PResult, Parser};
use crate::syntax::ast::*;
use crate::syntax::lexer::Tok;
use crate::syntax::source::Span;

impl<'t> Parser<'t> {
    /// Whether a body continues after `;` (Jason's `[ R = plan_body() ]` is optional).
    fn body_continues(&self) -> bool {
        !matches!(
            self.peek(),
            Tok::Dot | Tok::RBrace | Tok::RParen | Tok::RBracket | Tok::Eof | Tok::RuleSep
        )
    }

    /// `plan_body`: steps separated by `;`; a statement needs no `;` after it.
    pub(super) fn plan_body(&mut self) -> PResult<Body> {
        self.nested(|p| {
            let start = p.start();
            let mut steps = Vec::new();
            loop {
                if matches!(p.peek(), Tok::If | Tok::While | Tok::For) {
                    steps.push(p.statement()?);
                    p.eat(&Tok::Semi);
                } else {
                    steps.push(p.body_term()?);
                    if !p.eat(&Tok::Semi) {
                        break;
                    }
                }
                if !p.body_continues() {
                    break;
                }
            }
            Ok(Body {
                steps,
                span: p.span_from(start),
            })
        })
    }

    /// A possibly empty body inside `{ }` (statements and plan terms).
    fn braced_body(&mut self, what: &str) -> PResult<Body> {
        let open = self.expect(&Tok::LBrace, &format!("`{{` to open {what}"))?;
        let body = if self.peek() == &Tok::RBrace {
            Body {
                steps: Vec::new(),
                span: Span::new(self.file, open.end as usize, open.end as usize),
            }
        } else {
            self.plan_body()?
        };
        self.expect(&Tok::RBrace, &format!("`}}` to close {what}"))?;
        Ok(body)
    }

    /// `statement`: `if`, `while` or `for`.
    fn statement(&mut self) -> PResult<Step> {
        let start = self.start();
        let kind = match self.bump().tok {
            Tok::If => {
                let mut branches = Vec::new();
                let mut else_body = None;
                loop {
                    let cond = self.paren_cond("`if`")?;
                    let body = self.braced_body("the `if` body")?;
                    branches.push((cond, body));
                    if self.eat(&Tok::Elif) {
                        continue;
                    }
                    if self.eat(&Tok::Else) {
                        let b = self.braced_body("the `else` body")?;
                        // Jason: an empty `else {}` is no else.
                        else_body = (!b.steps.is_empty()).then_some(b);
                    }
                    break;
                }
                StepKind::If {
                    branches,
                    else_body,
                }
            }
            Tok::While => {
                let cond = self.paren_cond("`while`")?;
                let body = self.braced_body("the `while` body")?;
                StepKind::While { cond, body }
            }
            _ => {
                let cond = self.paren_cond("`for`")?;
                let body = self.braced_body("the `for` body")?;
                StepKind::For { cond, body }
            }
        };
        Ok(Step {
            kind,
            span: self.span_from(start),
        })
    }

    fn paren_cond(&mut self, what: &str) -> PResult<Expr> {
        self.expect(&Tok::LParen, &format!("`(` after {what}"))?;
        let e = self.log_expr()?;
        self.expect(&Tok::RParen, &format!("`)` to close the {what} condition"))?;
        Ok(e)
    }

    /// `plan_body_term`: factors joined by `|||`.
    fn body_term(&mut self) -> PResult<Step> {
        let start = self.start();
        let first = self.body_factor()?;
        if self.peek() != &Tok::ParOr {
            return Ok(ungroup(first));
        }
        let mut branches = vec![first];
        while self.eat(&Tok::ParOr) {
            branches.push(self.body_factor()?);
        }
        Ok(self.fork(ForkOp::Or, branches, start))
    }

    /// `plan_body_factor`: formulas joined by `|&|`.
    fn body_factor(&mut self) -> PResult<Step> {
        let start = self.start();
        let first = self.body_formula()?;
        if self.peek() != &Tok::ParAnd {
            return Ok(first);
        }
        let mut branches = vec![first];
        while self.eat(&Tok::ParAnd) {
            branches.push(self.body_formula()?);
        }
        Ok(self.fork(ForkOp::And, branches, start))
    }

    /// Builds a fork, flattening branches that are forks of the same kind (as Jason does).
    fn fork(&self, op: ForkOp, parts: Vec<Step>, start: u32) -> Step {
        let mut branches = Vec::new();
        for part in parts {
            let span = part.span;
            match part.kind {
                StepKind::Group(body) if is_single_fork(&body, op) => {
                    if let Some(Step {
                        kind: StepKind::Fork { branches: bs, .. },
                        ..
                    }) = body.steps.into_iter().next()
                    {
                        branches.extend(bs);
                    }
                }
                StepKind::Group(body) => branches.push(body),
                StepKind::Fork {
                    op: o,
                    branches: bs,
                } if o == op => branches.extend(bs),
                kind => branches.push(Body {
                    steps: vec![Step { kind, span }],
                    span,
                }),
            }
        }
        Step {
            kind: StepKind::Fork { op, branches },
            span: self.span_from(start),
        }
    }

    /// `body_formula`: `!g`, `!!g`, `?f`, `+b`, `-b`, `-+b`, ..., an action, a constraint, or
    /// `( plan_body )`.
    pub(super) fn body_formula(&mut self) -> PResult<Step> {
        let start = self.start();
        let (prefix, prefix_len) = match (self.peek(), self.peek_at(1)) {
            (Tok::Bang, _) => (Prefix::Achieve, 1),
            (Tok::BangBang, _) => (Prefix::AchieveNewFocus, 1),
            (Tok::Question, _) => (Prefix::Test, 1),
            (Tok::Plus, Tok::Plus) => (Prefix::AddNewFocus, 2),
            (Tok::Plus, Tok::Lt) => (Prefix::Add, 2),
            (Tok::Plus, Tok::Gt) => (Prefix::AddEnd, 2),
            (Tok::Plus, _) => (Prefix::Add, 1),
            (Tok::Minus, Tok::Plus) => (Prefix::DelAdd, 2),
            (Tok::Minus, Tok::Minus) => (Prefix::DelNewFocus, 2),
            (Tok::Minus, _) => (Prefix::Del, 1),
            _ => (Prefix::None, 0),
        };
        let prefix_span = self.span_here();
        for _ in 0..prefix_len {
            self.bump();
        }
        let kind = match prefix {
            Prefix::Achieve | Prefix::AchieveNewFocus => {
                if !self.starts_literal() {
                    return self.error_expected("a goal literal");
                }
                let lit = self.literal()?;
                if let ExprKind::Literal(l) = &lit.kind {
                    if l.is_internal_action() {
                        return self.error_at(
                            lit.span,
                            format!("an internal action (`{}`) cannot be a goal", l.functor),
                            "internal action",
                        );
                    }
                }
                if prefix == Prefix::Achieve {
                    StepKind::Achieve(lit)
                } else {
                    StepKind::AchieveNewFocus(lit)
                }
            }
            Prefix::None if self.peek() == &Tok::LParen => {
                // Jason: LOOKAHEAD(log_expr()) first, else `( plan_body )`. The attempt is
                // remembered per position: nested groups would otherwise retry it
                // exponentially often.
                let (save_pos, save_err, save_end) = (self.pos, self.errors.len(), self.prev_end);
                let attempt = match self.speculated.get(&save_pos) {
                    Some(hit) => hit.clone(),
                    None => {
                        let r = self.log_expr().ok().map(|e| (e, self.pos, self.prev_end));
                        self.speculated.insert(save_pos, r.clone());
                        r
                    }
                };
                self.errors.truncate(save_err);
                match attempt {
                    Some((e, pos, end)) => {
                        self.pos = pos;
                        self.prev_end = end;
                        return self.formula_step(Prefix::None, e, prefix_span, start);
                    }
                    None => {
                        self.pos = save_pos;
                        self.prev_end = save_end;
                    }
                }
                self.bump();
                let body = self.plan_body()?;
                self.expect(&Tok::RParen, "`)` to close the group")?;
                StepKind::Group(body)
            }
            _ => {
                let e = self.log_expr()?;
                return self.formula_step(prefix, e, prefix_span, start);
            }
        };
        Ok(Step {
            kind,
            span: self.span_from(start),
        })
    }

    /// Classifies `prefix expr` as a step, refusing the combinations Jason refuses.
    fn formula_step(
        &mut self,
        prefix: Prefix,
        e: Expr,
        prefix_span: Span,
        start: u32,
    ) -> PResult<Step> {
        let is_literal = matches!(e.kind, ExprKind::Literal(_) | ExprKind::Var(_));
        let is_ia = matches!(&e.kind, ExprKind::Literal(l) if l.is_internal_action());
        let is_plan = matches!(e.kind, ExprKind::PlanTerm(_));
        let is_formula = matches!(
            e.kind,
            ExprKind::Literal(_)
                | ExprKind::Var(_)
                | ExprKind::Rel(..)
                | ExprKind::Not(_)
                | ExprKind::And(..)
                | ExprKind::Or(..)
        );
        if is_ia && prefix != Prefix::None {
            let name = match &e.kind {
                ExprKind::Literal(l) => l.functor.clone(),
                _ => String::new(),
            };
            return self.error_at(
                prefix_span.to(e.span),
                format!(
                    "an internal action (`{name}`) cannot follow `{}`",
                    prefix.symbol()
                ),
                "wrong combination of operator and internal action",
            );
        }
        let kind = match prefix {
            Prefix::None => match e.kind {
                ExprKind::Rel(..) => StepKind::Constraint(e),
                _ if is_literal => StepKind::Action(e),
                _ => {
                    return self.error_at(
                        e.span,
                        "not a body formula: expected an action, a goal, a belief update or a relational expression",
                        "not a body literal",
                    )
                }
            },
            Prefix::Test if is_formula => StepKind::Test(e),
            Prefix::Add if is_literal || is_plan => StepKind::AddBel(e),
            Prefix::AddEnd if is_literal || is_plan => StepKind::AddBelEnd(e),
            Prefix::Del if is_literal || is_plan => StepKind::DelBel(e),
            Prefix::AddNewFocus if is_literal => StepKind::AddBelNewFocus(e),
            Prefix::DelAdd if is_literal => StepKind::DelAddBel(e),
            Prefix::DelNewFocus if is_literal => StepKind::DelBelNewFocus(e),
            _ => {
                let what = if prefix == Prefix::Test {
                    "a logical formula"
                } else {
                    "a literal"
                };
                return self.error_at(
                    e.span,
                    format!("`{}` must be followed by {what}", prefix.symbol()),
                    "wrong combination of operator and formula",
                );
            }
        };
        Ok(Step {
            kind,
            span: self.span_from(start),
        })
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Prefix {
    None,
    Achieve,
    AchieveNewFocus,
    Test,
    Add,
    AddEnd,
    AddNewFocus,
    Del,
    DelAdd,
    DelNewFocus,
}

impl Prefix {
    fn symbol(self) -> &'static str {
        match self {
            Prefix::None => "",
            Prefix::Achieve => "!",
            Prefix::AchieveNewFocus => "!!",
            Prefix::Test => "?",
            Prefix::Add => "+",
            Prefix::AddEnd => "+>",
            Prefix::AddNewFocus => "++",
            Prefix::Del => "-",
            Prefix::DelAdd => "-+",
            Prefix::DelNewFocus => "--",
        }
    }
}

fn is_single_fork(body: &Body, op: ForkOp) -> bool {
    matches!(body.steps.as_slice(), [Step { kind: StepKind::Fork { op: o, .. }, .. }] if *o == op)
}

/// A parenthesised group of one step is that step.
fn ungroup(step: Step) -> Step {
    match step.kind {
        StepKind::Group(mut body) if body.steps.len() == 1 => body.steps.remove(0),
        kind => Step {
            kind,
            span: step.span,
        },
    }
}
