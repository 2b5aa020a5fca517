//! Properties of the model's terms, unification and printer (`bdi_check::model`).
//!
//! Random terms are drawn from a small signature so that unifications often succeed and
//! variables are often shared between the two sides.

use bdi_check::model::{term_from_expr, unifier, unify, Substitution, Term, Var};
use bdi_check::syntax::{parse_expr, FileId};
use proptest::prelude::*;
use std::cmp::Ordering;

fn atom() -> impl Strategy<Value = Term> {
    prop::sample::select(vec!["a", "b", "c", "source"]).prop_map(Term::atom)
}

fn var() -> impl Strategy<Value = Term> {
    prop::sample::select(vec!["X", "Y", "Z", "_W"]).prop_map(Term::var)
}

fn number() -> impl Strategy<Value = Term> {
    prop_oneof![
        (-3i64..4).prop_map(Term::int),
        prop::sample::select(vec![1.5, -0.25, 0.1, 1e-5, 2.5e20]).prop_map(Term::num),
    ]
}

fn string() -> impl Strategy<Value = Term> {
    prop::sample::select(vec!["", "s", "say \"hi\"", "a\\b", "l1\nl2"]).prop_map(Term::string)
}

/// Terms without annotations.
fn plain_term() -> impl Strategy<Value = Term> {
    let leaf = prop_oneof![
        3 => atom(),
        4 => var(),
        1 => number(),
        1 => string(),
        1 => Just(Term::nil()),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            (
                prop::sample::select(vec!["f", "g"]),
                any::<bool>(),
                prop::collection::vec(inner.clone(), 1..3)
            )
                .prop_map(|(f, neg, args)| Term::literal(f, neg, args, vec![])),
            (
                prop::collection::vec(inner.clone(), 0..3),
                prop::option::of(var())
            )
                .prop_map(|(elems, tail)| Term::list_with_tail(
                    elems,
                    tail.unwrap_or_else(Term::nil)
                )),
        ]
    })
}

/// Terms whose literals may carry annotations (themselves possibly annotated).
fn annotated_term() -> impl Strategy<Value = Term> {
    let leaf = prop_oneof![
        3 => atom(),
        4 => var(),
        1 => number(),
        1 => Just(Term::nil()),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            (
                prop::sample::select(vec!["f", "g", "p"]),
                any::<bool>(),
                prop::collection::vec(inner.clone(), 0..3),
                prop::collection::vec(inner.clone(), 0..3),
            )
                .prop_map(|(f, neg, args, annots)| Term::literal(f, neg, args, annots)),
            prop::collection::vec(inner, 0..3).prop_map(Term::list),
        ]
    })
}

/// `t` with its variables `X`, `Y`, `Z`, `_W` replaced by `bs[0..4]` (when given).
fn instantiate(t: &Term, bs: &[Term]) -> Term {
    t.map_vars(&mut |v| {
        let i = ["X", "Y", "Z", "_W"].iter().position(|n| *n == v.name());
        i.and_then(|i| bs.get(i))
            .cloned()
            .unwrap_or_else(|| Term::Var(v.clone()))
    })
}

/// `t` with `extra` added to the annotations of every literal (not inside annotations).
fn widen(t: &Term, extra: &Term) -> Term {
    match t {
        Term::Cons(c) => Term::cons(widen(c.head(), extra), widen(c.tail(), extra)),
        _ if t.is_literal() => {
            let args = t.args().iter().map(|a| widen(a, extra)).collect();
            let mut annots = t.annots().to_vec();
            annots.push(extra.clone());
            Term::literal(t.functor().unwrap(), t.is_negated(), args, annots)
        }
        _ => t.clone(),
    }
}

/// Pairs of plain terms: unrelated, or a term and an instance of it (in either order), so
/// that unification succeeds often.
fn plain_pair() -> impl Strategy<Value = (Term, Term)> {
    prop_oneof![
        (plain_term(), plain_term()),
        (
            plain_term(),
            prop::collection::vec(plain_term(), 0..4),
            any::<bool>()
        )
            .prop_map(|(t, bs, swap)| {
                let i = instantiate(&t, &bs);
                if swap {
                    (i, t)
                } else {
                    (t, i)
                }
            }),
    ]
}

