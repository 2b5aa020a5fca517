//! The AgentSpeak abstract syntax tree, one node per construct of Jason 3, every node with
//! its [`Span`].
//!
//! The tree keeps what the programmer wrote, not Jason's run-time objects: `if`/`while`/`for`
//! stay statements (Jason turns them into `.if_then_else`, `.loop`, `.foreach`), forks stay
//! forks. Jason's own normalisations that do not lose meaning are applied by the parser so
//! that printing and re-parsing gives the same tree: an empty annotation list is no list
//! (`p[]` is `p`), `+<b` is `+b`, nested forks of one kind are flattened, a parenthesised
//! group of one step is that step, an empty `else {}` is no `else`, and a plan term
//! `{ +b; c }` whose trigger is a belief addition with no label and no context is the body
//! `+b; c` (as in Jason's `rule_plan_term`).
//!
//! Equality compares spans too; use [`ClearSpans`] (or the `PartialEq` of a cleared copy) to
//! compare shapes only.

use super::source::Span;

/// One parsed `.asl` file.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentFile {
    /// Beliefs, rules, initial goals, plans and directives, in source order.
    pub items: Vec<Item>,
    /// The whole file.
    pub span: Span,
}

/// A top-level component of an agent.
// Trees are built once per file and walked a few times: boxing plans would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `p(a).`
    Belief(Belief),
    /// `head :- body.`
    Rule(Rule),
    /// `!g.`
    InitialGoal(InitialGoal),
    /// `@l +!g : c <- b.`
    Plan(Plan),
    /// `{ include("f.asl") }` or `{ begin namespace(n, local) } ... { end }`.
    Directive(Directive),
}

impl Item {
    /// The item's span.
    pub fn span(&self) -> Span {
        match self {
            Item::Belief(b) => b.span,
            Item::Rule(r) => r.span,
            Item::InitialGoal(g) => g.span,
            Item::Plan(p) => p.span,
            Item::Directive(d) => d.span,
        }
    }
}

/// An initial belief.
#[derive(Clone, Debug, PartialEq)]
pub struct Belief {
    /// The believed literal (never a variable: Jason refuses that).
    pub literal: Literal,
    /// From the literal to the dot.
    pub span: Span,
}

/// A Prolog-like rule `head :- body.`, in the belief base.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// The head literal.
    pub head: Literal,
    /// The body: a logical expression.
    pub body: Expr,
    /// From the head to the dot.
    pub span: Span,
}

/// An initial achievement goal `!g.`.
#[derive(Clone, Debug, PartialEq)]
pub struct InitialGoal {
    /// The goal literal.
    pub literal: Literal,
    /// From `!` to the dot.
    pub span: Span,
}

/// A directive: `{ name(args)[annots] }` alone, or as a block `{ begin name(args) } ... { end }`.
#[derive(Clone, Debug, PartialEq)]
pub struct Directive {
    /// `include`, `namespace`, ...
    pub name: String,
    /// The directive's arguments.
    pub args: Vec<Expr>,
    /// Its annotations, if any.
    pub annots: Option<ListExpr>,
    /// `None` for a single directive; the enclosed items for a `begin ... end` block.
    pub block: Option<Vec<Item>>,
    /// From the first `{` to the last `}`.
    pub span: Span,
}

/// A plan: `@label trigger : context <: goal_condition <- body.` followed by optional
/// sub-plans `{ ... }` (Jason 3).
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// `@name[annots]`, if given.
    pub label: Option<Label>,
    /// The triggering event.
    pub trigger: Trigger,
    /// `: context`, if given (none means `true`).
    pub context: Option<Expr>,
    /// `<: condition` (Jason 3's goal condition), if given.
    pub goal_condition: Option<Expr>,
    /// `<- body`, if given; a plan with no body (`+!at(L) : at(L).`) has `None`.
    pub body: Option<Body>,
    /// Jason 3 sub-plans written in braces after the plan.
    pub sub_plans: Vec<Plan>,
    /// From the label (or trigger) to the dot (or the sub-plans' closing brace).
    pub span: Span,
}

impl Plan {
    /// The body as Jason's interpreter sees it: its parser drops a leading `true`
    /// (AS2JavaParser.jj, rule `plan`), so `<- true` is the empty body.
    pub fn jason_body(&self) -> Option<Body> {
        let b = self.body.as_ref()?;
        let leading_true = b.steps.first().is_some_and(|s| {
            matches!(&s.kind, StepKind::Action(e) if matches!(&e.kind,
                ExprKind::Literal(l) if l.functor == "true" && l.args.is_empty()
                    && l.annots.is_none() && !l.negated && l.namespace.is_none()))
        });
        let mut b = b.clone();
        if leading_true {
            b.steps.remove(0);
        }
        Some(b)
    }
}

