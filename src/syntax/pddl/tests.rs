//! Unit tests of the PDDL front end: the lexer, tree repair, reading, printing and the
//! structural checks.

use super::check::suggest;
use super::lexer::{Atom, Tok};
use super::*;
use crate::syntax::source::Span;

fn parse(text: &str) -> (Option<Domain>, Vec<Diagnostic>) {
    parse_domain(FileId(0), text)
}

fn ok(text: &str) -> Domain {
    let (d, errs) = parse(text);
    assert!(errs.is_empty(), "{errs:#?}");
    d.expect("a domain")
}

#[test]
fn lexes_names_with_dashes_and_comments() {
    let mut errs = Vec::new();
    let toks = lex(FileId(0), "(pick-up ?x_1 - t) ; c\n:Action 3 =", &mut errs);
    assert!(errs.is_empty());
    let atoms: Vec<_> = toks
        .iter()
        .filter_map(|t| match &t.tok {
            Tok::Atom(a) => Some(a.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(
        atoms,
        vec![
            Atom::Name("pick-up".into()),
            Atom::Var("x_1".into()),
            Atom::Dash,
            Atom::Name("t".into()),
            Atom::Keyword(":action".into()),
            Atom::Number("3".into()),
            Atom::Op("=".into()),
        ]
    );
    assert_eq!(toks[1].span, Span::new(FileId(0), 1, 8));
}

#[test]
fn typed_lists_default_to_object_and_share_types() {
    let d = ok("(define (domain d) (:types a b - p c p) \
                (:predicates (q ?x ?y - a ?z)))");
    let ty = |n: &str| d.type_decl(n).unwrap().parent.clone();
    assert_eq!(
        (ty("a"), ty("b"), ty("c"), ty("p")),
        ("p".into(), "p".into(), "object".into(), "object".into())
    );
    let p = d.predicate("q").unwrap();
    let tys: Vec<_> = p.params.iter().map(|v| v.ty.as_str()).collect();
    assert_eq!(tys, ["a", "a", "object"]);
}

#[test]
fn ancestors_and_subtypes() {
    let d = ok("(define (domain d) (:types cup plate - dish dish - item item))");
    assert_eq!(d.type_ancestors("cup"), ["dish", "item", "object"]);
    assert_eq!(d.type_ancestors("object"), Vec::<String>::new());
    assert_eq!(d.type_ancestors("unknown"), ["object"]);
    assert!(d.is_subtype("cup", "item"));
    assert!(d.is_subtype("cup", "cup"));
    assert!(d.is_subtype("item", "object"));
    assert!(!d.is_subtype("item", "cup"));
}

#[test]
fn ancestors_terminate_on_cycles() {
    let (d, errs) = parse("(define (domain d) (:types a - b b - a))");
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(errs[0].message.contains("own ancestor"));
    let d = d.unwrap();
    assert_eq!(d.type_ancestors("a"), ["b", "object"]);
}

#[test]
fn display_round_trips() {
    let src = "(define (domain d) (:predicates (p ?x) (q ?x ?y))
          (:action a :parameters (?x ?y)
            :precondition (and (p ?x) (not (= ?x ?y)) (or (q ?x c) (imply (p ?y) (p ?x)))
                               (exists (?z - object) (q ?z ?x)) (forall (?z) (p ?z)) ())
            :effect (and (p ?x) (not (q ?x ?y)) (forall (?z) (when (p ?z) (not (p ?z)))) ())))";
    let d = ok(src);
    let a = &d.actions[0];
    let pre = print_gd(a.precondition.as_ref().unwrap());
    let eff = print_effect(a.effect.as_ref().unwrap());
    assert_eq!(
        pre,
        "(and (p ?x) (not (= ?x ?y)) (or (q ?x c) (imply (p ?y) (p ?x))) \
         (exists (?z - object) (q ?z ?x)) (forall (?z - object) (p ?z)) (and))"
    );
    assert_eq!(
        eff,
        "(and (p ?x) (not (q ?x ?y)) (forall (?z - object) (when (p ?z) (not (p ?z)))) (and))"
    );
    let again = ok(&format!(
        "(define (domain d) (:predicates (p ?x) (q ?x ?y)) \
         (:action a :parameters (?x ?y) :precondition {pre} :effect {eff}))"
    ));
    assert_eq!(
        print_gd(again.actions[0].precondition.as_ref().unwrap()),
        pre
    );
    assert_eq!(print_effect(again.actions[0].effect.as_ref().unwrap()), eff);
    assert_eq!(
        d.undeclared_constants()
            .iter()
            .map(|c| c.0)
            .collect::<Vec<_>>(),
        ["c"]
    );
    let eff_atoms = a.effect.as_ref().unwrap().atoms();
    assert_eq!(eff_atoms.len(), 3);
    assert!(eff_atoms[0].0 && !eff_atoms[1].0);
}

#[test]
fn keywords_ignore_case_names_do_not() {
    let (_, errs) = parse("(DEFINE (DOMAIN d) (:PREDICATES (p)) (:Action a :Effect (AND (P))))");
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(errs[0].message.contains("undefined predicate `P`"));
    assert_eq!(
        errs[0].help.as_deref(),
        Some("did you mean `p`? (names are case-sensitive)")
    );
}

#[test]
fn deep_nesting_is_refused_without_overflow() {
    for n in [65, 1000, 100_000] {
        let text = format!(
            "(define (domain d) (:predicates (p)) (:action a :precondition {}(p){}))",
            "(not ".repeat(n),
            ")".repeat(n)
        );
        let (_, errs) = parse(&text);
        assert_eq!(errs.len(), 1, "{errs:#?}");
        assert!(errs[0].message.contains("nesting deeper than 64"));
        let (_, errs) = parse(&"(".repeat(n));
        assert!(!errs.is_empty());
    }
    // Just below the bound is fine.
    let text = format!(
        "(define (domain d) (:predicates (p)) (:action a :precondition {}(p){}))",
        "(not ".repeat(60),
        ")".repeat(60)
    );
    ok(&text);
}

#[test]
fn missing_paren_is_repaired_at_next_section() {
    let (d, errs) = parse(
        "(define (domain d) (:predicates (p))\n(:action a :effect (and (p))\n(:action b :effect (p)))",
    );
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(errs[0].message.contains("unclosed"));
    assert_eq!(errs[0].span.unwrap().start, 37);
    assert_eq!(d.unwrap().actions.len(), 2);
}

#[test]
fn problem_files_are_refused() {
    let (d, errs) = parse("(define (problem p) (:domain d))");
    assert!(d.is_none());
    assert_eq!(errs.len(), 1);
    assert_eq!(errs[0].code, "input");
}

#[test]
fn empty_input_is_an_error() {
    let (d, errs) = parse("  ; nothing\n");
    assert!(d.is_none());
    assert_eq!(errs.len(), 1);
    assert!(errs[0].message.contains("found the end of the file"));
}

#[test]
fn a_broken_action_is_left_out_and_the_rest_is_read() {
    let (d, errs) = parse(
        "(define (domain d) (:predicates (p))
               (:action a :precondition (not) :effect (and (p) 3))
               (:action b :effect (p)))",
    );
    // Both values of `a` are reported, then `b` is read.
    assert_eq!(errs.len(), 2, "{errs:#?}");
    let d = d.unwrap();
    assert_eq!(d.actions.len(), 1);
    assert_eq!(d.actions[0].name, "b");
}

#[test]
fn a_file_without_define_or_with_two_domains() {
    let (d, errs) = parse("(:action a :effect (p))");
    assert!(d.is_none());
    assert_eq!(errs.len(), 1);
    assert_eq!(
        errs[0].message,
        "expected `(define (domain NAME) ...)`, found `(:action`"
    );
    assert_eq!(errs[0].span.unwrap().len(), "(:action".len());
    let (d, errs) = parse("(define (domain d))\n(define (domain e))");
    assert_eq!(d.unwrap().name, "d");
    assert_eq!(errs.len(), 1);
    assert!(errs[0].message.contains("expected the end of the file"));
}

#[test]
fn suggestions() {
    assert_eq!(suggest("cupat", ["cupAt", "at"].into_iter()), Some("cupAt"));
    assert_eq!(suggest("holdng", ["holding"].into_iter()), Some("holding"));
    assert_eq!(suggest("xyz", ["holding"].into_iter()), None);
}