/// Pairs of annotated terms: unrelated, or a term and an instance of it whose literals
/// carry one more annotation (the first is then below the second in the subset order).
fn annotated_pair() -> impl Strategy<Value = (Term, Term)> {
    prop_oneof![
        (annotated_term(), annotated_term()),
        (
            annotated_term(),
            prop::collection::vec(annotated_term(), 0..4),
            annotated_term(),
        )
            .prop_map(|(t, bs, extra)| {
                let i = widen(&instantiate(&t, &bs), &extra);
                (t, i)
            }),
    ]
}

/// `a` is `b` up to annotations: each annotation of a literal in `a` is, recursively, such
/// a match of some annotation of the literal at the same place in `b`.
fn sub(a: &Term, b: &Term) -> bool {
    match (a, b) {
        (Term::Cons(x), Term::Cons(y)) => sub(x.head(), y.head()) && sub(x.tail(), y.tail()),
        _ if a.is_literal() && b.is_literal() => {
            a.functor() == b.functor()
                && a.is_negated() == b.is_negated()
                && a.arity() == b.arity()
                && a.args().iter().zip(b.args()).all(|(x, y)| sub(x, y))
                && a.annots()
                    .iter()
                    .all(|x| b.annots().iter().any(|y| sub(x, y)))
        }
        _ => a == b,
    }
}

/// No variable of `t` is bound in `s`.
fn fully_resolved(t: &Term, s: &Substitution) -> bool {
    t.vars().iter().all(|v| s.get(v).is_none())
}

