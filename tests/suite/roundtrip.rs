//! Printing and re-parsing gives back the same tree.
//!
//! * Generated trees: a proptest strategy builds ASTs that respect every invariant the parser
//!   guarantees (see `ast.rs`), and `parse(print(ast))` must equal `ast`, spans aside.
//! * Files: every valid `.asl` file under `tests/` (and Jason's own examples when a copy is
//!   at `/tmp/jason/asl`) parses, prints, re-parses to the same tree, and printing is
//!   idempotent.

use bdi_check::syntax::ast::*;
use bdi_check::syntax::printer::{print_agent, print_body, print_expr};
use bdi_check::syntax::{parse_agent, parse_expr, FileId, Span};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use std::path::{Path, PathBuf};

// ----- helpers -----------------------------------------------------------------------------

fn ex(kind: ExprKind) -> Expr {
    Expr {
        kind,
        span: Span::default(),
    }
}

fn st(kind: StepKind) -> Step {
    Step {
        kind,
        span: Span::default(),
    }
}

fn bx(e: Expr) -> Box<Expr> {
    Box::new(e)
}

fn body(steps: Vec<Step>) -> Body {
    Body {
        steps,
        span: Span::default(),
    }
}

fn cleared<T: ClearSpans + Clone>(x: &T) -> T {
    let mut y = x.clone();
    y.clear_spans();
    y
}

/// A fixed seed keeps runs reproducible; `PROPTEST_RNG_SEED` and `PROPTEST_CASES` still
/// override it, to explore further by hand.
fn config(cases: u32) -> Config {
    let mut c = Config::default();
    if matches!(c.rng_seed, RngSeed::Random) {
        c.rng_seed = RngSeed::Fixed(0x0bd1_c4ec);
    }
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    c.failure_persistence = None;
    c
}

// ----- names -------------------------------------------------------------------------------

/// Words the lexer reads as keywords, never as atoms.
const KEYWORDS: &[&str] = &[
    "true", "false", "not", "div", "mod", "if", "else", "elif", "for", "while", "begin", "end",
];

/// A plain atom: a namespace, directive or ordinary functor name.
fn plain_atom() -> BoxedStrategy<String> {
    prop_oneof![
        3 => prop::sample::select(vec!["a", "b", "cup", "at", "holding", "p1", "x_Y", "go"])
            .prop_map(String::from),
        2 => "[a-z][a-zA-Z0-9_]{0,4}".prop_filter("keyword", |s| !KEYWORDS.contains(&s.as_str())),
    ]
    .boxed()
}

/// A functor that is not an internal action: also quoted atoms and `begin`/`end`, which the
/// grammar accepts where a literal is expected.
fn functor() -> BoxedStrategy<String> {
    prop_oneof![
        8 => plain_atom(),
        1 => "'[a-z A-Z0-9.(]{0,5}'",
        1 => prop::sample::select(vec!["begin", "end"]).prop_map(String::from),
    ]
    .boxed()
}

/// An internal action or arithmetic function name: a functor with a dot.
fn ia_functor() -> BoxedStrategy<String> {
    prop_oneof![
        prop::sample::select(vec![".print", ".my_name", "math.abs", ".member", "a.b.c"])
            .prop_map(String::from),
        "\\.[a-z][a-z0-9_]{0,3}",
        "[a-z]{1,3}\\.[a-z][a-zA-Z0-9]{0,3}",
    ]
    .boxed()
}

fn var_name() -> BoxedStrategy<String> {
    prop_oneof![
        3 => prop::sample::select(vec!["X", "Y", "Cup", "_", "_L", "N1"]).prop_map(String::from),
        1 => "[A-Z][a-zA-Z0-9_]{0,3}",
        1 => "_[a-zA-Z0-9_]{0,3}",
    ]
    .boxed()
}

fn namespace() -> BoxedStrategy<Namespace> {
    prop_oneof![
        plain_atom().prop_map(NamespaceKind::Named),
        var_name().prop_map(NamespaceKind::Var),
        Just(NamespaceKind::Current),
    ]
    .prop_map(|kind| Namespace {
        kind,
        span: Span::default(),
    })
    .boxed()
}

// ----- expressions -------------------------------------------------------------------------

fn int() -> BoxedStrategy<i64> {
    prop_oneof![4 => 0i64..100, 1 => 0..=i64::MAX].boxed()
}

