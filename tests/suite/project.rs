//! Loading whole projects: the kitchen's ground atoms, ground actions and initial states,
//! each checked against a count computed another way (from the files directly, and by
//! brute force over every assignment), and PDDL semantics on concrete states.

use bdi_check::model::atoms::AtomSet;
use bdi_check::model::project::{load_project, Project};
use bdi_check::model::ObjectId;
use bdi_check::syntax::ast::ExprKind;
use std::path::Path;

fn kitchen() -> Project {
    match load_project(Path::new("specs/kitchen")) {
        Ok(p) => p,
        Err(e) => {
            let text: Vec<String> = e
                .diagnostics
                .iter()
                .map(|d| d.render(&e.map, false))
                .collect();
            panic!("specs/kitchen does not load:\n{}", text.join("\n"))
        }
    }
}

/// Number of objects of a PDDL type, counted from the PDDL constants and the manifest
/// objects directly (not through the `Universe`).
fn objects_of(p: &Project, ty: &str) -> usize {
    let is_sub = |t: &str| p.domain.is_subtype(t, ty) || t == ty;
    let constants = p.domain.constants.iter().filter(|c| is_sub(&c.ty)).count();
    let manifest: usize = p
        .manifest
        .objects
        .iter()
        .filter(|g| is_sub(&g.name.value))
        .map(|g| g.objects.len())
        .sum();
    constants + manifest
}

#[test]
fn kitchen_ground_atoms_and_actions_match_the_signatures() {
    let p = kitchen();
    let atoms: usize = p
        .domain
        .predicates
        .iter()
        .map(|pr| {
            pr.params
                .iter()
                .map(|v| objects_of(&p, &v.ty))
                .product::<usize>()
        })
        .sum();
    // The kitchen agent adds no mental notes: every atom is a PDDL atom.
    assert_eq!(p.atoms.len(), atoms);
    let actions: usize = p
        .domain
        .actions
        .iter()
        .map(|a| {
            a.params
                .iter()
                .map(|v| objects_of(&p, &v.ty))
                .product::<usize>()
        })
        .sum();
    assert_eq!(p.actions.len(), actions);
    // 3 locations, 2 cups + none, 2 door states.
    assert_eq!(objects_of(&p, "location"), 3);
    assert_eq!(objects_of(&p, "item"), 3);
    assert_eq!(atoms, 3 + 3 + 2 * 3 + 2 + 2 + 3);
}

#[test]
fn kitchen_initial_states_equal_brute_force_enumeration() {
    let p = kitchen();
    let vary = &p.initial.vary;
    assert!(vary.len() <= 20, "brute force needs a small vary set");
    let checks: Vec<_> = p
        .constraints
        .iter()
        .chain(p.invariants.iter().map(|(_, c)| c))
        .collect();
    let mut brute = Vec::new();
    for bits in 0u64..(1 << vary.len()) {
        let mut s = p.initial.facts.clone();
        for (i, a) in vary.iter().enumerate() {
            if bits >> i & 1 == 1 {
                s.insert(*a);
            }
        }
        if checks.iter().all(|c| c.eval(&s)) && !brute.contains(&s) {
            brute.push(s);
        }
    }
    brute.sort();
    assert_eq!(p.initial.states(), brute);
    // By hand: per cup 5 (used or not) x (table, dishwasher, cupboard) combinations minus a
    // used cup in the cupboard; 2 door states; the table dirty or not.
    assert_eq!(p.initial.states().len(), 5 * 5 * 2 * 2);
}

fn state(p: &Project, atoms: &[&str]) -> AtomSet {
    let mut s = AtomSet::empty(p.atoms.len());
    for text in atoms {
        let e = bdi_check::syntax::parse_expr(bdi_check::syntax::FileId(0), text).unwrap();
        let ExprKind::Literal(l) = &e.kind else {
            panic!("{text}")
        };
        let pred = p.atoms.pred(&l.functor).unwrap();
        let args: Vec<ObjectId> = l
            .args
            .iter()
            .map(|a| match &a.kind {
                ExprKind::Literal(o) => p.universe.object(&o.functor).unwrap(),
                _ => panic!(),
            })
            .collect();
        s.insert(p.atoms.id(pred, &args).unwrap());
    }
    s
}

fn show(p: &Project, s: &AtomSet) -> Vec<String> {
    s.iter().map(|a| p.atoms.display(a, &p.universe)).collect()
}

