//! Unit tests of the pure internal actions and arithmetic functions.
//!
//! Expected values come from Jason 3 itself (`jason.stdlib` and `jason.functions` run on
//! the parsed arguments), where there is any doubt.

use super::*;
use crate::model::Var;

fn a(s: &str) -> Term {
    Term::atom(s)
}
fn v(s: &str) -> Term {
    Term::var(s)
}
fn n(x: f64) -> Term {
    Term::num(x)
}
fn st(s: &str) -> Term {
    Term::string(s)
}
fn f(name: &str, args: Vec<Term>) -> Term {
    Term::structure(name, args)
}
fn l(elems: Vec<Term>) -> Term {
    Term::list(elems)
}

/// The answers of `name(args)` from scratch, each as the bindings of the query's
/// variables, printed: `["{X -> a}", ...]`.
fn run(name: &str, args: Vec<Term>) -> Vec<String> {
    let vars: Vec<Var> = f("q", args.clone()).vars();
    call(name, &args, &Substitution::new())
        .unwrap_or_else(|| panic!("{name} is pure"))
        .iter()
        .map(|s| s.restrict(&vars).to_string())
        .collect()
}

/// The value of `X` in the one answer.
fn one(name: &str, args: Vec<Term>) -> String {
    let answers = call(name, &args, &Substitution::new()).expect("pure");
    assert_eq!(answers.len(), 1, "{name}{args:?}");
    answers[0].resolve(&Var::named("X")).to_string()
}

fn holds(name: &str, args: Vec<Term>) -> bool {
    !call(name, &args, &Substitution::new())
        .expect("pure")
        .is_empty()
}

/// The function's value as Jason prints it.
fn printed(name: &str, args: Vec<Term>) -> String {
    function(name, &args)
        .expect("known function")
        .unwrap()
        .to_string()
}

fn value(name: &str, args: Vec<Term>) -> Result<f64, String> {
    function(name, &args)
        .expect("known function")
        .map(|t| t.as_f64().unwrap())
}

#[test]
fn not_pure_is_none() {
    assert!(call(".print", &[a("x")], &Substitution::new()).is_none());
    assert!(call("member", &[v("X"), l(vec![])], &Substitution::new()).is_none());
    assert!(function("math.random", &[]).is_none());
    assert!(function("math.abs", &[n(1.0), n(2.0)]).is_none());
}

#[test]
fn member_in_order_and_annotation_direction() {
    assert_eq!(
        run(".member", vec![v("X"), l(vec![a("a"), a("b"), a("c")])]),
        ["{X -> a}", "{X -> b}", "{X -> c}"]
    );
    let fx = f("f", vec![v("X")]);
    let list = l(vec![
        f("f", vec![n(1.0)]),
        f("g", vec![n(2.0)]),
        f("f", vec![n(3.0)]),
    ]);
    assert_eq!(run(".member", vec![fx, list]), ["{X -> 1}", "{X -> 3}"]);
    let px = Term::literal("p", false, vec![], vec![a("x")]);
    assert!(holds(".member", vec![a("p"), l(vec![px.clone()])]));
    assert!(!holds(".member", vec![px, l(vec![a("p")])]));
    assert!(!holds(".member", vec![v("X"), a("a")]));
}

#[test]
fn bindings_of_the_caller_are_applied_and_kept() {
    let mut s = Substitution::new();
    assert!(s.bind(Var::named("L"), l(vec![a("a"), a("b")])));
    let answers = call(".member", &[v("X"), v("L")], &s).unwrap();
    assert_eq!(answers.len(), 2);
    assert_eq!(answers[1].resolve(&Var::named("X")), a("b"));
    assert_eq!(answers[1].resolve(&Var::named("L")).to_string(), "[a,b]");
}

#[test]
fn length_of_lists_and_strings() {
    let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
    assert_eq!(one(".length", vec![partial, v("X")]), "2");
    // UTF-16 units: "héllo" is 5, an emoji is 2.
    assert_eq!(one(".length", vec![st("héllo"), v("X")]), "5");
    assert_eq!(one(".length", vec![st("😀"), v("X")]), "2");
    assert_eq!(one(".length", vec![st(""), v("X")]), "0");
    assert!(holds(".length", vec![st("abc"), n(3.0)]));
    assert!(!holds(".length", vec![f("f", vec![a("a")]), v("X")]));
}