/// Finite, not negative (a sign is a `Unary`), not `-0.0`.
fn float() -> BoxedStrategy<f64> {
    prop_oneof![
        3 => (0u32..4000).prop_map(|n| f64::from(n) / 8.0),
        1 => any::<f64>().prop_filter("finite, positive", |x| x.is_finite() && x.is_sign_positive()),
    ]
    .boxed()
}

fn string() -> BoxedStrategy<String> {
    let ch = prop_oneof![
        3 => any::<char>(),
        2 => prop::sample::select(vec![
            '"', '\\', '\'', '\n', '\r', '\t', '\u{0}', '\u{1}', '\u{7f}', '\u{8}', '\u{c}',
            '0', '7', 'a', ' ', '/', '*',
        ]),
    ];
    prop::collection::vec(ch, 0..6)
        .prop_map(String::from_iter)
        .boxed()
}

fn plain_var(name: String) -> Expr {
    ex(ExprKind::Var(Var {
        namespace: None,
        negated: false,
        name,
        annots: None,
        span: Span::default(),
    }))
}

fn bool_lit(b: bool) -> Expr {
    ex(ExprKind::Literal(Literal {
        namespace: None,
        negated: false,
        functor: if b { "true" } else { "false" }.into(),
        args: Vec::new(),
        annots: None,
        span: Span::default(),
    }))
}

/// A list whose elements come from `elem`; the tail is a plain variable or a list.
fn list(elem: BoxedStrategy<Expr>, non_empty: bool) -> BoxedStrategy<ListExpr> {
    let tail = prop_oneof![
        var_name().prop_map(plain_var),
        prop::collection::vec(elem.clone(), 0..2).prop_map(|elems| ex(ExprKind::List(ListExpr {
            elems,
            tail: None,
            span: Span::default(),
        }))),
    ];
    (
        prop::collection::vec(elem, 0..3),
        prop::option::weighted(0.25, tail),
    )
        .prop_filter("annotations are never empty", move |(e, t)| {
            !non_empty || !e.is_empty() || t.is_some()
        })
        .prop_map(|(elems, tail)| ListExpr {
            elems,
            tail: tail.map(Box::new),
            span: Span::default(),
        })
        .boxed()
}

fn annots(elem: BoxedStrategy<Expr>) -> BoxedStrategy<Option<ListExpr>> {
    prop::option::weighted(0.2, list(elem, true)).boxed()
}