#[test]
fn pddl_semantics_on_the_kitchen() {
    let p = kitchen();
    let obj = |n: &str| p.universe.object(n).unwrap();
    let s0 = state(
        &p,
        &[
            "robotAt(table)",
            "holding(none)",
            "cupAt(cup1,table)",
            "used(cup1)",
            "dishwasherDoor(closed)",
            "cupAt(cup2,cupboard)",
        ],
    );
    // navigateTo: conditional delete of the old place, add of the new.
    let go = p.actions.get("navigateTo", &[obj("dishwasher")]).unwrap();
    assert!(go.applicable(&s0));
    let s1 = go.apply(&s0);
    assert!(show(&p, &s1).contains(&"robotAt(dishwasher)".to_string()));
    assert!(!show(&p, &s1).contains(&"robotAt(table)".to_string()));
    // Moving to where the robot is: delete-then-add keeps it there.
    let stay = p.actions.get("navigateTo", &[obj("table")]).unwrap();
    assert_eq!(stay.apply(&s0), s0);
    // pickUp needs the cup where the robot is.
    let pick = p.actions.get("pickUp", &[obj("cup1")]).unwrap();
    assert!(pick.applicable(&s0));
    assert!(!pick.applicable(&s1));
    let s2 = pick.apply(&s0);
    // Atoms print in predicate order (robotAt, holding, cupAt, used, dishwasherDoor).
    assert_eq!(
        show(&p, &s2),
        [
            "robotAt(table)",
            "holding(cup1)",
            "cupAt(cup2,cupboard)",
            "used(cup1)",
            "dishwasherDoor(closed)"
        ]
    );
    // putDown into the dishwasher needs the door open.
    let s3 = go.apply(&s2);
    let put = p.actions.get("putDown", &[obj("cup1")]).unwrap();
    assert!(!put.applicable(&s3));
    // startDishwasher: the `when` reads the state before the action.
    let mut s4 = state(
        &p,
        &[
            "robotAt(dishwasher)",
            "holding(none)",
            "cupAt(cup1,dishwasher)",
            "used(cup1)",
            "used(cup2)",
            "cupAt(cup2,table)",
            "dishwasherDoor(closed)",
        ],
    );
    let start = p
        .actions
        .get("startDishwasher", &[obj("dishwasher")])
        .unwrap();
    assert!(start.applicable(&s4));
    s4 = start.apply(&s4);
    let after = show(&p, &s4);
    assert!(!after.contains(&"used(cup1)".to_string()));
    assert!(after.contains(&"used(cup2)".to_string()));
    // `openDoor(table)` exists as a ground action but can never run.
    let open_table = p.actions.get("openDoor", &[obj("table")]).unwrap();
    assert!(p.initial.states().iter().all(|s| !open_table.applicable(s)));
}

/// Every project under `tests/project/<case>/` fails to load with exactly the diagnostics
/// its manifest's `# expect: [FILE:]LINE:COLUMN substring` lines name.
#[test]
fn broken_projects_report_located_errors() {
    let mut cases = 0;
    for entry in std::fs::read_dir("tests/project").unwrap() {
        let dir = entry.unwrap().path();
        let manifest = dir.join("bdi-check.toml");
        if !manifest.exists() {
            continue;
        }
        cases += 1;
        let text = std::fs::read_to_string(&manifest).unwrap();
        let expected: Vec<(String, String)> = text
            .lines()
            .filter_map(|l| l.strip_prefix("# expect: "))
            .map(|l| {
                let (loc, msg) = l.split_once(' ').unwrap();
                (loc.to_string(), msg.to_string())
            })
            .collect();
        assert!(
            !expected.is_empty(),
            "{}: no `# expect:` line",
            dir.display()
        );
        let err = match load_project(&dir) {
            Ok(_) => panic!("{} loaded, but should fail", dir.display()),
            Err(e) => e,
        };
        let got: Vec<(String, String)> = err
            .diagnostics
            .iter()
            .map(|d| {
                let loc = d.location(&err.map).unwrap();
                (
                    format!("{}:{}:{}", loc.file, loc.line, loc.column),
                    d.message.clone(),
                )
            })
            .collect();
        assert_eq!(got.len(), expected.len(), "{}: got {got:#?}", dir.display());
        for (loc, msg) in &expected {
            let loc = if loc.matches(':').count() == 1 {
                format!("bdi-check.toml:{loc}")
            } else {
                loc.clone()
            };
            assert!(
                got.iter()
                    .any(|(l, m)| l.ends_with(&loc) && m.contains(msg.as_str())),
                "{}: expected {loc} {msg:?}, got {got:#?}",
                dir.display()
            );
        }
        for d in &err.diagnostics {
            let first = d.render(&err.map, false);
            assert!(
                first.lines().next().unwrap().contains(": error["),
                "{first}"
            );
        }
    }
    assert!(cases >= 7);
}

#[test]
fn swapping_cups_maps_states_and_atoms_consistently() {
    let p = kitchen();
    let (c1, c2) = (
        p.universe.object("cup1").unwrap(),
        p.universe.object("cup2").unwrap(),
    );
    let perm: Vec<ObjectId> = p
        .universe
        .objects()
        .map(|o| {
            if o == c1 {
                c2
            } else if o == c2 {
                c1
            } else {
                o
            }
        })
        .collect();
    let map = p.atoms.permutation_map(&perm);
    let s = state(
        &p,
        &[
            "robotAt(table)",
            "holding(cup1)",
            "cupAt(cup2,dishwasher)",
            "used(cup2)",
        ],
    );
    let t = s.permuted(&map);
    assert_eq!(
        show(&p, &t),
        [
            "robotAt(table)",
            "holding(cup2)",
            "cupAt(cup1,dishwasher)",
            "used(cup1)"
        ]
    );
    // A swap is its own inverse, and the initial states are closed under it.
    assert_eq!(t.permuted(&map), s);
    for s in p.initial.states() {
        assert!(p.initial.states().binary_search(&s.permuted(&map)).is_ok());
    }
}