#[test]
fn nth_bound_and_unbound() {
    let abc = l(vec![a("a"), a("b"), a("c")]);
    assert_eq!(one(".nth", vec![n(1.0), abc.clone(), v("X")]), "b");
    assert_eq!(one(".nth", vec![n(1.7), abc.clone(), v("X")]), "b");
    assert!(!holds(".nth", vec![n(3.0), abc.clone(), v("X")]));
    assert!(!holds(".nth", vec![n(-1.0), abc.clone(), v("X")]));
    assert_eq!(
        run(".nth", vec![v("I"), abc, v("X")]),
        ["{I -> 0, X -> a}", "{I -> 1, X -> b}", "{I -> 2, X -> c}"]
    );
    // The index does not unify with the element it became: Jason keeps the answer.
    let five_zero = l(vec![n(5.0), n(0.0)]);
    assert_eq!(
        run(".nth", vec![v("I"), five_zero, v("I")]),
        ["{I -> 5}", "{I -> 0}"]
    );
    let aba = l(vec![a("a"), a("b"), a("a")]);
    assert_eq!(
        run(".nth", vec![v("I"), aba, a("a")]),
        ["{I -> 0}", "{I -> 2}"]
    );
    assert_eq!(one(".nth", vec![n(1.0), st("abc"), v("X")]), "\"b\"");
    assert_eq!(
        run(".nth", vec![v("I"), st("aba"), st("a")]),
        ["{I -> 0}", "{I -> 2}"]
    );
    // Bytes of the UTF-8 form: "é" is two bytes, each U+FFFD.
    assert_eq!(one(".nth", vec![n(1.0), st("é"), v("X")]), "\"\u{FFFD}\"");
}

#[test]
fn concat_lists() {
    let r = |args: Vec<Term>| one(".concat", args);
    assert_eq!(
        r(vec![l(vec![a("a")]), l(vec![a("b"), a("c")]), v("X")]),
        "[a,b,c]"
    );
    assert_eq!(
        r(vec![
            l(vec![a("a")]),
            l(vec![a("b")]),
            l(vec![a("c")]),
            v("X")
        ]),
        "[a,b,c]"
    );
    assert_eq!(r(vec![l(vec![a("a")]), v("X")]), "[a]");
    // Nothing is appended after an unbound tail.
    let partial = Term::list_with_tail(vec![a("a")], v("T"));
    assert_eq!(r(vec![partial, l(vec![a("b")]), v("X")]), "[a|T]");
    let b_t = Term::list_with_tail(vec![a("b")], v("T"));
    let abc = vec![l(vec![a("a")]), b_t, l(vec![a("c")]), v("X")];
    assert_eq!(r(abc), "[a,b|T]");
    assert!(!holds(".concat", vec![l(vec![a("a")]), a("b"), v("X")]));
    assert!(!holds(".concat", vec![l(vec![a("a")]), l(vec![]), a("b")]));
    assert!(!holds(".concat", vec![]));
}

#[test]
fn concat_strings() {
    let r = |args: Vec<Term>| one(".concat", args);
    assert_eq!(r(vec![st("ab"), n(3.0), v("X")]), "\"ab3\"");
    assert!(holds(".concat", vec![st("ab"), n(3.0), st("ab3")]));
    // The last argument is compared through its text.
    assert!(holds(".concat", vec![st("a"), st("b"), a("ab")]));
    let args = vec![
        a("a"),
        a("'B c'"),
        f("f", vec![a("x"), st("s")]),
        l(vec![n(1.0), n(2.0)]),
        v("X"),
    ];
    assert_eq!(r(args), "\"aB cf(x,\\\"s\\\")[1,2]\"");
    assert_eq!(r(vec![n(2.5), v("X")]), "\"2.5\"");
    assert_eq!(r(vec![st("x"), v("X")]), "\"x\"");
    // Jason's text: the quote inside is not escaped.
    let q = r(vec![st("x\"y"), f("f", vec![st("q\"z")]), v("X")]);
    assert_eq!(q, "\"x\\\"yf(\\\"q\\\"z\\\")\"");
    let s = call(
        ".concat",
        &[st("x\"y"), f("f", vec![st("q\"z")]), v("X")],
        &Substitution::new(),
    )
    .unwrap();
    assert_eq!(
        s[0].resolve(&Var::named("X")).as_str(),
        Some("x\"yf(\"q\"z\")")
    );
}

