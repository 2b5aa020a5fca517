//! The PDDL domain front end on files: the valid kitchen domain parses cleanly, every invalid
//! file yields exactly the diagnostics its `; expect: LINE:COLUMN text` header lines announce,
//! and no input (random bytes, mutated domains) makes the parser panic.

use bdi_check::syntax::pddl::{parse_domain, Domain, EffectKind, GdKind};
use bdi_check::syntax::{Diagnostic, SourceMap};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/pddl")
        .join(sub)
}

fn pddl_files(sub: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir(sub))
        .expect("test folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "pddl"))
        .collect();
    files.sort();
    files
}

/// Loads a file into a fresh map and parses it.
fn load(path: &Path) -> (SourceMap, Option<Domain>, Vec<Diagnostic>) {
    let text = std::fs::read_to_string(path).expect("readable");
    let name = format!(
        "{}/{}",
        path.parent()
            .unwrap()
            .file_name()
            .unwrap()
            .to_string_lossy(),
        path.file_name().unwrap().to_string_lossy()
    );
    let mut map = SourceMap::new();
    let id = map.add(path, name, text.clone());
    let (d, errs) = parse_domain(id, &text);
    (map, d, errs)
}

fn kitchen() -> PathBuf {
    dir("valid").join("kitchen.pddl")
}

#[test]
fn kitchen_domain_parses_without_diagnostics() {
    let (map, d, errs) = load(&kitchen());
    let rendered: Vec<String> = errs.iter().map(|e| e.render(&map, false)).collect();
    assert!(errs.is_empty(), "{}", rendered.join("\n"));
    let d = d.expect("a domain");
    assert_eq!(d.name, "kitchen");
    assert_eq!(d.types.len(), 8);
    assert_eq!(d.constants.len(), 7);
    assert_eq!(d.predicates.len(), 8);
    assert_eq!(d.actions.len(), 7);
    assert_eq!(
        map.location(d.name_span).to_string(),
        "valid/kitchen.pddl:5:17"
    );

    // Typing with inheritance.
    assert_eq!(d.type_ancestors("cup"), ["dish", "item", "object"]);
    assert!(d.is_subtype("appliance", "location"));
    assert!(!d.is_subtype("location", "appliance"));
    assert_eq!(d.constant("dishwasher").unwrap().ty, "appliance");
    assert!(d.requires(":conditional-effects"));
    let reachable = d.predicate("reachable").unwrap();
    let tys: Vec<&str> = reachable.params.iter().map(|p| p.ty.as_str()).collect();
    assert_eq!(tys, ["location", "location"]);

    // Keys in any order, each optional.
    let close = d.action("closeDoor").unwrap();
    assert!(close.params.is_empty());
    assert!(close.precondition.is_some() && close.effect.is_some());
    let wait = d.action("wait").unwrap();
    assert!(matches!(&wait.precondition.as_ref().unwrap().kind, GdKind::And(g) if g.is_empty()));
    assert!(matches!(&wait.effect.as_ref().unwrap().kind, EffectKind::And(e) if e.is_empty()));

    // Spans point into the file, and printing gives PDDL back.
    let nav = d.action("navigateTo").unwrap();
    assert_eq!(
        map.location(nav.name_span).to_string(),
        "valid/kitchen.pddl:34:12"
    );
    assert_eq!(
        nav.precondition.as_ref().unwrap().to_string(),
        "(and (not (robotAt ?to)) (exists (?from - location) \
         (and (robotAt ?from) (reachable ?from ?to))))"
    );
    assert_eq!(
        map.slice(nav.span).lines().next(),
        Some("(:action navigateTo")
    );

    // Every constant used is declared here; none is left for the manifest.
    assert!(d.undeclared_constants().is_empty());
    let used: Vec<&str> = d.constant_uses().iter().map(|c| c.0).collect();
    assert!(used.contains(&"dishwasher") && used.contains(&"none"));
}

/// `; expect: LINE:COLUMN text` lines at the top of a file.
fn expectations(path: &Path) -> Vec<(usize, usize, String)> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .map_while(|l| l.strip_prefix("; expect: "))
        .map(|l| {
            let (pos, msg) = l.split_once(' ').expect("`LINE:COLUMN text`");
            let (line, col) = pos.split_once(':').expect("LINE:COLUMN");
            (line.parse().unwrap(), col.parse().unwrap(), msg.to_string())
        })
        .collect()
}