/// A plan label `@name[annots]` or `@[annots]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// The label's name: an atom, or a variable in a plan term; `None` for `@[annots]`.
    pub name: Option<String>,
    /// The label's annotations.
    pub annots: Option<ListExpr>,
    /// From `@` to the end of the label.
    pub span: Span,
}

/// `+`, `-` or `^` (goal state) in a trigger.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TriggerOp {
    /// `+`
    Add,
    /// `-`
    Del,
    /// `^` (goal-state change, Jason 3)
    GoalState,
}

impl TriggerOp {
    /// The operator as written: `+`, `-`, `^`.
    pub fn symbol(self) -> &'static str {
        match self {
            TriggerOp::Add => "+",
            TriggerOp::Del => "-",
            TriggerOp::GoalState => "^",
        }
    }
}

/// What a trigger is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TriggerKind {
    /// A belief: `+b`, `-b`.
    Belief,
    /// An achievement goal: `+!g`, `-!g`.
    Achieve,
    /// A test goal: `+?g`.
    Test,
}

impl TriggerKind {
    /// The marker as written after the operator: `!`, `?`, or nothing for a belief.
    pub fn symbol(self) -> &'static str {
        match self {
            TriggerKind::Belief => "",
            TriggerKind::Achieve => "!",
            TriggerKind::Test => "?",
        }
    }
}

/// A triggering event such as `+!storeCup(C)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Trigger {
    /// `+`, `-` or `^`.
    pub op: TriggerOp,
    /// Belief, achievement or test goal.
    pub kind: TriggerKind,
    /// The literal: an [`ExprKind::Literal`] or an [`ExprKind::Var`].
    pub literal: Expr,
    /// From the operator to the end of the literal.
    pub span: Span,
}

/// A plan body: steps separated by `;`.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The steps, in order.
    pub steps: Vec<Step>,
    /// The body's extent (empty for `{}`).
    pub span: Span,
}

/// One body step (a "body formula" in Jason's grammar, or a statement).
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// What the step does.
    pub kind: StepKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of body step.
#[derive(Clone, Debug, PartialEq)]
pub enum StepKind {
    /// An environment action `a(x)`, an internal action `.print(x)`, or a variable holding one.
    /// The expression is an [`ExprKind::Literal`] or an [`ExprKind::Var`].
    Action(Expr),
    /// `!g`: achieve a subgoal in this intention.
    Achieve(Expr),
    /// `!!g`: achieve a goal in a new intention.
    AchieveNewFocus(Expr),
    /// `?f`: a test goal (any logical formula).
    Test(Expr),
    /// `+b` (also written `+<b`), or `+{plan}` to add a plan.
    AddBel(Expr),
    /// `+>b`: add at the end of the belief base, or `+>{plan}`.
    AddBelEnd(Expr),
    /// `++b`: add and handle the event in a new intention.
    AddBelNewFocus(Expr),
    /// `-b`, or `-{plan}` to remove a plan.
    DelBel(Expr),
    /// `-+b`: replace.
    DelAddBel(Expr),
    /// `--b`: delete, event in a new intention.
    DelBelNewFocus(Expr),
    /// A relational expression used as a step: `X = Y + 1`, `N > 0`.
    Constraint(Expr),
    /// `if (c) {...} elif (c2) {...} else {...}`.
    If {
        /// The condition and body of `if` and of each `elif`, in order (at least one).
        branches: Vec<(Expr, Body)>,
        /// The `else` body, if any and not empty.
        else_body: Option<Body>,
    },
    /// `while (c) {...}`.
    While {
        /// The loop condition.
        cond: Expr,
        /// The loop body.
        body: Body,
    },
    /// `for (c) {...}`: the body runs once for every answer of `c`.
    For {
        /// The formula whose answers are iterated.
        cond: Expr,
        /// The loop body.
        body: Body,
    },
    /// `a |&| b` (all branches) or `a ||| b` (the first to finish), at least two branches.
    Fork {
        /// `|&|` or `|||`.
        op: ForkOp,
        /// One body per branch.
        branches: Vec<Body>,
    },
    /// `( a; b )`: a parenthesised sequence of at least two steps.
    Group(Body),
}

/// Which fork.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ForkOp {
    /// `|&|`: the fork ends when every branch has ended.
    And,
    /// `|||`: the fork ends when one branch has ended.
    Or,
}

/// A namespace prefix `ns::`, `V::` or `::` (the current namespace).
#[derive(Clone, Debug, PartialEq)]
pub struct Namespace {
    /// Which namespace.
    pub kind: NamespaceKind,
    /// From the name to `::`.
    pub span: Span,
}