#[test]
fn reverse_lists_and_strings() {
    assert_eq!(
        one(".reverse", vec![l(vec![a("a"), a("b"), a("c")]), v("X")]),
        "[c,b,a]"
    );
    let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
    assert_eq!(one(".reverse", vec![partial, v("X")]), "[b,a|T]");
    assert_eq!(one(".reverse", vec![st("abc"), v("X")]), "\"cba\"");
    assert_eq!(one(".reverse", vec![st("a😀b"), v("X")]), "\"b😀a\"");
    assert!(!holds(".reverse", vec![st("abc"), l(vec![])]));
    assert!(!holds(".reverse", vec![a("abc"), v("X")]));
}

#[test]
fn sort_by_jason_order() {
    let list = l(vec![a("c"), n(1.0), st("s"), f("f", vec![a("x")]), a("b")]);
    assert_eq!(one(".sort", vec![list, v("X")]), "[1,\"s\",b,c,f(x)]");
    let list = l(vec![
        a("b"),
        l(vec![a("a")]),
        st("b"),
        st("a"),
        n(2.0),
        n(1.5),
        Term::literal("a", true, vec![], vec![]),
        f("a", vec![n(1.0)]),
        a("a"),
        v("Y"),
        l(vec![]),
        Term::Var(Var::anonymous(1)),
    ]);
    assert_eq!(
        one(".sort", vec![list, v("X")]),
        "[1.5,2,\"a\",\"b\",[],[a],a,a(1),~a,b,Y,_1]"
    );
    let list = l(vec![
        f("f", vec![a("b")]),
        f("f", vec![a("a"), a("a")]),
        f("f", vec![a("a")]),
        a("g"),
        st("ab c"),
        st("ab"),
    ]);
    assert_eq!(
        one(".sort", vec![list, v("X")]),
        "[\"ab c\",\"ab\",f(a),f(a,a),f(b),g]"
    );
    assert_eq!(
        one(
            ".sort",
            vec![l(vec![n(1.0), n(1.0), a("a"), a("a")]), v("X")]
        ),
        "[1,1,a,a]"
    );
}

#[test]
fn min_and_max() {
    let l312 = l(vec![n(3.0), n(1.0), n(2.0)]);
    assert_eq!(one(".min", vec![l312.clone(), v("X")]), "1");
    assert_eq!(one(".max", vec![l312, v("X")]), "3");
    let mixed = l(vec![a("b"), st("a"), n(3.0), l(vec![a("x")])]);
    assert_eq!(one(".min", vec![mixed.clone(), v("X")]), "3");
    assert_eq!(one(".max", vec![mixed, v("X")]), "b");
    assert_eq!(one(".min", vec![l(vec![v("Y"), n(1.0)]), v("X")]), "1");
    assert!(!holds(".min", vec![l(vec![]), v("X")]));
}

#[test]
fn type_tests() {
    let neg = Term::literal("p", true, vec![], vec![]);
    let annotated = Term::literal("p", false, vec![], vec![a("x")]);
    let fa = f("f", vec![a("a")]);
    let cases: Vec<(&str, Term, bool)> = vec![
        (".structure", a("a"), false),
        (".structure", fa.clone(), true),
        (".structure", l(vec![a("a")]), true),
        (".structure", l(vec![]), true),
        (".structure", st("s"), false),
        (".structure", n(1.0), false),
        (".structure", v("X"), false),
        (".structure", neg.clone(), true),
        (".structure", annotated.clone(), true),
        (".atom", a("a"), true),
        (".atom", l(vec![]), false),
        (".atom", neg.clone(), false),
        (".atom", annotated, false),
        (".atom", fa.clone(), false),
        (".atom", st("a"), false),
        (".atom", v("X"), false),
        (".literal", a("a"), true),
        (".literal", neg, true),
        (".literal", l(vec![a("a")]), false),
        (".literal", st("s"), false),
        (".literal", n(1.0), false),
        (".literal", f("f", vec![v("X")]), true),
        (".list", l(vec![]), true),
        (".list", Term::list_with_tail(vec![a("a")], v("T")), true),
        (".list", a("a"), false),
        (".ground", f("f", vec![v("X")]), false),
        (".ground", l(vec![a("a"), st("s"), n(1.0)]), true),
        (".ground", v("X"), false),
        (".number", n(1.5), true),
        (".number", st("1"), false),
        (".string", st("s"), true),
        (".string", a("s"), false),
        (".empty", l(vec![]), true),
        (".empty", st(""), true),
        (".empty", l(vec![a("a")]), false),
        (".empty", a("a"), false),
    ];
    for (name, t, expected) in cases {
        assert_eq!(holds(name, vec![t.clone()]), expected, "{name}({t})");
    }
}

