//! Type checking across the three files of a project (`bdi_check::model::vocabulary`): the
//! example projects check with the expected vocabulary, and each broken project under
//! `tests/typecheck/<case>/` yields exactly the diagnostics its `expect.txt` lists, one per
//! line as `FILE:LINE:COLUMN message-substring` (FILE is the file's name, without folders).

use bdi_check::model::vocabulary::{check, PredicateKind, Vocabulary};
use bdi_check::model::{TypeId, Universe};
use bdi_check::syntax::manifest::load_manifest;
use bdi_check::syntax::{load_agent, pddl, Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// What a caller does: load the manifest, the agent and the domain, build the universe and
/// check. Errors of the earlier stages fail the test; `check`'s own are returned.
fn load(project: &Path) -> (SourceMap, Universe, Result<Vocabulary, Vec<Diagnostic>>) {
    let mut map = SourceMap::new();
    let render = |map: &SourceMap, ds: Vec<Diagnostic>| -> String {
        ds.iter().map(|d| d.render(map, false)).collect()
    };
    let m = match load_manifest(project, &mut map) {
        Ok(m) => m,
        Err(ds) => panic!("manifest: {}", render(&map, ds)),
    };
    let agent = match load_agent(&m.agent.plans.path, &mut map) {
        Ok(a) => a,
        Err(ds) => panic!("agent: {}", render(&map, ds)),
    };
    let path = &m.agent.actions.path;
    let text = std::fs::read_to_string(path).unwrap();
    let file = map.add(path, path.display().to_string(), text.clone());
    let (domain, ds) = pddl::parse_domain(file, &text);
    if !ds.is_empty() {
        panic!("pddl: {}", render(&map, ds));
    }
    let domain = domain.unwrap();
    let universe = match Universe::build(&domain, &m) {
        Ok(u) => u,
        Err(ds) => panic!("universe: {}", render(&map, ds)),
    };
    let result = check(&agent, &domain, &m, &universe, &map);
    (map, universe, result)
}

fn ok(project: &str) -> (SourceMap, Universe, Vocabulary) {
    let (map, u, r) = load(&root().join(project));
    match r {
        Ok(v) => (map, u, v),
        Err(ds) => panic!(
            "{project}: {}",
            ds.iter().map(|d| d.render(&map, false)).collect::<String>()
        ),
    }
}

fn names(u: &Universe, ts: &[TypeId]) -> Vec<String> {
    ts.iter().map(|&t| u.type_name(t).to_string()).collect()
}

#[test]
fn kitchen_checks_with_its_vocabulary() {
    let (map, u, v) = ok("specs/kitchen");
    let preds: Vec<(&str, Vec<String>)> = v
        .predicates
        .iter()
        .map(|p| (p.name.as_str(), names(&u, &p.params)))
        .collect();
    assert_eq!(
        preds,
        [
            ("robotAt", vec!["location".to_string()]),
            ("holding", vec!["item".into()]),
            ("cupAt", vec!["cup".into(), "location".into()]),
            ("used", vec!["cup".into()]),
            ("dishwasherDoor", vec!["doorstate".into()]),
            ("dirty", vec!["location".into()]),
        ]
    );
    assert!(v.predicates.iter().all(|p| p.is_environment()));
    assert_eq!(v.mental_notes().count(), 0);
    let (i, cup_at) = v.predicate("cupAt").unwrap();
    assert_eq!(i, 2);
    let PredicateKind::Environment { span } = cup_at.kind else {
        panic!("cupAt is PDDL's")
    };
    assert_eq!(map.slice(span), "(cupAt ?c - cup ?l - location)");

    let actions: Vec<(&str, Vec<String>)> = v
        .actions
        .iter()
        .map(|a| (a.name.as_str(), names(&u, &a.params)))
        .collect();
    assert_eq!(
        actions,
        [
            ("navigateTo", vec!["location".to_string()]),
            ("pickUp", vec!["cup".into()]),
            ("putDown", vec!["cup".into()]),
            ("openDoor", vec!["location".into()]),
            ("closeDoor", vec!["location".into()]),
            ("startDishwasher", vec!["location".into()]),
            ("wipe", vec!["location".into()]),
        ]
    );
    assert_eq!(v.action("pickUp").map(|(i, _)| i), Some(1));

    let goals: Vec<(&str, usize, Vec<String>, bool)> = v
        .goals
        .iter()
        .map(|g| (g.name.as_str(), g.arity, names(&u, &g.params), g.has_plan))
        .collect();
    assert_eq!(
        goals,
        [
            ("storeCup", 1, vec!["cup".to_string()], true),
            ("stow", 1, vec!["cup".into()], true),
            ("closeDishwasherIfNeed", 0, vec![], true),
            ("openDishwasherIfNeed", 0, vec![], true),
            ("fetch", 1, vec!["cup".into()], true),
            ("deliver", 2, vec!["cup".into(), "location".into()], true),
            ("putAway", 1, vec!["cup".into()], true),
            ("shelve", 1, vec!["cup".into()], true),
            ("reach", 1, vec!["cup".into()], true),
            ("runDishwasher", 0, vec![], true),
            ("startWash", 0, vec![], true),
            ("unloadDishwasher", 0, vec![], true),
            ("wipeTable", 0, vec![], true),
        ]
    );
    let (_, store) = v.goal("storeCup", 1).unwrap();
    assert_eq!(map.slice(store.span), "+!storeCup(C)");
    assert_eq!(map.location(store.span).line, 21);
    assert!(v.goal("storeCup", 2).is_none());
    assert!(v.rules.is_empty());
    assert!(v.undefined_actions.is_empty());
}

#[test]
fn paper_checks_with_its_vocabulary() {
    let (_, u, v) = ok("specs/paper");
    assert_eq!(v.predicates.len(), 6);
    assert_eq!(v.mental_notes().count(), 0);
    let goals: Vec<(&str, Vec<String>)> = v
        .goals
        .iter()
        .map(|g| (g.name.as_str(), names(&u, &g.params)))
        .collect();
    assert_eq!(
        goals,
        [
            ("storeCup", vec!["cup".to_string()]),
            ("openDishwasherIfNeed", vec![]),
        ]
    );
    assert!(v.undefined_actions.is_empty());
}

/// The `expect.txt` of a case: (file name, line, column, message substring).
fn expectations(case: &Path) -> Vec<(String, usize, usize, String)> {
    let text = std::fs::read_to_string(case.join("expect.txt")).unwrap();
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let (pos, msg) = l.split_once(' ').unwrap();
            let mut parts = pos.rsplitn(3, ':');
            let col = parts.next().unwrap().parse().unwrap();
            let line = parts.next().unwrap().parse().unwrap();
            let file = parts.next().unwrap().to_string();
            let msg = msg.replace("{dir}", &case.display().to_string());
            (file, line, col, msg)
        })
        .collect()
}