#[test]
fn invalid_files_yield_exactly_the_expected_diagnostics() {
    let files = pddl_files("invalid");
    assert!(files.len() >= 12, "only {} invalid files", files.len());
    let mut failures = Vec::new();
    for path in &files {
        let expected = expectations(path);
        assert!(
            !expected.is_empty(),
            "{} has no `; expect:` line",
            path.display()
        );
        let (map, _, errs) = load(path);
        let mut actual: Vec<(usize, usize, String)> = errs
            .iter()
            .map(|e| {
                let loc = e.location(&map).expect("located");
                (loc.line, loc.column, e.message.clone())
            })
            .collect();
        actual.sort();
        let mut expected = expected.clone();
        expected.sort();
        let matches = actual.len() == expected.len()
            && actual
                .iter()
                .zip(&expected)
                .all(|(a, e)| a.0 == e.0 && a.1 == e.1 && a.2.contains(&e.2));
        if !matches {
            failures.push(format!(
                "{}:\n  expected {expected:?}\n  actual   {actual:?}",
                path.display()
            ));
        }
        for e in &errs {
            assert!(e.span.is_some(), "{}: unlocated {e}", path.display());
            let first = e.render(&map, false);
            let first = first.lines().next().unwrap();
            let loc = e.location(&map).unwrap();
            assert!(
                first.starts_with(&format!("{}:{}:{}: error[", loc.file, loc.line, loc.column)),
                "{first}"
            );
            assert!(
                e.code == "syntax" || e.code == "input",
                "{}: code {}",
                path.display(),
                e.code
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn rendering_names_file_line_column_and_shows_help() {
    let path = dir("invalid").join("durative_action.pddl");
    let (map, _, errs) = load(&path);
    let text = errs[0].render(&map, false);
    assert!(
        text.starts_with("invalid/durative_action.pddl:6:4: error[input]:"),
        "{text}"
    );
    assert!(text.contains("(:durative-action"), "{text}");
    assert!(text.contains("instantaneous"), "{text}");
}

#[test]
fn undeclared_constants_are_left_to_the_caller() {
    let text = "(define (domain d) (:constants table) (:predicates (at ?x ?y))
      (:action a :parameters (?x) :precondition (at ?x table) :effect (at ?x cup1)))";
    let (d, errs) = parse_domain(Default::default(), text);
    assert!(errs.is_empty(), "{errs:?}");
    let d = d.unwrap();
    let undeclared: Vec<&str> = d.undeclared_constants().iter().map(|c| c.0).collect();
    assert_eq!(undeclared, ["cup1"]);
}

/// Parses and renders every diagnostic: neither may panic, and every error is located.
fn no_panic(text: &str) {
    let mut map = SourceMap::new();
    let id = map.add("fuzz.pddl", "fuzz.pddl", text.to_string());
    let (d, errs) = parse_domain(id, text);
    for e in errs.iter().take(3) {
        assert!(e.span.is_some());
        let _ = e.render(&map, false);
    }
    if let Some(d) = d {
        for a in &d.actions {
            let _ = a.precondition.as_ref().map(|g| g.to_string());
            let _ = a.effect.as_ref().map(|e| e.to_string());
        }
        for t in &d.types {
            let _ = d.type_ancestors(&t.name);
        }
        let _ = d.undeclared_constants();
    }
}

/// One edit of a text: delete, duplicate or replace a span of characters.
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Duplicate(usize, usize),
    Insert(usize, String),
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for e in edits {
        let n = chars.len().max(1);
        match e {
            Edit::Delete(at, len) => {
                let at = at % n;
                let end = (at + len).min(chars.len());
                chars.drain(at.min(end)..end);
            }
            Edit::Duplicate(at, len) => {
                let at = at % n;
                let end = (at + len).min(chars.len());
                let piece: Vec<char> = chars[at.min(end)..end].to_vec();
                chars.splice(at.min(end)..at.min(end), piece);
            }
            Edit::Insert(at, s) => {
                let at = (at % n).min(chars.len());
                chars.splice(at..at, s.chars());
            }
        }
    }
    chars.into_iter().collect()
}

fn edit() -> impl Strategy<Value = Edit> {
    let piece = prop_oneof![
        Just("(".to_string()),
        Just(")".to_string()),
        Just(" - ".to_string()),
        Just("?x".to_string()),
        Just(":action".to_string()),
        Just("(not".to_string()),
        Just("(forall (?z) ".to_string()),
        Just(";".to_string()),
        Just("=".to_string()),
        Just("é".to_string()),
        "[ -~]{0,8}",
    ];
    prop_oneof![
        (any::<usize>(), 0usize..40).prop_map(|(a, l)| Edit::Delete(a, l)),
        (any::<usize>(), 0usize..40).prop_map(|(a, l)| Edit::Duplicate(a, l)),
        (any::<usize>(), piece).prop_map(|(a, s)| Edit::Insert(a, s)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        no_panic(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_s_expressions_never_panic(text in "[()a-z?:=; \n-]{0,400}") {
        no_panic(&text);
    }

    #[test]
    fn mutated_kitchen_never_panics(edits in proptest::collection::vec(edit(), 1..6)) {
        let text = std::fs::read_to_string(kitchen()).unwrap();
        no_panic(&apply(&text, &edits));
    }
}

/// Prints every diagnostic of the invalid files, to review their wording:
/// `cargo test --release --test suite pddl::show_all -- --ignored --nocapture`.
#[test]
#[ignore]
fn show_all() {
    for path in pddl_files("invalid") {
        let (map, _, errs) = load(&path);
        for e in errs {
            println!("{}", e.render(&map, false));
        }
    }
}