/// The namespace a prefix names.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum NamespaceKind {
    /// `ns::`
    Named(String),
    /// `V::`
    Var(String),
    /// `::p`: the namespace of the enclosing `begin namespace` block.
    Current,
}

/// A literal: `ns::~functor(args)[annots]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Literal {
    /// `ns::`, if written.
    pub namespace: Option<Namespace>,
    /// Strong negation `~`.
    pub negated: bool,
    /// The functor: an atom such as `cupAt`, `.print`, `math.abs`, `'quoted'` (quotes kept), or
    /// `true`/`false`.
    pub functor: String,
    /// The arguments (empty when written without parentheses; `p()` is not Jason).
    pub args: Vec<Expr>,
    /// `[annots]`, if written and not empty.
    pub annots: Option<ListExpr>,
    /// Where.
    pub span: Span,
}

impl Literal {
    /// The name of the predicate a belief literal names: `p`, or `~p` for a strongly
    /// negated one, which Jason keeps apart from `p` (a predicate indicator of its own).
    pub fn belief_name(&self) -> std::borrow::Cow<'_, str> {
        if self.negated {
            format!("~{}", self.functor).into()
        } else {
            self.functor.as_str().into()
        }
    }

    /// Whether Jason treats this literal as an internal action: an unquoted functor containing
    /// a dot (`.print`, `time.check`).
    pub fn is_internal_action(&self) -> bool {
        !self.functor.starts_with('\'') && self.functor.contains('.')
    }
}

/// A variable, possibly with a namespace, strong negation or annotations (`~X[a]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Var {
    /// `ns::`, if written.
    pub namespace: Option<Namespace>,
    /// Strong negation `~`.
    pub negated: bool,
    /// `X`, `_`, `_Name`.
    pub name: String,
    /// `[annots]`, if written and not empty.
    pub annots: Option<ListExpr>,
    /// Where.
    pub span: Span,
}

/// A list `[a, b | T]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ListExpr {
    /// The elements before `|`.
    pub elems: Vec<Expr>,
    /// The tail after `|`: a variable or a list.
    pub tail: Option<Box<Expr>>,
    /// From `[` to `]`.
    pub span: Span,
}

/// Unary arithmetic signs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `+x`
    Plus,
}

/// Binary arithmetic operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArithOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `div` (integer division)
    IntDiv,
    /// `mod`
    Mod,
    /// `**`
    Pow,
}

impl ArithOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            ArithOp::Add => "+",
            ArithOp::Sub => "-",
            ArithOp::Mul => "*",
            ArithOp::Div => "/",
            ArithOp::IntDiv => "div",
            ArithOp::Mod => "mod",
            ArithOp::Pow => "**",
        }
    }
}

/// Relational operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RelOp {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `\==`
    Ne,
    /// `=` (unification)
    Unify,
    /// `=..` (literal builder)
    Univ,
}

impl RelOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            RelOp::Lt => "<",
            RelOp::Le => "<=",
            RelOp::Gt => ">",
            RelOp::Ge => ">=",
            RelOp::Eq => "==",
            RelOp::Ne => "\\==",
            RelOp::Unify => "=",
            RelOp::Univ => "=..",
        }
    }
}

/// A term or a logical/arithmetic expression: Jason's grammar does not separate them (an
/// argument of a literal is a `log_expr`).
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub span: Span,
}

/// The kinds of expression.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A literal or atom (also `true`, `false`, internal actions and arithmetic functions).
    Literal(Literal),
    /// A variable.
    Var(Var),
    /// An integer, as written (never negative: `-5` is `Unary(Neg, 5)`).
    Int(i64),
    /// A floating-point number (finite, never negative).
    Float(f64),
    /// A string, escapes decoded.
    Str(String),
    /// A list.
    List(ListExpr),
    /// `-x`, `+x`.
    Unary(UnaryOp, Box<Expr>),
    /// `x + y`, `x ** y`, ...
    Arith(ArithOp, Box<Expr>, Box<Expr>),
    /// `x < y`, `x = y`, ...
    Rel(RelOp, Box<Expr>, Box<Expr>),
    /// `not f` (negation as failure).
    Not(Box<Expr>),
    /// `f & g`.
    And(Box<Expr>, Box<Expr>),
    /// `f | g`.
    Or(Box<Expr>, Box<Expr>),
    /// A plan, trigger, body or rule in braces: `{ +!g <- a }`.
    PlanTerm(Box<PlanTerm>),
}

/// A term in braces.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanTerm {
    /// Which kind.
    pub kind: PlanTermKind,
    /// From `{` to `}`.
    pub span: Span,
}

