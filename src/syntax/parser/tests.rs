//! Unit tests of the parser: plan terms as Jason's `rule_plan_term` tells them apart, and
//! bodies with groups and forks.

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