#[test]
fn substring_answers() {
    let r = |args: Vec<Term>| run(".substring", args);
    assert_eq!(
        r(vec![st("b"), st("abcb"), v("P")]),
        ["{P -> 1}", "{P -> 3}"]
    );
    // The end is the index of the last character (Jason's arithmetic).
    assert_eq!(
        r(vec![st("b"), st("abcb"), v("P"), v("E")]),
        ["{E -> 1, P -> 1}", "{E -> 3, P -> 3}"]
    );
    assert_eq!(
        r(vec![st("bc"), st("abcbc"), v("P"), v("E")]),
        ["{E -> 2, P -> 1}", "{E -> 4, P -> 3}"]
    );
    assert_eq!(
        r(vec![st(""), st("abc"), v("P")]),
        ["{P -> 0}", "{P -> 1}", "{P -> 2}"]
    );
    assert!(r(vec![st(""), st(""), v("P")]).is_empty());
    assert_eq!(r(vec![st("b"), st("abcb"), n(3.0)]), ["{}"]);
    assert_eq!(r(vec![st("b"), st("abcb"), n(1.0), v("E")]), ["{E -> 1}"]);
    assert_eq!(r(vec![st("é"), st("aéb"), v("P")]), ["{P -> 1}"]);
    // Texts of non-strings: "b" in "f(a,b)".
    assert_eq!(
        r(vec![a("b"), f("f", vec![a("a"), a("b")]), v("P")]),
        ["{P -> 4}"]
    );
    assert!(holds(".substring", vec![st("b"), st("abcb")]));
    assert!(!holds(".substring", vec![st("d"), st("abcb")]));
    let sub = |args: Vec<Term>| one(".substring", args);
    assert_eq!(sub(vec![v("X"), st("abcdef"), n(2.0), n(4.0)]), "\"cd\"");
    assert_eq!(sub(vec![v("X"), st("abcdef"), n(2.0)]), "\"cdef\"");
    assert_eq!(sub(vec![st("abcdef"), v("X"), n(2.0), n(4.0)]), "\"cd\"");
    assert!(!holds(
        ".substring",
        vec![v("X"), st("abcdef"), n(4.0), n(2.0)]
    ));
    // A fourth argument that is not a number means "to the end".
    assert_eq!(sub(vec![v("X"), st("abc"), n(1.0), v("E")]), "\"bc\"");
}

