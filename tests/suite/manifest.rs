//! The manifest and scenario readers against the files in `tests/manifest/`: the valid
//! manifest loads with the values written in it, and each invalid file yields exactly the
//! diagnostics its `# expect: LINE:COLUMN substring` comments announce.

use bdi_check::syntax::ast::{ExprKind, StepKind};
use bdi_check::syntax::manifest::*;
use bdi_check::syntax::{Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

fn dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/manifest")
        .join(sub)
}

/// The `# expect:` lines at the top of a file: (line, column, substring).
fn expectations(path: &Path) -> Vec<(usize, usize, String)> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .take_while(|l| l.starts_with('#'))
        .filter_map(|l| l.strip_prefix("# expect: "))
        .map(|l| {
            let (pos, msg) = l.split_once(' ').unwrap();
            let (line, col) = pos.split_once(':').unwrap();
            (line.parse().unwrap(), col.parse().unwrap(), msg.to_string())
        })
        .collect()
}

fn check_expected(path: &Path, map: &SourceMap, diags: &[Diagnostic]) -> Result<(), String> {
    let want = expectations(path);
    if want.is_empty() {
        return Err(format!("{}: no `# expect:` line", path.display()));
    }
    let got: Vec<(usize, usize, String)> = diags
        .iter()
        .map(|d| {
            let loc = d.location(map).expect("every diagnostic is located");
            (loc.line, loc.column, d.message.clone())
        })
        .collect();
    let ok = want.len() == got.len()
        && want
            .iter()
            .zip(&got)
            .all(|(w, g)| w.0 == g.0 && w.1 == g.1 && g.2.contains(&w.2));
    if ok {
        Ok(())
    } else {
        let rendered: String = diags.iter().map(|d| d.render(map, false)).collect();
        Err(format!(
            "{}:\n  expected {want:?}\n  got      {got:?}\n{rendered}",
            path.display()
        ))
    }
}

