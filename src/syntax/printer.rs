//! Writes an AST back as Jason AgentSpeak text.
//!
//! The output parses back to the same tree (spans aside): the printer adds exactly the
//! parentheses that Jason's grammar needs, and works around the places where the grammar
//! reads text differently from how a naive printer would write it (a constraint starting with
//! a sign, a plan term whose body starts with a fork on `+b`). Top-level plans are laid out
//! on several lines with Jason's usual 3-space indentation; everything nested inside an
//! expression (plan terms, groups, forks) stays on one line.

use super::ast::*;
use std::fmt::Write as _;

/// Prints a whole agent: every item ends with `.` (or `}` for a directive) and a newline.
pub fn print_agent(file: &AgentFile) -> String {
    let mut out = String::new();
    for item in &file.items {
        item_to(&mut out, item);
    }
    out
}

/// Prints an expression as it would appear where any logical expression is allowed (a
/// context, an argument, a rule body).
pub fn print_expr(e: &Expr) -> String {
    let mut out = String::new();
    expr_to(&mut out, e, Slot::Log);
    out
}

/// Prints one body step on one line.
pub fn print_step(s: &Step) -> String {
    let mut out = String::new();
    step_to(&mut out, s, None);
    out
}

/// Prints a body on one line, steps separated by `"; "`.
pub fn print_body(b: &Body) -> String {
    let mut out = String::new();
    body_to(&mut out, b, None);
    out
}

/// Prints a triggering event such as `+!g(X)`.
pub fn print_trigger(t: &Trigger) -> String {
    let mut out = String::new();
    trigger_to(&mut out, t);
    out
}

/// Prints a plan with its final dot and its sub-plans, laid out on several lines, with no
/// trailing newline.
pub fn print_plan(p: &Plan) -> String {
    let mut out = String::new();
    plan_to(&mut out, p, 0);
    out
}

/// Prints a literal such as `ns::~p(a, B)[source(self)]`.
pub fn print_literal(l: &Literal) -> String {
    let mut out = String::new();
    literal_to(&mut out, l);
    out
}

// ----- items ---------------------------------------------------------------------------------

const INDENT: usize = 3;

fn spaces(out: &mut String, n: usize) {
    out.extend(std::iter::repeat_n(' ', n));
}

fn item_to(out: &mut String, item: &Item) {
    match item {
        Item::Belief(b) => {
            literal_to(out, &b.literal);
            out.push('.');
        }
        Item::Rule(r) => {
            rule_to(out, r);
            out.push('.');
        }
        Item::InitialGoal(g) => {
            out.push('!');
            literal_to(out, &g.literal);
            out.push('.');
        }
        Item::Plan(p) => plan_to(out, p, 0),
        Item::Directive(d) => {
            out.push_str(if d.block.is_some() { "{ begin " } else { "{ " });
            out.push_str(&d.name);
            args_to(out, &d.args);
            if let Some(a) = &d.annots {
                list_to(out, a);
            }
            out.push_str(" }");
            if let Some(items) = &d.block {
                out.push('\n');
                for i in items {
                    item_to(out, i);
                }
                out.push_str("{ end }");
            }
        }
    }
    out.push('\n');
}

fn rule_to(out: &mut String, r: &Rule) {
    literal_to(out, &r.head);
    out.push_str(" :- ");
    expr_to(out, &r.body, Slot::Log);
}

/// A top-level (or sub-) plan starting at column `base`: the header on one line, the body
/// on the following lines after `<-`, then the dot and the sub-plans in braces.
fn plan_to(out: &mut String, p: &Plan, base: usize) {
    plan_head_to(out, p);
    if let Some(b) = &p.body {
        out.push('\n');
        spaces(out, base + INDENT);
        out.push_str("<- ");
        body_to(out, b, Some(base + 2 * INDENT));
    }
    out.push('.');
    if !p.sub_plans.is_empty() {
        out.push_str(" {");
        for sp in &p.sub_plans {
            out.push('\n');
            spaces(out, base + INDENT);
            plan_to(out, sp, base + INDENT);
        }
        out.push('\n');
        spaces(out, base);
        out.push('}');
    }
}