#[test]
fn term2string_both_ways() {
    let fa1 = f("f", vec![a("a"), n(1.0)]);
    assert_eq!(one(".term2string", vec![fa1.clone(), v("X")]), "\"f(a,1)\"");
    assert!(holds(".term2string", vec![fa1.clone(), st("f(a,1)")]));
    assert!(holds(".term2string", vec![n(1.0), st("1")]));
    assert!(holds(".term2string", vec![st("s"), st("\"s\"")]));
    let q = call(
        ".term2string",
        &[f("f", vec![a("a"), st("x\"y")]), v("X")],
        &Substitution::new(),
    )
    .unwrap();
    assert_eq!(
        q[0].resolve(&Var::named("X")).as_str(),
        Some("f(a,\"x\"y\")")
    );
    assert_eq!(
        one(".term2string", vec![a("'Hello'"), v("X")]),
        "\"'Hello'\""
    );
    let partial = Term::list_with_tail(vec![a("a"), a("b")], v("T"));
    assert_eq!(one(".term2string", vec![partial, v("X")]), "\"[a,b|T]\"");
    let parse = |text: &str| one(".term2string", vec![v("X"), st(text)]);
    assert_eq!(parse("f(a,1)"), "f(a,1)");
    assert_eq!(parse("f( a , 1 )"), "f(a,1)");
    assert_eq!(parse("f (a)"), "f(a)");
    assert_eq!(parse(" abc "), "abc");
    assert_eq!(parse("1.5"), "1.5");
    assert_eq!(parse("007"), "7");
    assert_eq!(parse("1e3"), "1000");
    assert_eq!(parse("1.5e-3"), "0.0015");
    assert_eq!(parse("3000000000"), "3000000000");
    assert_eq!(parse("[a ,b]"), "[a,b]");
    assert_eq!(parse("[ ]"), "[]");
    assert_eq!(parse("f(a,[1,2])"), "f(a,[1,2])");
    assert_eq!(parse("\"s\""), "\"s\"");
    assert_eq!(parse("f(\"a b\")"), "f(\"a b\")");
    assert_eq!(parse("'a b'"), "'a b'");
    assert_eq!(parse("begin"), "begin");
    assert_eq!(parse("f(true)"), "f(true)");
    // Not simple: Jason gives an atom of the whole text, a variable, annotations, or
    // evaluates arithmetic; here there is no answer.
    for text in [
        "hello world",
        "Abc",
        "~p[x]",
        "-1",
        "1+2",
        "",
        "f(",
        "not",
        "f(if)",
        "a.b",
        "1.",
        ".5",
        "f()",
        "[a|b]",
    ] {
        assert!(!holds(".term2string", vec![v("X"), st(text)]), "{text}");
    }
    // A non-string second argument is read through its text.
    assert_eq!(one(".term2string", vec![v("X"), a("a")]), "a");
    assert_eq!(run(".term2string", vec![v("X"), v("Y")]), ["{X -> Y}"]);
    assert!(!holds(".term2string", vec![a("a"), a("b")]));
}

#[test]
fn range_in_order() {
    let r = |args: Vec<Term>| run(".range", args);
    assert_eq!(
        r(vec![v("X"), n(1.0), n(3.0)]),
        ["{X -> 1}", "{X -> 2}", "{X -> 3}"]
    );
    assert_eq!(
        r(vec![v("X"), n(1.0), n(10.0), n(3.0)]),
        ["{X -> 1}", "{X -> 4}", "{X -> 7}", "{X -> 10}"]
    );
    assert_eq!(
        r(vec![v("X"), n(5.0), n(1.0), n(-2.0)]),
        ["{X -> 5}", "{X -> 3}", "{X -> 1}"]
    );
    assert!(r(vec![v("X"), n(3.0), n(1.0)]).is_empty());
    assert_eq!(
        r(vec![v("X"), n(1.9), n(3.9)]),
        ["{X -> 1}", "{X -> 2}", "{X -> 3}"]
    );
    assert!(holds(".range", vec![n(2.0), n(1.0), n(3.0)]));
    assert!(!holds(".range", vec![n(5.0), n(1.0), n(3.0)]));
    // The step is ignored when the value is bound.
    assert!(holds(".range", vec![n(2.0), n(1.0), n(9.0), n(4.0)]));
    // Endless in Jason.
    assert!(r(vec![v("X"), n(3.0), n(1.0), n(0.0)]).is_empty());
    assert!(r(vec![v("X"), n(1.0), n(f64::from(i32::MAX))]).is_empty());
    assert!(!holds(".range", vec![v("X"), a("a"), n(3.0)]));
}

#[test]
fn set_operations() {
    let caba = l(vec![a("c"), a("a"), a("b"), a("a")]);
    let r = |name: &str, x: Term, y: Term| one(name, vec![x, y, v("X")]);
    assert_eq!(
        r(".difference", caba.clone(), l(vec![a("b"), a("d")])),
        "[a,c]"
    );
    let bda = l(vec![a("b"), a("d"), a("a")]);
    assert_eq!(r(".intersection", caba.clone(), bda.clone()), "[a,b]");
    assert_eq!(r(".union", caba, bda), "[a,b,c,d]");
    assert_eq!(
        r(".union", l(vec![n(1.0), n(1.0), st("1")]), l(vec![])),
        "[1,\"1\"]"
    );
    let partial = Term::list_with_tail(vec![a("b"), a("a")], v("T"));
    assert_eq!(r(".union", partial, l(vec![a("c")])), "[a,b,c]");
    assert!(!holds(".union", vec![a("a"), l(vec![]), v("X")]));
}