fn toml_files(d: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

#[test]
fn the_full_manifest_loads_with_its_values() {
    let mut map = SourceMap::new();
    // The folder is accepted as well as the file.
    let m = load_manifest(&dir("valid"), &mut map).unwrap_or_else(|ds| {
        panic!(
            "{}",
            ds.iter().map(|d| d.render(&map, false)).collect::<String>()
        )
    });
    assert_eq!(m.path, dir("valid").join(MANIFEST_NAME));
    assert_eq!(m.agent.plans.path, dir("valid").join("kitchen.asl"));
    assert_eq!(m.agent.actions.written.value, "kitchen.pddl");
    assert_eq!(map.slice(m.agent.plans.written.span), "\"kitchen.asl\"");

    assert_eq!(m.objects.len(), 1);
    assert_eq!(m.objects[0].name.value, "cup");
    let cups: Vec<&str> = m.objects[0]
        .objects
        .iter()
        .map(|o| o.value.as_str())
        .collect();
    assert_eq!(cups, ["cup1", "cup2"]);

    let facts: Vec<&str> = m.initial.facts.iter().map(|f| f.text.as_str()).collect();
    assert_eq!(facts, ["robotAt(table)", "holding(none)"]);
    assert_eq!(map.slice(m.initial.facts[1].expr.span), "holding(none)");
    let vary: Vec<&str> = m.initial.vary.iter().map(|v| v.value.as_str()).collect();
    assert_eq!(vary, ["used", "cupAt", "dishwasherDoor"]);
    assert_eq!(map.slice(m.initial.vary[2].span), "dishwasherDoor");
    assert_eq!(m.initial.constraints.len(), 1);
    assert!(
        matches!(&m.initial.constraints[0].expr.kind, ExprKind::Literal(l) if l.functor == ".count")
    );

    assert_eq!(m.requests.goals[0].text, "storeCup(C)");
    assert_eq!(m.requests.max, 2);
    assert_eq!(m.requests.arrival, Arrival::Any);

    let inv: Vec<&str> = m.invariants.iter().map(|i| i.name.value.as_str()).collect();
    assert_eq!(
        inv,
        ["one_location", "one_hand"],
        "source order, not key order"
    );
    // A literal string maps exactly too.
    assert_eq!(
        map.slice(m.invariants[1].formula.expr.span),
        ".count(holding(_), 1)"
    );

    let props: Vec<(&str, PropertyKind)> = m
        .properties
        .iter()
        .map(|p| (p.name.value.as_str(), p.kind))
        .collect();
    assert_eq!(
        props,
        [
            ("cup_never_dropped_on_floor", PropertyKind::Always),
            ("cups_stored", PropertyKind::Eventually),
            ("door_can_open", PropertyKind::Reachable),
        ]
    );
    assert!(matches!(
        m.properties[0].formula.expr.kind,
        ExprKind::Not(_)
    ));
    // A multi-line string: the formula is on the line after the opening quotes.
    let loc = map.location(m.properties[2].formula.expr.span);
    assert_eq!((loc.line, loc.column), (34, 1));
    assert_eq!(
        map.slice(m.properties[2].formula.expr.span),
        "dishwasherDoor(open)"
    );

    let e = m.explanation.as_ref().expect("[explanation] is present");
    assert_eq!(map.slice(e.span), "explanation");
    let robot = e.robot.as_ref().unwrap();
    assert_eq!(robot.value, "kitchen");
    assert_eq!(map.slice(robot.span), "\"kitchen\"");
    assert_eq!(e.modifies, Modifies::Semantic);
    assert_eq!(e.emitted_by.as_ref().unwrap().value, "explain");
    let phrases: Vec<(&str, &str)> = e
        .phrases
        .iter()
        .map(|p| (p.pattern.text.as_str(), p.template.value.as_str()))
        .collect();
    assert_eq!(
        phrases,
        [
            ("dishwasherDoor(S)", "the dishwasher door is {S}"),
            ("navigateTo(L)", "go to the {L} {{now}}"),
        ]
    );
    let users: Vec<&str> = e.users.iter().map(|u| u.name.value.as_str()).collect();
    assert_eq!(users, ["newcomer", "owner"]);
    assert!(e.users[0].expected.is_empty());
    let owner = &e.users[1].expected;
    assert_eq!(owner.len(), 2);
    assert!(matches!(owner[0].before.step.kind, StepKind::Achieve(_)));
    assert!(matches!(owner[0].after.step.kind, StepKind::Action(_)));
    assert_eq!(map.slice(owner[1].after.step.span), "pickUp(C)");
    assert_eq!(
        map.slice(owner[0].span),
        "[\"!storeCup(C)\", \"navigateTo(table)\"]"
    );

    assert_eq!(m.bounds.max_states, 5_000_000);
    assert_eq!(m.bounds.max_depth, 2_000);
    assert_eq!(m.bounds.symmetry[0].value, "cup");
    assert_eq!(m.bounds.plan_selection, PlanSelection::Any);
}

#[test]
fn a_minimal_manifest_takes_the_defaults() {
    let mut map = SourceMap::new();
    let m = load_manifest(&dir("valid").join("minimal.toml"), &mut map).unwrap();
    assert!(m.objects.is_empty());
    assert_eq!(m.initial, InitialSection::default());
    assert!(m.requests.goals.is_empty());
    assert_eq!(m.requests.max, DEFAULT_MAX_REQUESTS);
    assert_eq!(m.requests.arrival, Arrival::Idle);
    assert!(m.invariants.is_empty() && m.properties.is_empty());
    assert!(m.explanation.is_none());
    assert_eq!(m.bounds, Bounds::default());
    assert_eq!(m.bounds.max_states, 5_000_000);
    assert_eq!(m.bounds.max_depth, 2_000);
    assert_eq!(m.bounds.plan_selection, PlanSelection::First);
}

#[test]
fn each_invalid_manifest_yields_exactly_its_expected_diagnostics() {
    let files = toml_files(&dir("invalid"));
    assert!(files.len() >= 15, "{files:?}");
    let mut failures = Vec::new();
    for path in files {
        let mut map = SourceMap::new();
        match load_manifest(&path, &mut map) {
            Ok(_) => failures.push(format!("{}: loaded without error", path.display())),
            Err(ds) => {
                if let Err(e) = check_expected(&path, &map, &ds) {
                    failures.push(e);
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn scenarios_load_and_invalid_ones_are_located() {
    let mut map = SourceMap::new();
    let s = load_scenario(&dir("scenario").join("valid.toml"), &mut map).unwrap();
    let initial: Vec<&str> = s.initial.iter().map(|f| f.text.as_str()).collect();
    assert_eq!(
        initial,
        [
            "robotAt(table)",
            "holding(none)",
            "used(cup1)",
            "cupAt(cup1,table)",
            "dishwasherDoor(closed)"
        ]
    );
    assert_eq!(s.requests[0].text, "storeCup(cup1)");
    assert_eq!(map.location(s.initial[4].expr.span).line, 3);

    let mut failures = Vec::new();
    for path in toml_files(&dir("scenario/invalid")) {
        let mut map = SourceMap::new();
        match load_scenario(&path, &mut map) {
            Ok(_) => failures.push(format!("{}: loaded without error", path.display())),
            Err(ds) => {
                if let Err(e) = check_expected(&path, &map, &ds) {
                    failures.push(e);
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn rendering_names_file_line_column_and_shows_the_toml_line() {
    let path = dir("invalid").join("formula_syntax.toml");
    let mut map = SourceMap::new();
    let ds = load_manifest(&path, &mut map).unwrap_err();
    let text = ds[0].render(&map, false);
    let head = format!("{}:7:23: error[syntax]: ", path.display());
    assert!(text.starts_with(&head), "{text}");
    assert!(text.contains("always = \"not cupAt(C,, floor)\""), "{text}");
}

#[test]
fn a_folder_without_manifest_and_a_missing_file_are_errors() {
    let mut map = SourceMap::new();
    let ds = load_manifest(&dir("scenario"), &mut map).unwrap_err();
    assert_eq!(ds.len(), 1);
    assert!(
        ds[0].message.contains("has no `bdi-check.toml`"),
        "{}",
        ds[0].message
    );
    let ds = load_manifest(&dir("nowhere.toml"), &mut map).unwrap_err();
    assert!(ds[0].message.contains("cannot read"), "{}", ds[0].message);
    assert!(ds[0].location(&map).is_some());
}

#[test]
#[ignore = "prints every invalid file's rendering, for reviewing messages"]
fn dump_renderings() {
    for path in toml_files(&dir("invalid")) {
        let mut map = SourceMap::new();
        if let Err(ds) = load_manifest(&path, &mut map) {
            for d in ds {
                println!("{}", d.render(&map, false));
            }
        }
    }
}

/// Loads a manifest text written next to the placeholder files of `tests/manifest/invalid`.
fn load_text(text: &str) -> (SourceMap, Result<Manifest, Vec<Diagnostic>>) {
    let mut map = SourceMap::new();
    let path = dir("invalid").join("inline.toml");
    let id = map.add(&path, "inline.toml", text.to_string());
    let r = parse_manifest(id, &map.file(id).text.clone(), &path);
    (map, r)
}

#[test]
fn crlf_escapes_and_empty_formulas_are_located() {
    let head = "[agent]\r\nplans = \"kitchen.asl\"\r\nactions = \"kitchen.pddl\"\r\n";
    let (map, m) = load_text(&format!(
        "{head}[invariants]\r\na = \"p(\\\"x\\\") & q(Y)\"\r\nb = '''\r\nr(1)\r\n'''\r\n"
    ));
    let m = m.unwrap();
    let loc = map.location(m.invariants[0].formula.expr.span);
    assert_eq!((loc.line, loc.column), (5, 6));
    let ExprKind::And(_, q) = &m.invariants[0].formula.expr.kind else {
        panic!("{:?}", m.invariants[0].formula.expr)
    };
    assert_eq!(map.slice(q.span), "q(Y)");
    // Whatever `toml` does with CRLF inside a multi-line string, the span stays in the string.
    let s = m.invariants[1].formula.expr.span;
    assert!(map.slice(s).contains("r(1)"), "{:?}", map.slice(s));

    let (map, r) = load_text(&format!("{head}[invariants]\r\na = \"\"\r\n"));
    let ds = r.unwrap_err();
    assert_eq!(ds.len(), 1);
    let loc = ds[0].location(&map).unwrap();
    assert_eq!(
        (loc.line, loc.column),
        (5, 6),
        "{}",
        ds[0].render(&map, false)
    );
}

#[test]
fn every_error_of_a_file_is_reported_in_order() {
    let (map, r) = load_text(
        "[agent]\nplans = 1\nactions = \"kitchen.pddl\"\nfoo = 2\n\
         [[property]]\nname = \"a\"\n[[property]]\nname = \"a\"\nalways = \"p(\"\n",
    );
    let ds = r.unwrap_err();
    let got: Vec<(usize, usize)> = ds
        .iter()
        .map(|d| {
            let l = d.location(&map).unwrap();
            (l.line, l.column)
        })
        .collect();
    // wrong type, unknown key, property without kind, duplicate name, formula syntax error.
    assert_eq!(got, [(2, 9), (4, 1), (5, 1), (8, 8), (9, 13)], "{ds:#?}");
}