/// `@label trigger : context <: condition`, the part of a plan before its body.
fn plan_head_to(out: &mut String, p: &Plan) {
    if let Some(l) = &p.label {
        out.push('@');
        if let Some(n) = &l.name {
            out.push_str(n);
        }
        match (&l.name, &l.annots) {
            (_, Some(a)) => list_to(out, a),
            // `@` alone is not a label: an unnamed one keeps its (empty) brackets.
            (None, None) => out.push_str("[]"),
            (Some(_), None) => {}
        }
        out.push(' ');
    }
    trigger_to(out, &p.trigger);
    if let Some(c) = &p.context {
        out.push_str(" : ");
        expr_to(out, c, Slot::Log);
    }
    if let Some(c) = &p.goal_condition {
        out.push_str(" <: ");
        expr_to(out, c, Slot::Log);
    }
}

fn trigger_to(out: &mut String, t: &Trigger) {
    out.push_str(match t.op {
        TriggerOp::Add => "+",
        TriggerOp::Del => "-",
        TriggerOp::GoalState => "^",
    });
    out.push_str(match t.kind {
        TriggerKind::Belief => "",
        TriggerKind::Achieve => "!",
        TriggerKind::Test => "?",
    });
    expr_to(out, &t.literal, Slot::Log);
}

// ----- bodies --------------------------------------------------------------------------------

/// Steps separated by `;`: on one line when `indent` is `None`, else one step per line, each
/// continuation line indented to `indent` (the column of the first step).
fn body_to(out: &mut String, b: &Body, indent: Option<usize>) {
    for (i, s) in b.steps.iter().enumerate() {
        if i > 0 {
            match indent {
                None => out.push_str("; "),
                Some(n) => {
                    out.push_str(";\n");
                    spaces(out, n);
                }
            }
        }
        step_to(out, s, indent);
    }
}

/// A statement's body in braces; `indent` is the column of the statement.
fn block_to(out: &mut String, b: &Body, indent: Option<usize>) {
    if b.steps.is_empty() {
        out.push_str("{ }");
        return;
    }
    match indent {
        None => {
            out.push_str("{ ");
            body_to(out, b, None);
            out.push_str(" }");
        }
        Some(n) => {
            out.push_str("{\n");
            spaces(out, n + INDENT);
            body_to(out, b, Some(n + INDENT));
            out.push('\n');
            spaces(out, n);
            out.push('}');
        }
    }
}

/// Whether a step can stand alone as a fork branch: the grammar's `body_formula` without
/// parentheses (statements, groups and forks need them).
fn is_simple(s: &Step) -> bool {
    !matches!(
        s.kind,
        StepKind::Group(_)
            | StepKind::If { .. }
            | StepKind::While { .. }
            | StepKind::For { .. }
            | StepKind::Fork { .. }
    )
}

fn step_to(out: &mut String, s: &Step, indent: Option<usize>) {
    let prefixed = |out: &mut String, prefix: &str, e: &Expr| {
        out.push_str(prefix);
        expr_to(out, e, Slot::Log);
    };
    match &s.kind {
        StepKind::Action(e) => expr_to(out, e, Slot::Log),
        StepKind::Achieve(e) => prefixed(out, "!", e),
        StepKind::AchieveNewFocus(e) => prefixed(out, "!!", e),
        StepKind::Test(e) => prefixed(out, "?", e),
        StepKind::AddBel(e) => prefixed(out, "+", e),
        StepKind::AddBelEnd(e) => prefixed(out, "+>", e),
        StepKind::AddBelNewFocus(e) => prefixed(out, "++", e),
        StepKind::DelBel(e) => prefixed(out, "-", e),
        StepKind::DelAddBel(e) => prefixed(out, "-+", e),
        StepKind::DelBelNewFocus(e) => prefixed(out, "--", e),
        StepKind::Constraint(e) => {
            let text = print_expr(e);
            // `-X = Y` as a step would read as the belief deletion `-(X = Y)`.
            if text.starts_with(['+', '-']) {
                out.push('(');
                out.push_str(&text);
                out.push(')');
            } else {
                out.push_str(&text);
            }
        }
        StepKind::If {
            branches,
            else_body,
        } => {
            for (i, (cond, body)) in branches.iter().enumerate() {
                out.push_str(if i == 0 { "if (" } else { " elif (" });
                expr_to(out, cond, Slot::Log);
                out.push_str(") ");
                block_to(out, body, indent);
            }
            if let Some(b) = else_body {
                out.push_str(" else ");
                block_to(out, b, indent);
            }
        }
        StepKind::While { cond, body } => {
            out.push_str("while (");
            expr_to(out, cond, Slot::Log);
            out.push_str(") ");
            block_to(out, body, indent);
        }
        StepKind::For { cond, body } => {
            out.push_str("for (");
            expr_to(out, cond, Slot::Log);
            out.push_str(") ");
            block_to(out, body, indent);
        }
        StepKind::Fork { op, branches } => {
            let sep = match op {
                ForkOp::And => " |&| ",
                ForkOp::Or => " ||| ",
            };
            for (i, b) in branches.iter().enumerate() {
                if i > 0 {
                    out.push_str(sep);
                }
                match b.steps.as_slice() {
                    [one] if is_simple(one) => step_to(out, one, None),
                    _ => group_to(out, b),
                }
            }
        }
        StepKind::Group(b) => group_to(out, b),
    }
}