/// Checks one broken case; returns the diagnostics when they are exactly the expected ones.
fn broken(case: &str) -> (SourceMap, Vec<Diagnostic>) {
    let dir = root().join("tests/typecheck").join(case);
    let want = expectations(&dir);
    let (map, _, r) = load(&dir);
    let ds = match r {
        Ok(_) => panic!("{case}: checked without error, expected {want:?}"),
        Err(ds) => ds,
    };
    let got: Vec<(String, usize, usize, String)> = ds
        .iter()
        .map(|d| {
            let loc = d.location(&map).expect("every diagnostic is located");
            let file = Path::new(&loc.file)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned();
            (file, loc.line, loc.column, d.message.clone())
        })
        .collect();
    let ok = want.len() == got.len()
        && want
            .iter()
            .zip(&got)
            .all(|(w, g)| w.0 == g.0 && w.1 == g.1 && w.2 == g.2 && g.3.contains(&w.3));
    let rendered: String = ds.iter().map(|d| d.render(&map, false)).collect();
    assert!(
        ok,
        "{case}:\n  expected {want:#?}\n  got      {got:#?}\n{rendered}"
    );
    for d in &ds {
        assert_eq!(d.code, "input", "{rendered}");
        assert_eq!(d.severity, bdi_check::syntax::Severity::Error);
    }
    (map, ds)
}

