//! A recursive-descent parser for Jason 3 AgentSpeak, rule for rule after Jason's
//! `AS2JavaParser.jj` (the grammar productions are named in the comments).
//!
//! Errors are collected, not thrown: after an error the parser skips to the end of the item
//! (the next `.` outside brackets, or a line that starts a new item in column 1) and goes on,
//! so one run reports every broken item of a file. Nesting is bounded so that no input can
//! exhaust the stack.

use super::ast::*;
use super::diagnostic::Diagnostic;
use super::lexer::{lex, Tok, Token};
use super::source::{FileId, Span};
use std::collections::HashMap;

/// Deepest nesting of brackets and expressions accepted; Jason programs stay far below it,
/// and the bound keeps hostile input from overflowing the stack.
const MAX_DEPTH: usize = 64;
/// After this many errors in one file the rest of the file is not parsed.
const MAX_ERRORS: usize = 50;

/// `Err(())` means a diagnostic has been recorded.
type PResult<T> = Result<T, ()>;

/// Parses one `.asl` text. The tree holds every item that parsed; the diagnostics hold every
/// error (the file is valid exactly when there is none).
pub fn parse_agent(file: FileId, text: &str) -> (AgentFile, Vec<Diagnostic>) {
    let (toks, lex_errors) = lex(file, text);
    let mut p = Parser::new(file, text, toks);
    p.errors = lex_errors;
    let items = p.items_until_eof();
    let file_ast = AgentFile {
        items,
        span: Span::new(file, 0, text.len()),
    };
    (file_ast, p.errors)
}

/// Parses a logical expression (a manifest formula, a context) that must fill `text`.
pub fn parse_expr(file: FileId, text: &str) -> Result<Expr, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.log_expr())
}

/// Parses one body formula (`navigateTo(table)`, `!storeCup(C)`, `+b`) that must fill `text`.
pub fn parse_step(file: FileId, text: &str) -> Result<Step, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.body_formula())
}

/// Parses one trigger (`+!storeCup(C)`) that must fill `text`.
pub fn parse_trigger(file: FileId, text: &str) -> Result<Trigger, Vec<Diagnostic>> {
    parse_whole(file, text, |p| p.trigger())
}

fn parse_whole<T>(
    file: FileId,
    text: &str,
    f: impl FnOnce(&mut Parser) -> PResult<T>,
) -> Result<T, Vec<Diagnostic>> {
    let (toks, lex_errors) = lex(file, text);
    if !lex_errors.is_empty() {
        return Err(lex_errors);
    }
    let mut p = Parser::new(file, text, toks);
    let r = f(&mut p);
    if r.is_ok() && p.peek() != &Tok::Eof {
        let _: PResult<()> = p.error_expected("the end of the formula");
    }
    match r {
        Ok(v) if p.errors.is_empty() => Ok(v),
        _ => Err(p.errors),
    }
}

struct Parser<'t> {
    file: FileId,
    text: &'t str,
    toks: Vec<Token>,
    pos: usize,
    /// End of the last consumed token, for spans.
    prev_end: u32,
    errors: Vec<Diagnostic>,
    depth: usize,
    /// Outcome of the speculative `log_expr` at a body position starting with `(`.
    speculated: HashMap<usize, Option<(Expr, usize, u32)>>,
    /// Plan terms already parsed, by position: result, position after, end, errors.
    plan_terms: HashMap<usize, PlanTermMemo>,
}

type PlanTermMemo = (PResult<Expr>, usize, u32, Vec<Diagnostic>);

impl<'t> Parser<'t> {
    fn new(file: FileId, text: &'t str, toks: Vec<Token>) -> Parser<'t> {
        Parser {
            file,
            text,
            toks,
            pos: 0,
            prev_end: 0,
            errors: Vec::new(),
            depth: 0,
            speculated: HashMap::new(),
            plan_terms: HashMap::new(),
        }
    }

    // ----- token access -------------------------------------------------------------------

    fn peek(&self) -> &Tok {
        self.peek_at(0)
    }

    fn peek_at(&self, k: usize) -> &Tok {
        let i = (self.pos + k).min(self.toks.len() - 1);
        &self.toks[i].tok
    }

    fn span_here(&self) -> Span {
        self.toks[self.pos.min(self.toks.len() - 1)].span
    }

    fn start(&self) -> u32 {
        self.span_here().start
    }

    fn span_from(&self, start: u32) -> Span {
        Span {
            file: self.file,
            start,
            end: self.prev_end.max(start),
        }
    }

    fn bump(&mut self) -> Token {
        let t = self.toks[self.pos.min(self.toks.len() - 1)].clone();
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
        }
        self.prev_end = t.span.end;
        t
    }