/// What a term in braces holds.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum PlanTermKind {
    /// `{ @l +!g : c <- b }` (sub-plans are not allowed in a plan term).
    Plan(Plan),
    /// `{ +!g }`: a trigger alone.
    Trigger(Trigger),
    /// `{ a; b }` or `{}`: a body.
    Body(Body),
    /// `{ p :- q }`: a rule.
    Rule(Rule),
}

/// Resets every span in a tree to the default, so that two trees can be compared by shape.
pub trait ClearSpans {
    /// Sets every span to `Span::default()`.
    fn clear_spans(&mut self);
}

impl<T: ClearSpans> ClearSpans for Vec<T> {
    fn clear_spans(&mut self) {
        self.iter_mut().for_each(ClearSpans::clear_spans);
    }
}

impl<T: ClearSpans> ClearSpans for Option<T> {
    fn clear_spans(&mut self) {
        if let Some(x) = self {
            x.clear_spans();
        }
    }
}

impl<T: ClearSpans> ClearSpans for Box<T> {
    fn clear_spans(&mut self) {
        (**self).clear_spans();
    }
}

impl ClearSpans for AgentFile {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.items.clear_spans();
    }
}

impl ClearSpans for Item {
    fn clear_spans(&mut self) {
        match self {
            Item::Belief(b) => b.clear_spans(),
            Item::Rule(r) => r.clear_spans(),
            Item::InitialGoal(g) => g.clear_spans(),
            Item::Plan(p) => p.clear_spans(),
            Item::Directive(d) => d.clear_spans(),
        }
    }
}

impl ClearSpans for Belief {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.literal.clear_spans();
    }
}

impl ClearSpans for Rule {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.head.clear_spans();
        self.body.clear_spans();
    }
}

impl ClearSpans for InitialGoal {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.literal.clear_spans();
    }
}

impl ClearSpans for Directive {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.args.clear_spans();
        self.annots.clear_spans();
        self.block.clear_spans();
    }
}

impl ClearSpans for Plan {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.label.clear_spans();
        self.trigger.clear_spans();
        self.context.clear_spans();
        self.goal_condition.clear_spans();
        self.body.clear_spans();
        self.sub_plans.clear_spans();
    }
}

impl ClearSpans for Label {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.annots.clear_spans();
    }
}

impl ClearSpans for Trigger {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.literal.clear_spans();
    }
}

impl ClearSpans for Body {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.steps.clear_spans();
    }
}

impl ClearSpans for Step {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        match &mut self.kind {
            StepKind::Action(e)
            | StepKind::Achieve(e)
            | StepKind::AchieveNewFocus(e)
            | StepKind::Test(e)
            | StepKind::AddBel(e)
            | StepKind::AddBelEnd(e)
            | StepKind::AddBelNewFocus(e)
            | StepKind::DelBel(e)
            | StepKind::DelAddBel(e)
            | StepKind::DelBelNewFocus(e)
            | StepKind::Constraint(e) => e.clear_spans(),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    c.clear_spans();
                    b.clear_spans();
                }
                else_body.clear_spans();
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                cond.clear_spans();
                body.clear_spans();
            }
            StepKind::Fork { branches, .. } => branches.clear_spans(),
            StepKind::Group(b) => b.clear_spans(),
        }
    }
}

impl ClearSpans for Namespace {
    fn clear_spans(&mut self) {
        self.span = Span::default();
    }
}

impl ClearSpans for Literal {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.namespace.clear_spans();
        self.args.clear_spans();
        self.annots.clear_spans();
    }
}

impl ClearSpans for Var {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.namespace.clear_spans();
        self.annots.clear_spans();
    }
}

impl ClearSpans for ListExpr {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        self.elems.clear_spans();
        self.tail.clear_spans();
    }
}

impl ClearSpans for Expr {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        match &mut self.kind {
            ExprKind::Literal(l) => l.clear_spans(),
            ExprKind::Var(v) => v.clear_spans(),
            ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) => {}
            ExprKind::List(l) => l.clear_spans(),
            ExprKind::Unary(_, e) | ExprKind::Not(e) => e.clear_spans(),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                a.clear_spans();
                b.clear_spans();
            }
            ExprKind::PlanTerm(p) => p.clear_spans(),
        }
    }
}

impl ClearSpans for PlanTerm {
    fn clear_spans(&mut self) {
        self.span = Span::default();
        match &mut self.kind {
            PlanTermKind::Plan(p) => p.clear_spans(),
            PlanTermKind::Trigger(t) => t.clear_spans(),
            PlanTermKind::Body(b) => b.clear_spans(),
            PlanTermKind::Rule(r) => r.clear_spans(),
        }
    }
}