fn group_to(out: &mut String, b: &Body) {
    out.push_str("( ");
    body_to(out, b, None);
    out.push_str(" )");
}

/// The body of a plan term `{ ... }`. A first step `+b`/`-b` followed by a fork operator
/// would be read as a trigger (`{ +b |&| c }` is refused, by Jason too), so such a fork is
/// written in parentheses, which the parser drops again.
fn plan_term_body_to(out: &mut String, b: &Body) {
    let starts_with_belief_fork = match b.steps.first().map(|s| &s.kind) {
        Some(StepKind::Fork { branches, .. }) => matches!(
            branches.first().map(|b| b.steps.as_slice()),
            Some([Step {
                kind: StepKind::AddBel(e) | StepKind::DelBel(e),
                ..
            }]) if !matches!(e.kind, ExprKind::PlanTerm(_))
        ),
        _ => false,
    };
    for (i, s) in b.steps.iter().enumerate() {
        if i > 0 {
            out.push_str("; ");
        }
        if i == 0 && starts_with_belief_fork {
            out.push('(');
            step_to(out, s, None);
            out.push(')');
        } else {
            step_to(out, s, None);
        }
    }
}

// ----- expressions ---------------------------------------------------------------------------

/// Where an expression stands, i.e. which grammar rule must accept it there. Anything the
/// rule does not accept is written in parentheses (which the parser drops: `( log_expr )` is
/// an `arithm_expr_simple`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Slot {
    /// `log_expr`: anything.
    Log,
    /// `log_expr_trm`: the left of `|`, the right of `&`.
    Trm,
    /// `log_expr_factor`: the left of `&`.
    Factor,
    /// `rel_expr`: after `not`.
    Rel,
    /// An operand of a relation or a list element: `arithm_expr`, string, list, plan term.
    RelOperand,
    /// `arithm_expr`: the left of `+ -`.
    Arith,
    /// `arithm_expr_trm`: the right of `+ -`, the left of `* / div mod`.
    ArithTrm,
    /// `arithm_expr_factor`: the right of `* / div mod` and of `**`.
    ArithFactor,
    /// `arithm_expr_simple`: the left of `**`.
    Simple,
    /// After a unary sign: a number, a literal or a variable.
    Signed,
}

/// The binding strength of an expression's outermost construct (higher binds tighter).
fn strength(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Or(..) => 0,
        ExprKind::And(..) => 1,
        ExprKind::Not(_) => 2,
        ExprKind::Rel(..) => 3,
        ExprKind::Str(_) | ExprKind::List(_) | ExprKind::PlanTerm(_) => 3,
        ExprKind::Arith(ArithOp::Add | ArithOp::Sub, ..) => 4,
        ExprKind::Arith(ArithOp::Pow, ..) => 6,
        ExprKind::Arith(..) => 5,
        ExprKind::Unary(..) => 7,
        ExprKind::Literal(_) | ExprKind::Var(_) | ExprKind::Int(_) | ExprKind::Float(_) => 8,
    }
}