#[test]
fn every_pure_action_answers_something() {
    let abc = || l(vec![a("a"), a("b"), a("c")]);
    let samples: Vec<(&str, Vec<Term>)> = vec![
        (".member", vec![v("X"), abc()]),
        (".length", vec![abc(), v("X")]),
        (".nth", vec![n(0.0), abc(), v("X")]),
        (".concat", vec![abc(), abc(), v("X")]),
        (".reverse", vec![abc(), v("X")]),
        (".sort", vec![abc(), v("X")]),
        (".min", vec![abc(), v("X")]),
        (".max", vec![abc(), v("X")]),
        (".empty", vec![l(vec![])]),
        (".list", vec![abc()]),
        (".ground", vec![abc()]),
        (".atom", vec![a("a")]),
        (".number", vec![n(1.0)]),
        (".string", vec![st("s")]),
        (".structure", vec![f("f", vec![a("a")])]),
        (".literal", vec![a("a")]),
        (".substring", vec![st("b"), st("abc"), v("X")]),
        (".term2string", vec![a("a"), v("X")]),
        (".range", vec![v("X"), n(1.0), n(3.0)]),
        (".difference", vec![abc(), abc(), v("X")]),
        (".intersection", vec![abc(), abc(), v("X")]),
        (".union", vec![abc(), abc(), v("X")]),
        (".add_nested_source", vec![a("a"), a("bob"), v("X")]),
        (".remove_source_annot", vec![a("a"), v("X")]),
    ];
    for (name, arities) in PURE {
        let (_, args) = samples
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no sample for {name}"));
        assert!(arities.contains(&args.len()), "{name}");
        assert!(holds(name, args.clone()), "{name}");
    }
    assert_eq!(samples.len(), PURE.len());
}

#[test]
fn functions_as_jason_computes_them() {
    assert_eq!(value("math.round", vec![n(2.5)]), Ok(3.0));
    assert_eq!(value("math.round", vec![n(-2.5)]), Ok(-2.0));
    assert_eq!(value("math.round", vec![n(0.49999999999999994)]), Ok(0.0));
    assert_eq!(value("math.round", vec![n(-0.5)]), Ok(0.0));
    let big = function("math.round", &[n(1e19)]).unwrap().unwrap();
    assert_eq!(big.to_string(), "9223372036854775807");
    assert_eq!(value("math.abs", vec![n(-3.0)]), Ok(3.0));
    assert_eq!(value("math.max", vec![n(3.0), n(7.0)]), Ok(7.0));
    assert_eq!(value("math.min", vec![n(3.0), n(7.0)]), Ok(3.0));
    assert_eq!(
        value("math.max", vec![l(vec![n(-3.0), n(-5.0)])]),
        Ok(4.9e-324)
    );
    assert_eq!(value("math.max", vec![l(vec![])]), Ok(4.9e-324));
    assert_eq!(value("math.min", vec![l(vec![])]), Ok(f64::MAX));
    assert_eq!(
        value("math.min", vec![l(vec![n(4.0), n(2.0), a("a"), n(9.0)])]),
        Ok(2.0)
    );
    assert_eq!(value("math.max", vec![l(vec![n(1.0)]), n(5.0)]), Ok(1.0));
    assert!(value("math.min", vec![n(2.0), l(vec![n(1.0)])]).is_err());
    assert!(value("math.max", vec![n(2.0)]).is_err());
    assert_eq!(printed("math.sqrt", vec![n(2.0)]), "1.4142135623730951");
    assert!(value("math.sqrt", vec![n(-1.0)]).is_err());
    assert_eq!(value("math.floor", vec![n(-1.5)]), Ok(-2.0));
    assert_eq!(value("math.ceil", vec![n(-1.5)]), Ok(-1.0));
    let mixed = l(vec![n(1.0), n(2.0), a("a"), n(3.5)]);
    assert_eq!(value("math.sum", vec![mixed]), Ok(6.5));
    assert_eq!(value("math.sum", vec![l(vec![])]), Ok(0.0));
    assert_eq!(
        value("math.average", vec![l(vec![n(1.0), n(2.0)])]),
        Ok(1.5)
    );
    assert!(value("math.average", vec![l(vec![])]).is_err());
    assert!(value("math.mean", vec![l(vec![])]).is_err());
    assert_eq!(
        value("math.mean", vec![l(vec![n(1.0), n(2.0), n(4.0)])]),
        Ok(2.3333333333333335)
    );
    assert_eq!(
        value("math.median", vec![l(vec![n(3.0), n(1.0), n(2.0)])]),
        Ok(2.0)
    );
    let four = l(vec![n(4.0), n(1.0), n(3.0), n(2.0)]);
    assert_eq!(value("math.median", vec![four]), Ok(2.5));
    assert!(value("math.median", vec![l(vec![n(1.0), a("a")])]).is_err());
    let four = l(vec![n(1.0), n(2.0), n(3.0), n(4.0)]);
    assert_eq!(value("math.std_dev", vec![four]), Ok(1.2909944487358056));
    assert!(value("math.std_dev", vec![l(vec![n(1.0)])]).is_err());
    assert_eq!(printed("math.log", vec![n(10.0)]), "2.302585092994046");
    assert!(value("math.log", vec![n(0.0)]).is_err());
    assert_eq!(printed("math.e", vec![]), "2.718281828459045");
    assert_eq!(printed("math.pi", vec![]), "3.141592653589793");
    assert_eq!(value("math.sin", vec![n(1.0)]), Ok(0.8414709848078965));
    assert_eq!(value("math.cos", vec![n(1.0)]), Ok(0.5403023058681398));
    assert_eq!(value("math.tan", vec![n(1.0)]), Ok(1.5574077246549023));
    assert_eq!(printed("math.asin", vec![n(0.5)]), "0.5235987755982989");
    assert_eq!(printed("math.acos", vec![n(0.5)]), "1.0471975511965979");
    assert_eq!(printed("math.atan", vec![n(1.0)]), "0.7853981633974483");
    assert_eq!(value(".length", vec![l(vec![a("a"), a("b")])]), Ok(2.0));
    assert_eq!(value(".length", vec![st("abc")]), Ok(3.0));
    assert!(value(".length", vec![a("a")]).is_err());
    assert!(value("math.abs", vec![a("a")]).is_err());
    assert!(value("math.abs", vec![v("X")]).is_err());
}