/// A substitution built by unifying random pairs (each attempt may fail).
fn some_substitution(pairs: &[(Term, Term)]) -> Substitution {
    let mut s = Substitution::new();
    for (a, b) in pairs {
        unify(a, b, &mut s);
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn unifier_equalizes_plain_terms((a, b) in plain_pair()) {
        if let Some(s) = unifier(&a, &b) {
            prop_assert_eq!(s.apply(&a), s.apply(&b));
        }
    }

    #[test]
    fn unifier_respects_annotation_subset((a, b) in annotated_pair()) {
        if let Some(s) = unifier(&a, &b) {
            let (ia, ib) = (s.apply(&a), s.apply(&b));
            prop_assert!(sub(&ia, &ib), "{} vs {} under {}", ia, ib, s);
        }
    }

    #[test]
    fn unification_is_symmetric_without_annotations((a, b) in plain_pair()) {
        let ab = unifier(&a, &b);
        let ba = unifier(&b, &a);
        prop_assert_eq!(ab.is_some(), ba.is_some());
        if let (Some(s), Some(t)) = (ab, ba) {
            // Most general unifiers: each instance is an instance of the other.
            let (x, y) = (s.apply(&a), t.apply(&a));
            prop_assert!(unifier(&x, &y).is_some());
        }
    }

    #[test]
    fn failure_leaves_substitution_unchanged(
        pre in prop::collection::vec(annotated_pair(), 0..3),
        (a, b) in annotated_pair(),
    ) {
        let mut s = some_substitution(&pre);
        let before = s.clone();
        if !unify(&a, &b, &mut s) {
            prop_assert_eq!(s, before);
        } else {
            // Success only adds bindings.
            for (v, t) in before.iter() {
                prop_assert_eq!(s.get(v), Some(t));
            }
        }
    }

    #[test]
    fn term_unifies_with_itself(
        pre in prop::collection::vec(annotated_pair(), 0..3),
        t in annotated_term(),
    ) {
        let s = unifier(&t, &t).expect("a term unifies with itself");
        prop_assert!(s.is_empty());
        let mut s = some_substitution(&pre);
        prop_assert!(unify(&t, &t, &mut s));
    }

    #[test]
    fn occurs_check_refuses_cycles(t in annotated_term()) {
        for v in t.vars() {
            if t != Term::Var(v.clone()) {
                prop_assert!(unifier(&Term::Var(v.clone()), &t).is_none());
                prop_assert!(unifier(&t, &Term::Var(v)).is_none());
            }
        }
    }

    #[test]
    fn resolution_terminates_and_is_idempotent(
        pairs in prop::collection::vec(annotated_pair(), 1..6),
        t in annotated_term(),
    ) {
        let s = some_substitution(&pairs);
        let r = s.apply(&t);
        prop_assert!(fully_resolved(&r, &s));
        prop_assert_eq!(s.apply(&r), r.clone());
        for (v, _) in s.iter() {
            prop_assert!(fully_resolved(&s.resolve(v), &s));
        }
        // The resolved form means the same.
        prop_assert_eq!(s.resolved().apply(&t), r);
    }

    #[test]
    fn order_is_total_and_agrees_with_eq(
        a in annotated_term(),
        b in annotated_term(),
        c in annotated_term(),
    ) {
        prop_assert_eq!(a.cmp(&b) == Ordering::Equal, a == b);
        prop_assert_eq!(a.cmp(&b), b.cmp(&a).reverse());
        if a <= b && b <= c {
            prop_assert!(a <= c);
        }
    }

    #[test]
    fn printed_terms_parse_back(t in plain_term()) {
        let text = t.to_string();
        let e = parse_expr(FileId(0), &text);
        prop_assert!(e.is_ok(), "{} does not parse: {:?}", text, e);
        let back = term_from_expr(&e.unwrap());
        prop_assert_eq!(back, Ok(t), "{}", text);
    }

    #[test]
    fn printed_annotated_terms_parse_back(t in annotated_term()) {
        let text = t.to_string();
        let back = term_from_expr(&parse_expr(FileId(0), &text).expect("parses"));
        prop_assert_eq!(back, Ok(t), "{}", text);
    }
}

#[test]
fn x_against_f_x_fails() {
    let x = Term::var("X");
    let fx = Term::structure("f", vec![x.clone()]);
    let mut s = Substitution::new();
    assert!(!unify(&x, &fx, &mut s));
    assert!(s.is_empty());
    assert!(!unify(&fx, &x, &mut s));
    assert!(s.is_empty());
}

#[test]
fn printer_table() {
    let a = Term::atom;
    let s = Term::structure;
    let cases: Vec<(Term, &str)> = vec![
        (s("cupAt", vec![a("cup1"), a("table")]), "cupAt(cup1,table)"),
        (a("table"), "table"),
        (Term::string("a string"), "\"a string\""),
        (Term::string("say \"hi\""), r#""say \"hi\"""#),
        (Term::string("a\\b"), r#""a\\b""#),
        (Term::string("l1\nl2"), r#""l1\nl2""#),
        (Term::list(vec![a("a"), a("b")]), "[a,b]"),
        (
            Term::list_with_tail(vec![a("a"), a("b")], Term::var("T")),
            "[a,b|T]",
        ),
        (Term::nil(), "[]"),
        (
            Term::literal(
                "p",
                false,
                vec![a("a")],
                vec![a("x"), s("source", vec![a("self")])],
            ),
            "p(a)[source(self),x]",
        ),
        (Term::literal("p", true, vec![], vec![]), "~p"),
        (
            Term::literal("at", true, vec![a("r1"), Term::int(2)], vec![]),
            "~at(r1,2)",
        ),
        (Term::int(3), "3"),
        (Term::int(-2), "-2"),
        (Term::num(3.0), "3"),
        (Term::num(-0.0), "0"),
        (Term::num(1.5), "1.5"),
        (Term::num(0.1), "0.1"),
        (Term::num(1e-5), "1.0E-5"),
        (Term::num(1e20), "1.0E20"),
        (Term::num(1e19), "1.0E19"),
        (Term::num(2.5e20), "2.5E20"),
        (Term::var("X"), "X"),
        (Term::var("_Name"), "_Name"),
        (Term::Var(Var::anonymous(1)), "_1"),
        (
            s(".print", vec![Term::string("at"), Term::var("L")]),
            ".print(\"at\",L)",
        ),
    ];
    for (t, want) in cases {
        assert_eq!(t.to_string(), want);
    }
}

#[test]
fn from_ast_prints_as_jason() {
    let cases = [
        ("cupAt(cup1,table)", "cupAt(cup1,table)"),
        ("cupAt( cup1 , table )", "cupAt(cup1,table)"),
        ("~holding(C)[source(self)]", "~holding(C)[source(self)]"),
        ("p[b, a, b]", "p[a,b]"),
        ("at(X, -1.5)", "at(X,-1.5)"),
        ("[a | [b | T]]", "[a,b|T]"),
        ("msg(\"done\", 2 * 21)", "msg(\"done\",42)"),
        ("p(_, _)", "p(_1,_2)"),
    ];
    for (src, want) in cases {
        let e = parse_expr(FileId(0), src).expect("parses");
        let t = term_from_expr(&e).expect("a term");
        assert_eq!(t.to_string(), want, "{src}");
    }
}