/// A literal that is not an internal action (nor `true`/`false`), with sub-terms from `sub`.
fn ordinary_literal(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Literal> {
    (
        prop::option::weighted(0.15, namespace()),
        prop::bool::weighted(0.15),
        functor(),
        prop::collection::vec(sub.clone(), 0..3),
        annots(sub),
    )
        .prop_map(|(namespace, negated, functor, args, annots)| Literal {
            namespace,
            negated,
            functor,
            args,
            annots,
            span: Span::default(),
        })
        .boxed()
}

/// An internal action: never negated nor annotated.
fn ia_literal(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Literal> {
    (
        prop::option::weighted(0.1, namespace()),
        ia_functor(),
        prop::collection::vec(sub, 0..3),
    )
        .prop_map(|(namespace, functor, args)| Literal {
            namespace,
            negated: false,
            functor,
            args,
            annots: None,
            span: Span::default(),
        })
        .boxed()
}

fn var(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Expr> {
    (
        prop::option::weighted(0.1, namespace()),
        prop::bool::weighted(0.1),
        var_name(),
        annots(sub),
    )
        .prop_map(|(namespace, negated, name, annots)| {
            ex(ExprKind::Var(Var {
                namespace,
                negated,
                name,
                annots,
                span: Span::default(),
            }))
        })
        .boxed()
}

/// A literal or variable that can be a goal, a trigger's literal or a belief update.
fn goal_literal(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Expr> {
    prop_oneof![
        6 => ordinary_literal(sub.clone()).prop_map(|l| ex(ExprKind::Literal(l))),
        2 => var(sub),
        1 => any::<bool>().prop_map(bool_lit),
    ]
    .boxed()
}

/// A literal of any kind, or a variable: what an action step holds.
fn any_literal(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Expr> {
    prop_oneof![
        3 => goal_literal(sub.clone()),
        1 => ia_literal(sub).prop_map(|l| ex(ExprKind::Literal(l))),
    ]
    .boxed()
}

fn leaf() -> BoxedStrategy<Expr> {
    let none = Just(ex(ExprKind::Int(0))).boxed();
    prop_oneof![
        4 => goal_literal(none.clone()),
        1 => ia_literal(none.clone()).prop_map(|l| ex(ExprKind::Literal(l))),
        2 => int().prop_map(|n| ex(ExprKind::Int(n))),
        1 => float().prop_map(|x| ex(ExprKind::Float(x))),
        1 => string().prop_map(|s| ex(ExprKind::Str(s))),
        1 => Just(ex(ExprKind::List(ListExpr { elems: Vec::new(), tail: None, span: Span::default() }))),
    ]
    .prop_map(|mut e| {
        // Leaves have no sub-terms: drop the placeholder arguments of literals.
        if let ExprKind::Literal(l) = &mut e.kind {
            l.args.clear();
            l.annots = None;
        }
        if let ExprKind::Var(v) = &mut e.kind {
            v.annots = None;
        }
        e
    })
    .boxed()
}

fn rel_op() -> impl Strategy<Value = RelOp> {
    prop::sample::select(vec![
        RelOp::Lt,
        RelOp::Le,
        RelOp::Gt,
        RelOp::Ge,
        RelOp::Eq,
        RelOp::Ne,
        RelOp::Unify,
        RelOp::Univ,
    ])
}

fn arith_op() -> impl Strategy<Value = ArithOp> {
    prop::sample::select(vec![
        ArithOp::Add,
        ArithOp::Sub,
        ArithOp::Mul,
        ArithOp::Div,
        ArithOp::IntDiv,
        ArithOp::Mod,
        ArithOp::Pow,
    ])
}

fn rel(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Expr> {
    (rel_op(), sub.clone(), sub)
        .prop_map(|(op, a, b)| ex(ExprKind::Rel(op, bx(a), bx(b))))
        .boxed()
}

/// Any expression, nested at most `depth` levels.
fn expr(depth: u32) -> BoxedStrategy<Expr> {
    if depth == 0 {
        return leaf();
    }
    let sub = expr(depth - 1);
    prop_oneof![
        4 => leaf(),
        3 => ordinary_literal(sub.clone()).prop_map(|l| ex(ExprKind::Literal(l))),
        1 => ia_literal(sub.clone()).prop_map(|l| ex(ExprKind::Literal(l))),
        1 => var(sub.clone()),
        2 => list(sub.clone(), false).prop_map(|l| ex(ExprKind::List(l))),
        2 => (prop::bool::ANY, sub.clone()).prop_map(|(neg, e)| ex(ExprKind::Unary(
            if neg { UnaryOp::Neg } else { UnaryOp::Plus },
            bx(e)
        ))),
        3 => (arith_op(), sub.clone(), sub.clone())
            .prop_map(|(op, a, b)| ex(ExprKind::Arith(op, bx(a), bx(b)))),
        2 => rel(sub.clone()),
        1 => sub.clone().prop_map(|e| ex(ExprKind::Not(bx(e)))),
        2 => (sub.clone(), sub.clone()).prop_map(|(a, b)| ex(ExprKind::And(bx(a), bx(b)))),
        2 => (sub.clone(), sub).prop_map(|(a, b)| ex(ExprKind::Or(bx(a), bx(b)))),
        1 => plan_term(depth - 1),
    ]
    .boxed()
}

/// A logical formula: what `?` accepts.
fn formula(depth: u32) -> BoxedStrategy<Expr> {
    let sub = expr(depth.saturating_sub(1));
    prop_oneof![
        3 => goal_literal(sub.clone()),
        1 => rel(sub.clone()),
        1 => sub.clone().prop_map(|e| ex(ExprKind::Not(bx(e)))),
        1 => (sub.clone(), sub.clone()).prop_map(|(a, b)| ex(ExprKind::And(bx(a), bx(b)))),
        1 => (sub.clone(), sub).prop_map(|(a, b)| ex(ExprKind::Or(bx(a), bx(b)))),
    ]
    .boxed()
}

// ----- plans and bodies --------------------------------------------------------------------

fn trigger(sub: BoxedStrategy<Expr>) -> BoxedStrategy<Trigger> {
    (
        prop::sample::select(vec![TriggerOp::Add, TriggerOp::Del, TriggerOp::GoalState]),
        prop::sample::select(vec![
            TriggerKind::Belief,
            TriggerKind::Achieve,
            TriggerKind::Test,
        ]),
        goal_literal(sub),
    )
        .prop_map(|(op, kind, literal)| Trigger {
            op,
            kind,
            literal,
            span: Span::default(),
        })
        .boxed()
}

/// A plan label; a variable name only inside a plan term.
fn label(sub: BoxedStrategy<Expr>, allow_var: bool) -> BoxedStrategy<Label> {
    let name = if allow_var {
        prop_oneof![3 => functor(), 1 => var_name()].boxed()
    } else {
        functor()
    };
    (prop::option::weighted(0.8, name), annots(sub))
        .prop_map(|(name, annots)| Label {
            name,
            annots,
            span: Span::default(),
        })
        .boxed()
}

/// A plan term `{ ... }`: the four kinds, each in the shape the parser gives it.
fn plan_term(depth: u32) -> BoxedStrategy<Expr> {
    let sub = expr(depth.saturating_sub(1));
    let plan = (
        prop::option::weighted(0.3, label(sub.clone(), true)),
        trigger(sub.clone()),
        prop::option::weighted(0.4, expr(depth)),
        prop::option::weighted(0.6, body_of(depth, 1, 3)),
    )
        .prop_filter("`{ +!g }` is a trigger, `{ +b }` a body", |(l, _, c, b)| {
            l.is_some() || c.is_some() || b.is_some()
        })
        .prop_map(|(label, trigger, context, body)| {
            PlanTermKind::Plan(Plan {
                label,
                trigger,
                context,
                goal_condition: None,
                body,
                sub_plans: Vec::new(),
                span: Span::default(),
            })
        });
    let trig = trigger(sub.clone())
        .prop_filter("`{ +b }` is a body", |t| {
            t.kind != TriggerKind::Belief || t.op == TriggerOp::GoalState
        })
        .prop_map(PlanTermKind::Trigger);
    let rule = (
        prop_oneof![
            3 => ordinary_literal(sub.clone()),
            1 => ia_literal(sub.clone()),
        ],
        expr(depth),
    )
        .prop_map(|(head, body)| {
            PlanTermKind::Rule(Rule {
                head,
                body,
                span: Span::default(),
            })
        });
    prop_oneof![
        2 => plan,
        1 => trig,
        2 => body_of(depth, 0, 3).prop_map(PlanTermKind::Body),
        1 => rule,
    ]
    .prop_map(|kind| {
        ex(ExprKind::PlanTerm(Box::new(PlanTerm {
            kind,
            span: Span::default(),
        })))
    })
    .boxed()
}

/// A body of `min..=max` steps nested at most `depth` levels.
fn body_of(depth: u32, min: usize, max: usize) -> BoxedStrategy<Body> {
    prop::collection::vec(step(depth), min..=max)
        .prop_map(body)
        .boxed()
}

fn is_single_fork(b: &Body, op: ForkOp) -> bool {
    matches!(b.steps.as_slice(), [Step { kind: StepKind::Fork { op: o, .. }, .. }] if *o == op)
}

/// One body step nested at most `depth` levels.
fn step(depth: u32) -> BoxedStrategy<Step> {
    let e = expr(depth.min(2));
    let sub = expr(depth.min(2).saturating_sub(1));
    let lit = goal_literal(sub.clone());
    let lit_or_plan = if depth == 0 {
        lit.clone()
    } else {
        prop_oneof![3 => lit.clone(), 1 => plan_term(depth - 1)].boxed()
    };
    let simple = prop_oneof![
        4 => any_literal(sub.clone()).prop_map(StepKind::Action),
        2 => lit.clone().prop_map(StepKind::Achieve),
        1 => lit.clone().prop_map(StepKind::AchieveNewFocus),
        2 => formula(depth.min(2)).prop_map(StepKind::Test),
        2 => lit_or_plan.clone().prop_map(StepKind::AddBel),
        1 => lit_or_plan.clone().prop_map(StepKind::AddBelEnd),
        1 => lit.clone().prop_map(StepKind::AddBelNewFocus),
        1 => lit_or_plan.prop_map(StepKind::DelBel),
        1 => lit.clone().prop_map(StepKind::DelAddBel),
        1 => lit.prop_map(StepKind::DelBelNewFocus),
        2 => rel(sub).prop_map(StepKind::Constraint),
    ]
    .prop_map(st)
    .boxed();
    if depth == 0 {
        return simple;
    }
    let block = body_of(depth - 1, 0, 2);
    let non_empty = body_of(depth - 1, 1, 2);
    let fork = prop::sample::select(vec![ForkOp::And, ForkOp::Or]).prop_flat_map(move |op| {
        prop::collection::vec(
            body_of(depth - 1, 1, 2).prop_filter("forks of one kind are flattened", move |b| {
                !is_single_fork(b, op)
            }),
            2..=3,
        )
        .prop_map(move |branches| StepKind::Fork { op, branches })
    });
    prop_oneof![
        6 => simple,
        1 => (
            prop::collection::vec((e.clone(), block.clone()), 1..=2),
            prop::option::weighted(0.4, non_empty),
        )
            .prop_map(|(branches, else_body)| StepKind::If { branches, else_body })
            .prop_map(st),
        1 => (e.clone(), block.clone())
            .prop_map(|(cond, body)| st(StepKind::While { cond, body })),
        1 => (e, block).prop_map(|(cond, body)| st(StepKind::For { cond, body })),
        1 => fork.prop_map(st),
        1 => body_of(depth - 1, 2, 3).prop_map(|b| st(StepKind::Group(b))),
    ]
    .boxed()
}

/// A plan as an item or a sub-plan (with a goal condition and, at `depth > 0`, sub-plans).
fn plan(depth: u32) -> BoxedStrategy<Plan> {
    let sub = expr(1);
    let sub_plans = if depth == 0 {
        Just(Vec::new()).boxed()
    } else {
        prop_oneof![
            4 => Just(Vec::new()),
            1 => prop::collection::vec(plan(depth - 1), 1..=2),
        ]
        .boxed()
    };
    (
        prop::option::weighted(0.3, label(sub.clone(), false)),
        trigger(sub),
        prop::option::weighted(0.5, expr(2)),
        prop::option::weighted(0.15, expr(1)),
        prop::option::weighted(0.8, body_of(2, 1, 4)),
        sub_plans,
    )
        .prop_map(
            |(label, trigger, context, goal_condition, body, sub_plans)| Plan {
                label,
                trigger,
                context,
                goal_condition,
                body,
                sub_plans,
                span: Span::default(),
            },
        )
        .boxed()
}

fn item(depth: u32) -> BoxedStrategy<Item> {
    let sub = expr(1);
    let lit = ordinary_literal(sub.clone());
    let directive = (
        plain_atom(),
        prop::collection::vec(sub.clone(), 0..3),
        annots(sub),
        if depth == 0 {
            Just(None).boxed()
        } else {
            prop::option::weighted(0.5, prop::collection::vec(item(depth - 1), 0..3)).boxed()
        },
    )
        .prop_map(|(name, args, annots, block)| {
            Item::Directive(Directive {
                name,
                args,
                annots,
                block,
                span: Span::default(),
            })
        });
    prop_oneof![
        2 => lit.clone().prop_map(|literal| Item::Belief(Belief { literal, span: Span::default() })),
        1 => (lit.clone(), expr(2)).prop_map(|(head, body)| Item::Rule(Rule {
            head,
            body,
            span: Span::default(),
        })),
        1 => lit.prop_map(|literal| Item::InitialGoal(InitialGoal { literal, span: Span::default() })),
        4 => plan(1).prop_map(Item::Plan),
        1 => directive,
    ]
    .boxed()
}

fn agent() -> BoxedStrategy<AgentFile> {
    prop::collection::vec(item(1), 0..5)
        .prop_map(|items| AgentFile {
            items,
            span: Span::default(),
        })
        .boxed()
}

// ----- generated trees ---------------------------------------------------------------------

fn check_agent(ast: &AgentFile) -> Result<(), TestCaseError> {
    let text = print_agent(ast);
    let (back, diags) = parse_agent(FileId(0), &text);
    prop_assert!(
        diags.is_empty(),
        "printed text does not parse:\n{text}\n{diags:#?}"
    );
    prop_assert_eq!(cleared(&back), cleared(ast), "printed text:\n{}", text);
    prop_assert_eq!(print_agent(&back), text);
    Ok(())
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn generated_agents_roundtrip(ast in agent()) {
        check_agent(&ast)?;
    }

    #[test]
    fn generated_expressions_roundtrip(e in expr(4)) {
        let text = print_expr(&e);
        match parse_expr(FileId(0), &text) {
            Ok(back) => prop_assert_eq!(cleared(&back), cleared(&e), "printed text: {}", text),
            Err(d) => prop_assert!(false, "printed text does not parse: {}\n{:#?}", text, d),
        }
    }

    #[test]
    fn generated_bodies_roundtrip(b in body_of(3, 1, 4)) {
        // A body reads back as the body of a plan.
        let text = format!("+!g <- {}.\n", print_body(&b));
        let (back, diags) = parse_agent(FileId(0), &text);
        prop_assert!(diags.is_empty(), "printed text does not parse:\n{}\n{:#?}", text, diags);
        let got = match back.items.as_slice() {
            [Item::Plan(Plan { body: Some(got), .. })] => cleared(got),
            _ => return Err(TestCaseError::fail(format!("not one plan: {text}"))),
        };
        prop_assert_eq!(got, cleared(&b), "printed text: {}", text);
    }
}

// ----- hand-picked trees -------------------------------------------------------------------

#[test]
fn tricky_shapes_roundtrip() {
    let atom = |s: &str| {
        ex(ExprKind::Literal(Literal {
            namespace: None,
            negated: false,
            functor: s.into(),
            args: Vec::new(),
            annots: None,
            span: Span::default(),
        }))
    };
    let neg = |e: Expr| ex(ExprKind::Unary(UnaryOp::Neg, bx(e)));
    let fork = |op, branches| st(StepKind::Fork { op, branches });
    let one = |s: Step| body(vec![s]);
    let add = |e: Expr| st(StepKind::AddBel(e));
    // `{ +b |&| c }` would read as a trigger: the printer writes `{ (+b |&| c) }`.
    let belief_fork = ex(ExprKind::PlanTerm(Box::new(PlanTerm {
        kind: PlanTermKind::Body(body(vec![
            fork(
                ForkOp::And,
                vec![one(add(atom("b"))), one(st(StepKind::Action(atom("c"))))],
            ),
            add(atom("d")),
        ])),
        span: Span::default(),
    })));
    // `-X = 1` as a step would read as a belief deletion.
    let constraint = st(StepKind::Constraint(ex(ExprKind::Rel(
        RelOp::Unify,
        bx(neg(plain_var("X".into()))),
        bx(ex(ExprKind::Int(1))),
    ))));
    let ast = AgentFile {
        items: vec![Item::Plan(Plan {
            label: None,
            trigger: Trigger {
                op: TriggerOp::Add,
                kind: TriggerKind::Achieve,
                literal: atom("g"),
                span: Span::default(),
            },
            context: Some(neg(neg(ex(ExprKind::Int(5))))),
            goal_condition: None,
            body: Some(body(vec![
                st(StepKind::Action(ex(ExprKind::Literal(Literal {
                    namespace: None,
                    negated: false,
                    functor: ".print".into(),
                    args: vec![belief_fork],
                    annots: None,
                    span: Span::default(),
                })))),
                constraint.clone(),
                fork(ForkOp::Or, vec![one(constraint), one(add(atom("e")))]),
            ])),
            sub_plans: Vec::new(),
            span: Span::default(),
        })],
        span: Span::default(),
    };
    check_agent(&ast).unwrap();
}

// ----- files -------------------------------------------------------------------------------

/// Every `.asl` file under `dir`, recursively, skipping directories named `invalid`.
fn asl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n != "invalid") {
                asl_files(&path, out);
            }
        } else if path.extension().is_some_and(|x| x == "asl") {
            out.push(path);
        }
    }
}

/// Parses, prints, re-parses; returns a description of what went wrong, if anything.
fn roundtrip_file(path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    let (ast, diags) = parse_agent(FileId(0), &text);
    if !diags.is_empty() {
        return Some(format!("{}: does not parse: {diags:?}", path.display()));
    }
    let printed = print_agent(&ast);
    let (back, diags) = parse_agent(FileId(0), &printed);
    if !diags.is_empty() {
        return Some(format!(
            "{}: printed text does not parse: {diags:?}\n{printed}",
            path.display()
        ));
    }
    if cleared(&back) != cleared(&ast) {
        return Some(format!(
            "{}: printed text parses to another tree:\n{printed}",
            path.display()
        ));
    }
    let again = print_agent(&back);
    if again != printed {
        return Some(format!(
            "{}: printing is not idempotent:\n{printed}\n---\n{again}",
            path.display()
        ));
    }
    None
}

#[test]
fn test_files_roundtrip() {
    let mut files = Vec::new();
    asl_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests"),
        &mut files,
    );
    files.sort();
    let failures: Vec<String> = files.iter().filter_map(|p| roundtrip_file(p)).collect();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Jason's own examples, when a copy is present (it is not part of the repository). Files
/// that Jason's parser would accept but ours does not are the corpus test's business.
#[test]
fn jason_examples_roundtrip() {
    let mut files = Vec::new();
    asl_files(Path::new("/tmp/jason/asl"), &mut files);
    files.sort();
    let failures: Vec<String> = files
        .iter()
        .filter_map(|p| roundtrip_file(p))
        .filter(|f| !f.contains(": does not parse:"))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