/// Whether `e` can be written without parentheses in `slot`.
fn fits(slot: Slot, e: &Expr) -> bool {
    let s = strength(e);
    // Strings, lists and plan terms are relational operands, not arithmetic ones.
    let term = matches!(
        e.kind,
        ExprKind::Str(_) | ExprKind::List(_) | ExprKind::PlanTerm(_)
    );
    match slot {
        Slot::Log => true,
        Slot::Trm => s >= 1,
        Slot::Factor => s >= 2,
        Slot::Rel => s >= 3,
        Slot::RelOperand => s >= 4 || term,
        Slot::Arith => s >= 4,
        Slot::ArithTrm => s >= 5,
        Slot::ArithFactor => s >= 6,
        Slot::Simple => s >= 7,
        Slot::Signed => s >= 8,
    }
}

fn expr_to(out: &mut String, e: &Expr, slot: Slot) {
    if !fits(slot, e) {
        out.push('(');
        expr_to(out, e, Slot::Log);
        out.push(')');
        return;
    }
    match &e.kind {
        ExprKind::Literal(l) => literal_to(out, l),
        ExprKind::Var(v) => {
            namespace_to(out, &v.namespace);
            if v.negated {
                out.push('~');
            }
            out.push_str(&v.name);
            if let Some(a) = &v.annots {
                list_to(out, a);
            }
        }
        ExprKind::Int(n) => {
            let _ = write!(out, "{n}");
        }
        // `{:?}` keeps a `.0` or an exponent, so the number reads back as a float, exactly.
        ExprKind::Float(x) => {
            let _ = write!(out, "{x:?}");
        }
        ExprKind::Str(s) => string_to(out, s),
        ExprKind::List(l) => list_to(out, l),
        ExprKind::Unary(op, x) => {
            out.push(match op {
                UnaryOp::Neg => '-',
                UnaryOp::Plus => '+',
            });
            expr_to(out, x, Slot::Signed);
        }
        ExprKind::Arith(op, a, b) => {
            let (l, r) = match op {
                ArithOp::Add | ArithOp::Sub => (Slot::Arith, Slot::ArithTrm),
                ArithOp::Pow => (Slot::Simple, Slot::ArithFactor),
                _ => (Slot::ArithTrm, Slot::ArithFactor),
            };
            expr_to(out, a, l);
            out.push(' ');
            out.push_str(op.symbol());
            out.push(' ');
            expr_to(out, b, r);
        }
        ExprKind::Rel(op, a, b) => {
            expr_to(out, a, Slot::RelOperand);
            out.push(' ');
            out.push_str(op.symbol());
            out.push(' ');
            expr_to(out, b, Slot::RelOperand);
        }
        ExprKind::Not(x) => {
            out.push_str("not ");
            expr_to(out, x, Slot::Rel);
        }
        ExprKind::And(a, b) => {
            expr_to(out, a, Slot::Factor);
            out.push_str(" & ");
            expr_to(out, b, Slot::Trm);
        }
        ExprKind::Or(a, b) => {
            expr_to(out, a, Slot::Trm);
            out.push_str(" | ");
            expr_to(out, b, Slot::Log);
        }
        ExprKind::PlanTerm(pt) => plan_term_to(out, pt),
    }
}

fn plan_term_to(out: &mut String, pt: &PlanTerm) {
    match &pt.kind {
        PlanTermKind::Plan(p) => {
            out.push_str("{ ");
            plan_head_to(out, p);
            if let Some(b) = &p.body {
                out.push_str(" <- ");
                body_to(out, b, None);
            }
            out.push_str(" }");
        }
        PlanTermKind::Trigger(t) => {
            out.push_str("{ ");
            trigger_to(out, t);
            out.push_str(" }");
        }
        PlanTermKind::Body(b) if b.steps.is_empty() => out.push_str("{}"),
        PlanTermKind::Body(b) => {
            out.push_str("{ ");
            plan_term_body_to(out, b);
            out.push_str(" }");
        }
        PlanTermKind::Rule(r) => {
            out.push_str("{ ");
            rule_to(out, r);
            out.push_str(" }");
        }
    }
}

fn namespace_to(out: &mut String, ns: &Option<Namespace>) {
    if let Some(ns) = ns {
        match &ns.kind {
            NamespaceKind::Named(n) | NamespaceKind::Var(n) => out.push_str(n),
            NamespaceKind::Current => {}
        }
        out.push_str("::");
    }
}