#[test]
fn every_function_evaluates() {
    for (name, arity) in FUNCTIONS {
        let args = match (*name, *arity) {
            (_, 0) => vec![],
            ("math.acos" | "math.asin", _) => vec![n(0.5)],
            (
                "math.average" | "math.mean" | "math.median" | "math.std_dev" | "math.sum"
                | ".length",
                _,
            )
            | ("math.max" | "math.min", 1) => vec![l(vec![n(1.0), n(2.0)])],
            (_, 1) => vec![n(2.0)],
            _ => vec![n(2.0), n(3.0)],
        };
        assert!(
            matches!(function(name, &args), Some(Ok(_))),
            "{name}/{arity}"
        );
    }
}

#[test]
fn sources_are_nested_and_removed_as_jason_does() {
    let src = |who: &str, inner: Vec<Term>| Term::literal("source", false, vec![a(who)], inner);
    // `add_nested_source.addAnnotToList`: the sources a literal had go inside the new one.
    let told = Term::literal("p", false, vec![a("x")], vec![src("ana", vec![]), a("u")]);
    assert_eq!(
        one(".add_nested_source", vec![told.clone(), a("bob"), v("X")]),
        "p(x)[source(bob)[source(ana)],u]"
    );
    assert_eq!(
        one(".add_nested_source", vec![a("q"), a("bob"), v("X")]),
        "q[source(bob)]"
    );
    // Each element of a list; any other term as it is.
    assert_eq!(
        one(
            ".add_nested_source",
            vec![l(vec![a("q"), n(1.0)]), a("bob"), v("X")]
        ),
        "[q[source(bob)],1]"
    );
    assert!(!holds(".add_nested_source", vec![n(1.0), a("bob"), n(2.0)]));
    // `remove_source_annot`: every `source`, nested or not, and the other annotations kept.
    let nested = Term::literal(
        "p",
        false,
        vec![a("x")],
        vec![src("bob", vec![src("ana", vec![])]), a("u")],
    );
    assert_eq!(one(".remove_source_annot", vec![nested, v("X")]), "p(x)[u]");
    assert_eq!(
        one(".remove_source_annot", vec![l(vec![told, a("q")]), v("X")]),
        "[p(x)[u],q]"
    );
}