#[test]
fn every_broken_case_has_a_test() {
    let mut cases: Vec<String> = std::fs::read_dir(root().join("tests/typecheck"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("expect.txt").is_file())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    cases.sort();
    assert_eq!(
        cases,
        [
            "agent_misc",
            "constant_type",
            "env_update",
            "fact_type",
            "internal_action",
            "invariant_unknown",
            "manifest_misc",
            "pair_unknown_action",
            "performative",
            "request_arity",
            "strong_negation",
            "two_types",
            "unknown_object",
            "unknown_predicate",
            "wrong_arity",
        ]
    );
}

#[test]
fn unknown_predicates_are_located_with_suggestions() {
    broken("unknown_predicate");
}

#[test]
fn wrong_arity_points_at_the_pddl_declaration() {
    let (map, ds) = broken("wrong_arity");
    let decl = |d: &Diagnostic| {
        let l = &d.secondary[0];
        (
            map.location(l.span).line,
            map.slice(l.span).lines().next().unwrap().to_string(),
        )
    };
    assert_eq!(
        decl(&ds[0]),
        (19, "(cupAt ?c - cup ?l - location)".to_string())
    );
    assert_eq!(decl(&ds[1]), (26, "(:action navigateTo".to_string()));
}

#[test]
fn constants_of_the_wrong_type() {
    broken("constant_type");
}

#[test]
fn unknown_objects_numbers_and_strings() {
    broken("unknown_object");
}

#[test]
fn a_variable_with_two_unrelated_types_names_both_positions() {
    let (map, ds) = broken("two_types");
    let first = ds[0].secondary[0].span;
    assert_eq!(map.slice(first), "C");
    assert_eq!(map.location(first).line, 2);
    assert_eq!(ds[0].secondary[0].text, "`used` expects a `cup`");
    assert_eq!(ds[1].label.as_deref(), Some("`!fetch` expects a `cup`"));
}

#[test]
fn belief_updates_on_environment_predicates() {
    broken("env_update");
}

#[test]
fn unmodelled_internal_actions() {
    broken("internal_action");
}

#[test]
fn performatives_not_modelled_are_refused_where_written() {
    broken("performative");
}

#[test]
fn unknown_predicate_in_an_invariant_is_located_in_the_toml() {
    broken("invariant_unknown");
}

#[test]
fn a_fact_of_the_wrong_type() {
    broken("fact_type");
}

#[test]
fn an_expected_pair_naming_an_unknown_action() {
    broken("pair_unknown_action");
}

#[test]
fn a_request_with_the_wrong_arity() {
    broken("request_arity");
}

#[test]
fn strong_negation_of_an_environment_predicate() {
    broken("strong_negation");
}

#[test]
fn manifest_vary_emitted_by_phrases_and_properties() {
    broken("manifest_misc");
}

#[test]
fn an_undefined_action_is_not_an_error() {
    let (map, u, v) = ok("tests/typecheck/undefined_action");
    let undefined: Vec<(&str, usize, String)> = v
        .undefined_actions
        .iter()
        .map(|a| (a.name.as_str(), a.arity, map.slice(a.span).to_string()))
        .collect();
    // `say` is the `emitted_by` action: the manifest defines it.
    assert_eq!(
        undefined,
        [
            ("beep", 1, "beep(3)".to_string()),
            ("honk", 0, "honk".to_string())
        ]
    );
    assert_eq!(v.goals.len(), 1);
    assert_eq!(names(&u, &v.goals[0].params), Vec::<String>::new());
}

#[test]
fn mental_notes_rules_and_goal_types_are_inferred() {
    let (map, u, v) = ok("tests/typecheck/inference");
    let notes: Vec<(&str, Vec<String>, String)> = v
        .mental_notes()
        .map(|p| {
            (
                p.name.as_str(),
                names(&u, &p.params),
                map.slice(p.span()).to_string(),
            )
        })
        .collect();
    assert_eq!(
        notes,
        [
            // The initial belief is the first addition; `+visited(L)` agrees on `location`.
            (
                "visited",
                vec!["location".to_string()],
                "visited(table)".to_string()
            ),
            ("marked", vec!["cup".into()], "marked(C)".into()),
            // Added with a cup and with a location: their common ancestor.
            ("thing", vec!["object".into()], "thing(cup1)".into()),
        ]
    );
    assert_eq!(v.predicate("visited").map(|(i, _)| i), Some(6));
    let goals: Vec<(&str, usize, Vec<String>, bool)> = v
        .goals
        .iter()
        .map(|g| (g.name.as_str(), g.arity, names(&u, &g.params), g.has_plan))
        .collect();
    assert_eq!(
        goals,
        [
            ("tidy", 1, vec!["cup".to_string()], true),
            ("fetch", 1, vec!["cup".into()], true),
            // `!report(C)` passes a cup, but report's plan does not constrain its parameter.
            ("report", 1, vec!["object".into()], true),
            // The type of `c`'s parameter flows back through `b` to `a`.
            ("a", 1, vec!["location".into()], true),
            ("b", 1, vec!["location".into()], true),
            ("c", 1, vec!["location".into()], true),
            ("both", 0, vec![], true),
            // Requested but planned nowhere: recorded for lint's `no-plan-for-goal`.
            ("unplanned", 1, vec!["object".into()], false),
        ]
    );
    let rules: Vec<(&str, usize, Vec<String>)> = v
        .rules
        .iter()
        .map(|r| (r.name.as_str(), r.arity, names(&u, &r.params)))
        .collect();
    assert_eq!(rules, [("near", 1, vec!["location".to_string()])]);
    assert!(v.rule("near", 1).is_some());
    // `explain` is the `emitted_by` action.
    assert!(v.undefined_actions.is_empty());
}

#[test]
fn environment_beliefs_note_arity_and_unsupported_constructs() {
    broken("agent_misc");
}