    fn eat(&mut self, tok: &Tok) -> bool {
        if self.peek() == tok {
            self.bump();
            true
        } else {
            false
        }
    }

    fn expect(&mut self, tok: &Tok, what: &str) -> PResult<Span> {
        if self.peek() == tok {
            Ok(self.bump().span)
        } else {
            self.error_expected(what)
        }
    }

    fn error_expected<T>(&mut self, what: &str) -> PResult<T> {
        let found = self.peek().describe();
        let span = self.span_here();
        self.error(Diagnostic::syntax(
            span,
            format!("expected {what}, found {found}"),
            format!("expected {what}"),
        ))
    }

    fn error<T>(&mut self, d: Diagnostic) -> PResult<T> {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
        Err(())
    }

    fn error_at<T>(&mut self, span: Span, msg: impl Into<String>, label: &str) -> PResult<T> {
        self.error(Diagnostic::syntax(span, msg, label))
    }

    /// Runs `f` one nesting level deeper, refusing input nested beyond [`MAX_DEPTH`].
    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        if self.depth >= MAX_DEPTH {
            let span = self.span_here();
            return self.error_at(
                span,
                format!("nesting deeper than {MAX_DEPTH} levels"),
                "too deeply nested",
            );
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    /// Whether the current token is the first on its line, in column 1.
    fn at_line_start(&self) -> bool {
        let s = self.span_here().start as usize;
        s == 0 || self.text.as_bytes().get(s - 1) == Some(&b'\n')
    }

    /// Skips what is left of a broken item: up to and including the next `.` outside
    /// brackets, or up to a token in column 1 that can start a new item.
    fn recover(&mut self, item_start: usize) {
        let mut depth = 0usize;
        loop {
            match self.peek() {
                Tok::Eof => return,
                Tok::Dot if depth == 0 => {
                    self.bump();
                    return;
                }
                Tok::Plus
                | Tok::Minus
                | Tok::At
                | Tok::Caret
                | Tok::Bang
                | Tok::LBrace
                | Tok::Atom(_)
                    if self.pos > item_start && self.at_line_start() =>
                {
                    return
                }
                Tok::LParen | Tok::LBracket | Tok::LBrace => depth += 1,
                Tok::RParen | Tok::RBracket | Tok::RBrace => depth = depth.saturating_sub(1),
                _ => {}
            }
            self.bump();
        }
    }

    fn too_many_errors(&self) -> bool {
        self.errors.len() >= MAX_ERRORS
    }

    // ----- agent ------------------------------------------------------------------------------

    fn items_until_eof(&mut self) -> Vec<Item> {
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
    fn label(&mut self, allow_var: bool) -> PResult<Label> {
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
    fn trigger(&mut self) -> PResult<Trigger> {
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

    // ----- bodies -----------------------------------------------------------------------------

    /// Whether a body continues after `;` (Jason's `[ R = plan_body() ]` is optional).
    fn body_continues(&self) -> bool {
        !matches!(
            self.peek(),
            Tok::Dot | Tok::RBrace | Tok::RParen | Tok::RBracket | Tok::Eof | Tok::RuleSep
        )
    }

    /// `plan_body`: steps separated by `;`; a statement needs no `;` after it.
    fn plan_body(&mut self) -> PResult<Body> {
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
    fn body_formula(&mut self) -> PResult<Step> {
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

    // ----- plan terms ---------------------------------------------------------------------------

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
    fn plan_term(&mut self) -> PResult<Expr> {
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

    // ----- logical and arithmetic expressions ---------------------------------------------------

    /// `log_expr`: `log_expr_trm [| log_expr]`.
    fn log_expr(&mut self) -> PResult<Expr> {
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

    fn string(&mut self) -> Expr {
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
    fn arith_expr(&mut self) -> PResult<Expr> {
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

    // ----- literals and terms -----------------------------------------------------------------

    fn starts_literal(&self) -> bool {
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
    fn literal(&mut self) -> PResult<Expr> {
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
    fn terms(&mut self) -> PResult<Vec<Expr>> {
        let mut v = vec![self.log_expr()?];
        while self.eat(&Tok::Comma) {
            v.push(self.log_expr()?);
        }
        Ok(v)
    }

    /// Optional annotations: a list right after a literal or variable.
    fn opt_annots(&mut self) -> PResult<Option<ListExpr>> {
        if self.peek() == &Tok::LBracket {
            let l = self.list()?;
            Ok(non_empty(l))
        } else {
            Ok(None)
        }
    }

    fn list_expr(&mut self) -> PResult<Expr> {
        let l = self.list()?;
        let span = l.span;
        Ok(Expr {
            kind: ExprKind::List(l),
            span,
        })
    }

    /// `list`: `[ [elem (, elem)*] [| (VAR | _ | list)] ]`.
    fn list(&mut self) -> PResult<ListExpr> {
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

/// `p[]` is `p`: an empty annotation list (with no tail) is no list.
fn non_empty(l: ListExpr) -> Option<ListExpr> {
    (!l.elems.is_empty() || l.tail.is_some()).then_some(l)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn plan_term(src: &str) -> PlanTermKind {
        let e = parse_expr(FileId(0), src).expect("parses");
        match e.kind {
            ExprKind::PlanTerm(t) => t.kind,
            other => panic!("not a plan term: {other:?}"),
        }
    }

    #[test]
    fn plan_terms_follow_jason_rule_plan_term() {
        // `;` after a plain belief trigger: a body.
        assert!(matches!(plan_term("{ +b; a }"), PlanTermKind::Body(b) if b.steps.len() == 2));
        // `<-` always makes a plan, even for a belief trigger.
        assert!(matches!(plan_term("{ +b <- a }"), PlanTermKind::Plan(_)));
        assert!(matches!(plan_term("{ -b <- a }"), PlanTermKind::Plan(_)));
        assert!(matches!(plan_term("{ +!g }"), PlanTermKind::Trigger(_)));
        assert!(matches!(plan_term("{ +!g <- a }"), PlanTermKind::Plan(_)));
        assert!(matches!(plan_term("{ a :- b }"), PlanTermKind::Rule(_)));
        assert!(matches!(plan_term("{}"), PlanTermKind::Body(b) if b.steps.is_empty()));
        for bad in ["{ +!h; a }", "{ @l +b; a }", "{ +b : c; a }"] {
            let errs = parse_expr(FileId(0), bad).expect_err(bad);
            assert!(
                errs[0].message.contains("wrong place for `;`"),
                "{bad}: {errs:?}"
            );
        }
    }

    #[test]
    fn bodies_groups_and_forks() {
        let step = |s: &str| parse_step(FileId(0), s).expect(s).kind;
        assert!(matches!(step("(a)"), StepKind::Action(_)));
        assert!(matches!(step("X = 1 + 2"), StepKind::Constraint(_)));
        assert!(matches!(step("-+b(1)"), StepKind::DelAddBel(_)));
        assert!(matches!(step("+<b"), StepKind::AddBel(_)));
        let (file, errs) = parse_agent(
            FileId(0),
            "+!g <- (a; b); a |&| b ||| (c; d) ||| (e ||| f).",
        );
        assert!(errs.is_empty(), "{errs:?}");
        let Item::Plan(p) = &file.items[0] else {
            panic!()
        };
        let steps = &p.body.as_ref().unwrap().steps;
        assert!(matches!(&steps[0].kind, StepKind::Group(b) if b.steps.len() == 2));
        // `|&|` binds tighter than `|||`, and nested `|||` forks are flattened as Jason does.
        let StepKind::Fork {
            op: ForkOp::Or,
            branches,
        } = &steps[1].kind
        else {
            panic!()
        };
        assert_eq!(branches.len(), 4);
        assert!(matches!(
            &branches[0].steps[0].kind,
            StepKind::Fork {
                op: ForkOp::And,
                ..
            }
        ));
    }
}