fn literal_to(out: &mut String, l: &Literal) {
    namespace_to(out, &l.namespace);
    if l.negated {
        out.push('~');
    }
    out.push_str(&l.functor);
    args_to(out, &l.args);
    if let Some(a) = &l.annots {
        list_to(out, a);
    }
}

/// `(a,b)` as Jason prints arguments (no space, like the model's term printer), or nothing
/// when there are no arguments (`p()` is not Jason).
fn args_to(out: &mut String, args: &[Expr]) {
    if args.is_empty() {
        return;
    }
    out.push('(');
    for (i, a) in args.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        expr_to(out, a, Slot::Log);
    }
    out.push(')');
}

fn list_to(out: &mut String, l: &ListExpr) {
    out.push('[');
    for (i, e) in l.elems.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        expr_to(out, e, Slot::RelOperand);
    }
    if let Some(t) = &l.tail {
        out.push('|');
        expr_to(out, t, Slot::Log);
    }
    out.push(']');
}

/// A string literal with the escapes Jason's lexer reads back: the named ones, and octal for
/// the other control characters (so the text stays on one line and printable).
fn string_to(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\u{8}' => out.push_str("\\b"),
            '\r' => out.push_str("\\r"),
            '\u{c}' => out.push_str("\\f"),
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            // Always three digits, so a digit after the escape is not read as part of it.
            c if (c as u32) < 0x20 || c == '\u{7f}' => {
                let _ = write!(out, "\\{:03o}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::parser::{parse_agent, parse_expr};
    use crate::syntax::source::FileId;

    fn expr_roundtrip(src: &str, expected: &str) {
        let e = parse_expr(FileId(0), src).unwrap_or_else(|d| panic!("{src}: {d:?}"));
        assert_eq!(print_expr(&e), expected, "printing {src}");
    }

    #[test]
    fn minimal_parentheses() {
        expr_roundtrip("(a | b) & c", "(a | b) & c");
        expr_roundtrip("a | (b | c)", "a | b | c");
        expr_roundtrip("(a | b) | c", "(a | b) | c");
        expr_roundtrip("not (not a)", "not (not a)");
        expr_roundtrip("not (a = b)", "not a = b");
        expr_roundtrip("(1 - 2) - 3", "1 - 2 - 3");
        expr_roundtrip("1 - (2 - 3)", "1 - (2 - 3)");
        expr_roundtrip("(2 ** 3) ** 4", "(2 ** 3) ** 4");
        expr_roundtrip("2 ** (3 ** 4)", "2 ** 3 ** 4");
        expr_roundtrip("-(-5)", "-(-5)");
        expr_roundtrip("(-2) ** 2", "-2 ** 2");
        expr_roundtrip("-(2 ** 2)", "-(2 ** 2)");
        expr_roundtrip("X = (\"a\")", "X = \"a\"");
        expr_roundtrip("(\"a\") + 1 > 0", "(\"a\") + 1 > 0");
        expr_roundtrip("[(a & b), 1 + 2 * 3]", "[(a & b),1 + 2 * 3]");
        expr_roundtrip("p(a & b, (c))", "p(a & b,c)");
    }

    #[test]
    fn strings_are_escaped() {
        let e = Expr {
            kind: ExprKind::Str("a\"b\\c\n\u{1}7\u{7f}é".into()),
            span: Default::default(),
        };
        assert_eq!(print_expr(&e), r#""a\"b\\c\n\0017\177é""#);
        let back = parse_expr(FileId(0), &print_expr(&e)).unwrap();
        assert_eq!(back.kind, e.kind);
    }

    #[test]
    fn plan_layout() {
        let src = "@l[a] +!g(X) : c(X) <- if (X > 1) { a; b } else { c }; d. { +!h <- e. }\n";
        let (f, d) = parse_agent(FileId(0), src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(
            print_agent(&f),
            "@l[a] +!g(X) : c(X)\n   <- if (X > 1) {\n         a;\n         b\n      } else {\n         c\n      };\n      d. {\n   +!h\n      <- e.\n}\n"
        );
    }
}
