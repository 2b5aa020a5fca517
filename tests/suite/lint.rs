//! `bdi-check lint`: the seeded defects are found, the kitchen has no error, the paper's gap
//! is reported with the door open, and every state-based answer equals what brute-force
//! enumeration of all states says (an explicit evaluator of plan formulas, independent of
//! the z3 encoding).

use bdi_check::findings::{Report, Status, Verdict};
use bdi_check::model::atoms::{AtomId, AtomSet};
use bdi_check::model::cond::Cond;
use bdi_check::model::initial;
use bdi_check::model::plans::{BodyStep, Formula, Plan, Step};
use bdi_check::model::project::{load_project, Project};
use bdi_check::model::term::{Term, Var};
use bdi_check::model::universe::{ObjectId, TypeId};
use bdi_check::smt::encode::{rule_clauses, Clause};
use bdi_check::smt::summary::{matching_atoms, same_predicate_atoms, Effects, Summaries};
use bdi_check::smt::{lint, LintFinding, LintOptions};
use bdi_check::syntax::ast::{RelOp, TriggerKind, TriggerOp};
use bdi_check::syntax::manifest::PlanSelection;
use bdi_check::syntax::{Severity, Span};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::path::Path;
use std::process::Output;

use crate::common;
use common::bdi_check;

fn project(path: &str) -> Project {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    match load_project(&dir) {
        Ok(p) => p,
        Err(e) => panic!("{path} does not load: {:?}", e.diagnostics),
    }
}

fn run_lint(p: &Project) -> Vec<LintFinding> {
    lint(p, &LintOptions::default())
}

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).expect("the report is JSON")
}

fn failing(fs: &[LintFinding]) -> Vec<&LintFinding> {
    fs.iter()
        .filter(|f| f.finding.status == Status::Fail)
        .collect()
}

fn place(f: &LintFinding) -> String {
    let l = f
        .finding
        .location
        .as_ref()
        .expect("lint findings have a location");
    format!("{}:{}", l.file.rsplit('/').next().unwrap_or(""), l.line)
}

// ----- the done-when criteria -------------------------------------------------------------

#[test]
fn paper_reports_the_coverage_gap_with_the_door_open() {
    let o = bdi_check(&["lint", "specs/paper", "--format", "json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v = json(&o);
    assert_eq!(v["verdict"], "pass");
    let gaps: Vec<&serde_json::Value> = v["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .filter(|f| f["check"] == "coverage-gap" && f["status"] == "fail")
        .filter(|f| {
            f["message"]
                .as_str()
                .unwrap_or("")
                .contains("+!openDishwasherIfNeed")
        })
        .collect();
    assert_eq!(gaps.len(), 1, "{v:#}");
    let gap = gaps[0];
    assert_eq!(gap["severity"], "warning");
    assert_eq!(gap["location"]["line"], 19);
    assert_eq!(gap["id"], "coverage-gap:specs/paper/paper.asl:19");
    assert!(
        gap["message"]
            .as_str()
            .unwrap()
            .ends_with("when dishwasherDoor(open) (this can be an initial state)"),
        "{gap:#}"
    );
    let initial: Vec<&str> = gap["counterexample"]["initial"]
        .as_array()
        .expect("a state")
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    // The state the paper describes: the running example's initial state, door open.
    assert_eq!(
        initial,
        [
            "robotAt(table)",
            "holding(none)",
            "cupAt(cup1,table)",
            "used(cup1)",
            "dishwasherDoor(open)"
        ]
    );
}

#[test]
fn the_kitchen_has_no_error() {
    let p = project("specs/kitchen");
    let fs = run_lint(&p);
    let bad: Vec<&LintFinding> = fs
        .iter()
        .filter(|f| f.finding.status != Status::Pass && f.finding.severity == Severity::Error)
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    assert!(fs.iter().all(|f| f.finding.status != Status::Unknown));
    let o = bdi_check(&["lint", "specs/kitchen", "-q"]);
    assert_eq!(o.status.code(), Some(0));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.starts_with("lint specs/kitchen: 0 errors,"), "{out}");
    assert!(out.trim_end().ends_with(": pass"), "{out}");
}

/// Each seeded project (tests/lint/<case>) with the check it must fail and where; errors
/// other than the seeded one must not appear.
const SEEDED: &[(&str, &str, &str)] = &[
    ("dead_plan", "dead-plan", "kitchen.asl:84"),
    ("shadowed_plan", "shadowed-plan", "kitchen.asl:84"),
    ("coverage_gap", "coverage-gap", "kitchen.asl:53"),
    ("plan_overlap", "plan-overlap", "kitchen.asl:59"),
    ("precondition", "precondition", "kitchen.asl:61"),
    ("effect_conflict", "effect-conflict", "kitchen.pddl:25"),
    (
        "action_breaks_invariant",
        "action-breaks-invariant",
        "kitchen.pddl:32",
    ),
    ("undefined_action", "undefined-action", "kitchen.asl:82"),
    ("unused_action", "unused-action", "kitchen.pddl:72"),
    ("no_plan_for_goal", "no-plan-for-goal", "kitchen.asl:9"),
];

#[test]
fn every_seeded_defect_is_found_and_nothing_else_is_an_error() {
    let kitchen = run_lint(&project("specs/kitchen"));
    // By check, place and message: a seeded copy's lines need not be the kitchen's.
    let in_kitchen: BTreeSet<(String, String, String)> = failing(&kitchen)
        .iter()
        .map(|f| (f.finding.check.clone(), place(f), f.finding.message.clone()))
        .collect();
    for (case, check, at) in SEEDED {
        let fs = run_lint(&project(&format!("tests/lint/{case}")));
        let found: Vec<&LintFinding> = failing(&fs)
            .into_iter()
            .filter(|f| f.finding.check == *check && place(f) == *at)
            .collect();
        assert_eq!(
            found.len(),
            1,
            "{case}: no {check} at {at} in {:#?}",
            failing(&fs)
        );
        let f = found[0];
        assert_eq!(
            f.finding.severity,
            bdi_check::smt::lint::severity(check),
            "{case}"
        );
        assert!(
            f.finding.id.starts_with(&format!("{check}:")),
            "{case}: {}",
            f.finding.id
        );
        // The finding is new: the correct kitchen has none there.
        assert!(
            !in_kitchen.contains(&(check.to_string(), at.to_string(), f.finding.message.clone())),
            "{case}"
        );
        let errors: Vec<String> = failing(&fs)
            .iter()
            .filter(|f| f.finding.severity == Severity::Error)
            .map(|f| format!("{} {}", f.finding.check, place(f)))
            .collect();
        let expected: Vec<String> = if f.finding.severity == Severity::Error {
            vec![format!("{check} {at}")]
        } else {
            Vec::new()
        };
        assert_eq!(errors, expected, "{case}");
        assert!(
            fs.iter().all(|f| f.finding.status != Status::Unknown),
            "{case}"
        );
        // State-based findings show a state; the messages name the literals at fault.
        if ![
            "dead-plan",
            "undefined-action",
            "unused-action",
            "no-plan-for-goal",
        ]
        .contains(check)
        {
            let cx = f
                .finding
                .counterexample
                .as_ref()
                .expect("a counterexample state");
            assert!(!cx.initial.is_empty(), "{case}");
        }
    }
}

#[test]
fn seeded_messages_name_the_literals_at_fault() {
    let msg = |case: &str, check: &str| {
        let (_, _, at) = SEEDED
            .iter()
            .find(|(c, _, _)| *c == case)
            .expect("a seeded case");
        let fs = run_lint(&project(&format!("tests/lint/{case}")));
        failing(&fs)
            .iter()
            .find(|f| f.finding.check == check && place(f) == *at)
            .map(|f| f.finding.message.clone())
            .expect("the finding")
    };
    let dead = msg("dead_plan", "dead-plan");
    assert!(
        dead.contains("`dishwasherDoor(open)` and `dishwasherDoor(closed)`"),
        "{dead}"
    );
    assert!(dead.contains("invariant `door_open_or_closed`"), "{dead}");
    let shadow = msg("shadowed_plan", "shadowed-plan");
    assert!(
        shadow.starts_with("@tableAlreadyClean is never chosen: the earlier plan @wipeDirtyTable"),
        "{shadow}"
    );
    let gap = msg("coverage_gap", "coverage-gap");
    assert!(gap.contains("+!runDishwasher is applicable when not cupAt(cup1,dishwasher) & not cupAt(cup2,dishwasher)"), "{gap}");
    let pre = msg("precondition", "precondition");
    assert!(
        pre.ends_with("in @runClosedDishwasher, e.g. when not robotAt(dishwasher)"),
        "{pre}"
    );
    let conflict = msg("effect_conflict", "effect-conflict");
    assert!(
        conflict.contains("both adds and deletes robotAt("),
        "{conflict}"
    );
    let breaks = msg("action_breaks_invariant", "action-breaks-invariant");
    assert!(
        breaks.contains("`one_item_in_hand`") && breaks.contains("holding(none) & holding(cup"),
        "{breaks}"
    );
    let undefined = msg("undefined_action", "undefined-action");
    assert!(
        undefined.contains("`wype/1`") && undefined.contains("did you mean `wipe`?"),
        "{undefined}"
    );
}

/// A shadowed plan is hidden by plans that are chosen: one that is never chosen itself is
/// not named "chosen instead", even where it is applicable whenever the hidden one is.
#[test]
fn a_shadowed_plan_is_hidden_by_plans_that_are_chosen() {
    let fs = run_lint(&project("tests/lint/shadowed_by_chosen"));
    let shadowed: Vec<(String, String, Vec<String>)> = failing(&fs)
        .iter()
        .filter(|f| f.finding.check == "shadowed-plan")
        .map(|f| {
            let hiders = f.secondary.iter().map(|(_, label)| label.clone()).collect();
            (place(f), f.finding.message.clone(), hiders)
        })
        .collect();
    assert_eq!(shadowed.len(), 2, "{shadowed:#?}");
    for (at, msg, hiders) in &shadowed {
        assert!(
            ["agent.asl:3", "agent.asl:4"].contains(&at.as_str()),
            "{at}"
        );
        assert!(msg.contains("the earlier plan @broad "), "{msg}");
        assert_eq!(hiders, &["chosen instead".to_string()], "{at}");
    }
}

#[test]
fn goal_summaries_follow_subgoals_transitively() {
    fn atom_names(p: &Project, set: &BTreeSet<AtomId>) -> Vec<String> {
        set.iter()
            .map(|a| p.atoms.display(*a, &p.universe))
            .collect()
    }
    let p = project("specs/kitchen");
    let sum = Summaries::compute(&p);
    let names = |set: &BTreeSet<AtomId>| atom_names(&p, set);
    let open = sum.goal("openDishwasherIfNeed", 0).expect("a summary");
    assert_eq!(
        names(&open.add),
        ["robotAt(dishwasher)", "dishwasherDoor(open)"]
    );
    assert_eq!(
        names(&open.del),
        [
            "robotAt(table)",
            "robotAt(cupboard)",
            "dishwasherDoor(closed)"
        ]
    );
    // putAway goes through openDishwasherIfNeed; unloadDishwasher through putAway and itself.
    let put = sum.goal("putAway", 1).expect("a summary");
    let unload = sum.goal("unloadDishwasher", 0).expect("a summary");
    for (inner, outer) in [(open, put), (put, unload)] {
        assert!(inner.add.is_subset(&outer.add) && inner.del.is_subset(&outer.del));
    }
    assert!(put.add.len() > open.add.len());
    assert!(sum.goal("openDishwasher", 0).is_none());
    // Mental notes count: `-seen(_)` may delete every `seen` atom, `-+seen(I)` too.
    let q = project("tests/lint/subgoals");
    let sum = Summaries::compute(&q);
    let names = |set: &BTreeSet<AtomId>| atom_names(&q, set);
    let busy = sum.goal("busy", 0).expect("a summary");
    assert_eq!(
        names(&busy.del)
            .iter()
            .filter(|a| a.starts_with("seen("))
            .count(),
        2
    );
    assert!(names(&busy.add).contains(&"unlocked(hall)".to_string()));
}

// ----- the command line -------------------------------------------------------------------

#[test]
fn human_output_shows_the_plan_under_the_message() {
    let o = bdi_check(&["lint", "specs/paper"]);
    assert_eq!(o.status.code(), Some(0));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(
            "specs/paper/paper.asl:19:1: warning[coverage-gap]: no plan for +!openDishwasherIfNeed"
        ),
        "{out}"
    );
    assert!(
        out.contains("+!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)"),
        "{out}"
    );
    assert!(out.contains("  state: robotAt(table), holding(none), cupAt(cup1,table), used(cup1), dishwasherDoor(open)"), "{out}");
    // Notes only with `-v`; without, a line says how many there are. Warnings come
    // before notes.
    assert!(!out.contains("note[unused-action]"), "{out}");
    assert!(out.contains(" notes not shown (`-v` shows them)"), "{out}");
    assert!(!out.contains("passed["), "{out}");
    let verbose =
        String::from_utf8_lossy(&bdi_check(&["lint", "specs/paper", "-v"]).stdout).into_owned();
    assert!(verbose.contains("passed[dead-plan]"), "{verbose}");
    let note = verbose
        .find("note[unused-action]: no plan calls the action `wipe`")
        .expect("the note with -v");
    let warning = verbose.find("warning[coverage-gap]").expect("the warning");
    assert!(warning < note, "{verbose}");
}

#[test]
fn deny_warnings_makes_warnings_fail() {
    let o = bdi_check(&[
        "lint",
        "specs/paper",
        "--deny",
        "warnings",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let v = json(&o);
    assert_eq!(v["verdict"], "fail");
    let gap = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["check"] == "coverage-gap" && f["status"] == "fail")
        .expect("the gap");
    assert_eq!(gap["severity"], "error");
    // Notes stay notes.
    assert!(v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|f| f["check"] == "unused-action"
            && f["status"] == "fail"
            && f["severity"] == "note"));
}

#[test]
fn errors_exit_1_and_the_report_goes_to_a_file() {
    let dir = common::temp_dir("lint-test");
    let out = dir.join("report.json");
    let o = bdi_check(&[
        "lint",
        "tests/lint/dead_plan",
        "--format",
        "json",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(v["verdict"], "fail");
    assert_eq!(v["project"], "tests/lint/dead_plan");
    let ids: Vec<&str> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["id"].as_str().unwrap())
        .collect();
    let unique: BTreeSet<&str> = ids.iter().copied().collect();
    assert_eq!(ids.len(), unique.len(), "ids are unique: {ids:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_exits_2_with_input_findings() {
    let o = bdi_check(&["lint", "tests/project/broken_pddl", "--format", "json"]);
    assert_eq!(o.status.code(), Some(2));
    let v = json(&o);
    assert_eq!(v["verdict"], "error");
    let f = &v["findings"][0];
    assert_eq!(f["check"], "input");
    assert_eq!(f["severity"], "error");
    assert_eq!(f["location"]["line"], 3);
    let o = bdi_check(&["lint", "tests/project/broken_pddl"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("d.pddl:3:40: error[input]: undefined predicate `q`"),
        "{err}"
    );
    let o = bdi_check(&["lint", "tests/lint/no_such_project"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn what_lint_cannot_encode_is_undecided_exit_3() {
    let o = bdi_check(&["lint", "tests/lint/unsupported", "--format", "json"]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let v = json(&o);
    assert_eq!(v["verdict"], "incomplete");
    let unknown: Vec<&serde_json::Value> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["status"] == "unknown")
        .collect();
    assert!(!unknown.is_empty());
    assert!(
        unknown
            .iter()
            .any(|f| f["message"].as_str().unwrap().contains(".length")),
        "{unknown:#?}"
    );
    assert!(unknown.iter().all(|f| f["counterexample"].is_null()));
}

#[test]
fn desires_and_intentions_are_free_but_consistent_booleans() {
    let fs = run_lint(&project("tests/lint/desire"));
    let fails: Vec<(String, String)> = failing(&fs)
        .iter()
        .filter(|f| f.finding.severity != Severity::Note)
        .map(|f| (f.finding.check.clone(), f.finding.message.clone()))
        .collect();
    // `.desire(b)` and `not .desire(b)` cover `!a` and exclude each other; `!b` has a gap
    // when the agent does not desire it or does not intend `a`, and no plan is dead.
    assert_eq!(fails.len(), 1, "{fails:?}");
    assert_eq!(fails[0].0, "coverage-gap");
    let gap = &fails[0].1;
    assert!(
        gap.starts_with("no plan for +!b is applicable when not .desire(b)")
            || gap.starts_with("no plan for +!b is applicable when not .intend(a)"),
        "{gap}"
    );
    assert!(fs.iter().all(|f| f.finding.status != Status::Unknown));
}

#[test]
fn a_budget_too_small_gives_unknown_never_a_wrong_answer() {
    let p = project("specs/kitchen");
    let full = run_lint(&p);
    let tiny = lint(
        &p,
        &LintOptions {
            rlimit: 1,
            deadline: None,
        },
    );
    assert!(tiny.iter().any(|f| f.finding.status == Status::Unknown));
    let key = |f: &LintFinding| (f.finding.check.clone(), f.finding.id.clone());
    let full_status: BTreeMap<_, _> = full.iter().map(|f| (key(f), f.finding.status)).collect();
    for f in &tiny {
        if f.finding.status != Status::Unknown {
            assert_eq!(full_status.get(&key(f)), Some(&f.finding.status), "{f:#?}");
        }
    }
    let report = Report::new("kitchen", tiny.iter().map(|f| f.finding.clone()).collect());
    assert_ne!(report.verdict, Verdict::Pass);
}

#[test]
fn plans_that_change_at_run_time_are_judged_by_the_libraries_they_may_be_in() {
    let path = "tests/lint/dynamic_plans";
    let fs = run_lint(&project(path));
    let at = |check: &str, status: Status| -> Vec<String> {
        fs.iter()
            .filter(|f| f.finding.check == check && f.finding.status == status)
            .map(place)
            .collect()
    };
    // Hidden only by @s1, always there and before them; not @h2 (@h1 is removed), not
    // @early (added at the beginning).
    assert_eq!(
        at("shadowed-plan", Status::Fail),
        ["agent.asl:7", "agent.asl:13"]
    );
    assert_eq!(at("dead-plan", Status::Fail), ["agent.asl:15"]);
    // !k is covered by @s1; !g has a gap with every plan it may have; !h is covered only
    // while @h1 is there.
    assert!(at("coverage-gap", Status::Pass).contains(&"agent.asl:6".to_string()));
    assert_eq!(at("coverage-gap", Status::Fail), ["agent.asl:10"]);
    assert_eq!(at("coverage-gap", Status::Unknown), ["agent.asl:8"]);
    // verify settles !h by its runs: one removes @h1 and then meets the gap.
    let o = bdi_check(&["verify", path, "--format", "json"]);
    let v = json(&o);
    let gaps: Vec<&serde_json::Value> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["check"] == "coverage-gap" && f["status"] == "fail")
        .collect();
    let h = gaps
        .iter()
        .find(|f| f["location"]["line"] == 8)
        .unwrap_or_else(|| panic!("{gaps:#?}"));
    assert_eq!(h["severity"], "error");
    let steps = h["counterexample"]["steps"].to_string();
    assert!(steps.contains(".remove_plan(h1)"), "{steps}");
}

#[test]
fn lint_is_deterministic() {
    let p = project("tests/lint/constructs");
    let a = run_lint(&p);
    let b = run_lint(&p);
    assert_eq!(a, b);
}

// ----- brute force ------------------------------------------------------------------------

/// A value during explicit evaluation.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum V {
    Obj(ObjectId),
    Int(i64),
    Other(Term),
}

type B = BTreeMap<Var, V>;

/// Jason's answers to plan formulas on an explicit state, rules included.
struct Eval<'p> {
    p: &'p Project,
    rules: HashMap<(String, usize), Vec<Clause>>,
}

impl<'p> Eval<'p> {
    fn new(p: &'p Project) -> Eval<'p> {
        let rules = rule_clauses(p)
            .into_iter()
            .map(|(k, v)| (k, v.expect("test rules convert")))
            .collect();
        Eval { p, rules }
    }

    fn val(&self, t: &Term, b: &B) -> Option<V> {
        match t {
            Term::Var(v) => b.get(v).cloned(),
            Term::Atom(n) => Some(match self.p.universe.object(n) {
                Some(o) => V::Obj(o),
                None => V::Other(t.clone()),
            }),
            Term::Num(n) => Some(match n.as_i64() {
                Some(i) => V::Int(i),
                None => V::Other(t.clone()),
            }),
            Term::Struct(s) if ["+", "-", "*"].contains(&s.functor()) => {
                let xs: Option<Vec<i64>> = s
                    .args()
                    .iter()
                    .map(|a| match self.val(a, b) {
                        Some(V::Int(i)) => Some(i),
                        _ => None,
                    })
                    .collect();
                let xs = xs?;
                Some(V::Int(match (s.functor(), xs.as_slice()) {
                    ("+", [x, y]) => x + y,
                    ("-", [x, y]) => x - y,
                    ("*", [x, y]) => x * y,
                    ("-", [x]) => -x,
                    _ => panic!("arithmetic {t}"),
                }))
            }
            _ if t.is_ground() => Some(V::Other(t.clone())),
            _ => panic!("the brute force does not evaluate {t}"),
        }
    }

    /// Binds the arguments of `t` to the atom `a`'s objects, if they match.
    fn match_atom(&self, t: &Term, a: AtomId, b: &B) -> Option<B> {
        let (p, objs) = self.p.atoms.decode(a);
        if self.p.atoms.pred_name(p) != t.functor()? || objs.len() != t.arity() {
            return None;
        }
        let mut b = b.clone();
        for (x, o) in t.args().iter().zip(objs.iter()) {
            match x {
                Term::Var(v) => match b.get(v) {
                    Some(V::Obj(w)) if w == o => {}
                    Some(_) => return None,
                    None if v.is_anonymous() => {}
                    None => {
                        b.insert(v.clone(), V::Obj(*o));
                    }
                },
                Term::Atom(n) if self.p.universe.object(n) == Some(*o) => {}
                _ => return None,
            }
        }
        Some(b)
    }

    fn literal(&self, t: &Term, s: &AtomSet, b: &B) -> Vec<B> {
        let key = (t.functor().unwrap_or("").to_string(), t.arity());
        if let Some(clauses) = self.rules.get(&key) {
            return self.rule(t, clauses, s, b);
        }
        s.iter().filter_map(|a| self.match_atom(t, a, b)).collect()
    }

    fn rule(&self, t: &Term, clauses: &[Clause], s: &AtomSet, b: &B) -> Vec<B> {
        let mut out = Vec::new();
        'clauses: for c in clauses {
            let mut cb = B::new();
            let mut pre = b.clone();
            let mut outs: Vec<(Var, Var)> = Vec::new();
            for (h, arg) in c.head.args().iter().zip(t.args()) {
                let av = self.val(arg, &pre);
                match h {
                    Term::Var(hv) => match (cb.get(hv).cloned(), av) {
                        (None, Some(v)) => {
                            cb.insert(hv.clone(), v);
                        }
                        (Some(x), Some(v)) if x != v => continue 'clauses,
                        (_, Some(_)) => {}
                        (_, None) => {
                            if let Term::Var(cv) = arg {
                                outs.push((cv.clone(), hv.clone()));
                            }
                        }
                    },
                    _ => {
                        let hv = self.val(h, &cb).expect("ground head argument");
                        match av {
                            Some(v) if v != hv => continue 'clauses,
                            Some(_) => {}
                            None => {
                                if let Term::Var(cv) = arg {
                                    if !cv.is_anonymous() {
                                        pre.insert(cv.clone(), hv);
                                    }
                                }
                            }
                        }
                    }
                }
            }
            for cb2 in self.answers(&c.body, s, &cb) {
                let mut b2 = pre.clone();
                let mut good = true;
                for (cv, hv) in &outs {
                    if cv.is_anonymous() {
                        continue;
                    }
                    let v = cb2.get(hv).cloned().expect("the rule binds its output");
                    match b2.get(cv) {
                        Some(x) if *x != v => good = false,
                        Some(_) => {}
                        None => {
                            b2.insert(cv.clone(), v);
                        }
                    }
                }
                if good && !out.contains(&b2) {
                    out.push(b2);
                }
            }
        }
        out
    }

    fn answers(&self, f: &Formula, s: &AtomSet, b: &B) -> Vec<B> {
        match f {
            Formula::True => vec![b.clone()],
            Formula::Literal(t) => self.literal(t, s, b),
            Formula::Not(g) => {
                if self.answers(g, s, b).is_empty() {
                    vec![b.clone()]
                } else {
                    Vec::new()
                }
            }
            Formula::And(x, y) => self
                .answers(x, s, b)
                .iter()
                .flat_map(|b1| self.answers(y, s, b1))
                .collect(),
            Formula::Or(x, y) => {
                let mut v = self.answers(x, s, b);
                v.extend(self.answers(y, s, b));
                v
            }
            Formula::Rel(op, x, y) => {
                let (vx, vy) = (self.val(x, b), self.val(y, b));
                let ok = match (op, vx, vy) {
                    (RelOp::Unify, None, Some(v)) | (RelOp::Unify, Some(v), None) => {
                        let var = match (x, y) {
                            (Term::Var(w), _) if !b.contains_key(w) => w,
                            (_, Term::Var(w)) => w,
                            _ => panic!("unify"),
                        };
                        let mut b2 = b.clone();
                        b2.insert(var.clone(), v);
                        return vec![b2];
                    }
                    (RelOp::Unify | RelOp::Eq, Some(a), Some(c)) => a == c,
                    (RelOp::Ne, Some(a), Some(c)) => a != c,
                    (RelOp::Lt, Some(V::Int(a)), Some(V::Int(c))) => a < c,
                    (RelOp::Le, Some(V::Int(a)), Some(V::Int(c))) => a <= c,
                    (RelOp::Gt, Some(V::Int(a)), Some(V::Int(c))) => a > c,
                    (RelOp::Ge, Some(V::Int(a)), Some(V::Int(c))) => a >= c,
                    other => panic!("the brute force does not evaluate {other:?}"),
                };
                if ok {
                    vec![b.clone()]
                } else {
                    Vec::new()
                }
            }
            Formula::Call(t) => match (t.functor(), t.args()) {
                (Some(".count"), [q, n]) => {
                    let k = s
                        .iter()
                        .filter(|a| self.match_atom(q, *a, b).is_some())
                        .count() as i64;
                    match self.val(n, b) {
                        Some(V::Int(m)) if m == k => vec![b.clone()],
                        Some(_) => Vec::new(),
                        None => {
                            let Term::Var(v) = n else { panic!("count") };
                            let mut b2 = b.clone();
                            b2.insert(v.clone(), V::Int(k));
                            vec![b2]
                        }
                    }
                }
                _ => panic!("the brute force does not evaluate {t}"),
            },
        }
    }
}

/// A plan body in execution: the state now and the bindings.
type Config = (AtomSet, B);

/// What brute force says about one project.
struct Truth {
    /// Failing state-based findings: check and `file:line:column`, sorted.
    failing: Vec<(String, String)>,
    /// For each failing finding, the start states that show it, and whether one of them is
    /// an initial state (then lint must show an initial state).
    witnesses: BTreeMap<(String, String), Vec<BTreeSet<AtomSet>>>,
    /// For each failing precondition step, its plan.
    pre_plans: BTreeMap<String, usize>,
}

struct World<'p> {
    p: &'p Project,
    ev: Eval<'p>,
    states: Vec<AtomSet>,
    state_set: HashSet<AtomSet>,
    sum: Summaries,
    volatile: Effects,
    /// The action steps whose precondition failed in the current run.
    steps: BTreeSet<String>,
}

impl<'p> World<'p> {
    fn new(p: &'p Project) -> World<'p> {
        let n = p.atoms.len();
        let all: Vec<AtomId> = (0..n as u32).map(AtomId).collect();
        let invs: Vec<Cond> = p.invariants.iter().map(|(_, c)| c.clone()).collect();
        let states =
            initial::enumerate(n, &AtomSet::empty(n), &all, &invs, 1_000_000).expect("few states");
        World {
            p,
            ev: Eval::new(p),
            state_set: states.iter().cloned().collect(),
            states,
            sum: Summaries::compute(p),
            volatile: Effects::default(),
            steps: BTreeSet::new(),
        }
    }

    fn loc(&self, span: Span) -> String {
        self.p.map.location(span).to_string()
    }

    fn inv(&self, s: &AtomSet) -> bool {
        self.state_set.contains(s)
    }

    fn events(&self, plan: &Plan) -> Vec<Vec<ObjectId>> {
        let t = &plan.trigger;
        let name = t.literal.functor().unwrap();
        let arity = t.literal.arity();
        let types = match t.kind {
            TriggerKind::Achieve => self
                .p
                .vocabulary
                .goal(name, arity)
                .map(|(_, g)| g.params.clone()),
            TriggerKind::Belief => self
                .p
                .atoms
                .pred(name)
                .map(|p| self.p.atoms.pred_params(p).to_vec()),
            TriggerKind::Test => None,
        }
        .unwrap_or_else(|| vec![TypeId::OBJECT; arity]);
        let mut out = vec![Vec::new()];
        for ty in types {
            out = out
                .into_iter()
                .flat_map(|pre: Vec<ObjectId>| {
                    self.p.universe.objects_of(ty).iter().map(move |o| {
                        let mut v = pre.clone();
                        v.push(*o);
                        v
                    })
                })
                .collect();
        }
        out
    }

    fn applicable(&self, plan: &Plan, e: &[ObjectId], s: &AtomSet) -> Vec<B> {
        let mut b = B::new();
        for (t, o) in plan.trigger.literal.args().iter().zip(e) {
            match t {
                Term::Var(v) => match b.get(v) {
                    Some(x) if *x != V::Obj(*o) => return Vec::new(),
                    Some(_) => {}
                    None if v.is_anonymous() => {}
                    None => {
                        b.insert(v.clone(), V::Obj(*o));
                    }
                },
                Term::Atom(n) if self.p.universe.object(n) == Some(*o) => {}
                _ => return Vec::new(),
            }
        }
        self.ev.answers(&plan.context, s, &b)
    }

    /// Every configuration after something that may change what `eff` says.
    fn havoc(&self, configs: Vec<Config>, eff: &Effects) -> Vec<Config> {
        if eff.is_empty() {
            return configs;
        }
        let touched = eff.touched();
        let key = |s: &AtomSet| {
            let mut k = s.clone();
            touched.iter().for_each(|a| k.remove(*a));
            k
        };
        let mut index: HashMap<AtomSet, Vec<&AtomSet>> = HashMap::new();
        for t in &self.states {
            index.entry(key(t)).or_default().push(t);
        }
        let mut out = HashSet::new();
        for (s, b) in configs {
            for t in index.get(&key(&s)).into_iter().flatten() {
                // An atom only added stays true; one only deleted stays false.
                let ok = touched.iter().all(|a| {
                    let (add, del) = (eff.add.contains(a), eff.del.contains(a));
                    let lost = s.contains(*a) && !t.contains(*a);
                    let gained = !s.contains(*a) && t.contains(*a);
                    let only_added = add && !del;
                    let only_deleted = del && !add;
                    !(only_added && lost || only_deleted && gained)
                });
                if ok {
                    out.insert(((*t).clone(), b.clone()));
                }
            }
        }
        out.into_iter().collect()
    }

    fn run(&mut self, steps: &[Step], mut configs: Vec<Config>) -> Vec<Config> {
        for s in steps {
            configs = self.step(s, configs);
            if !self.volatile.is_empty() {
                configs = self.havoc(configs, &self.volatile.clone());
            }
            configs.sort();
            configs.dedup();
        }
        configs
    }

    fn with_answers(&self, f: &Formula, configs: Vec<Config>) -> Vec<Config> {
        configs
            .into_iter()
            .flat_map(|(s, b)| {
                self.ev
                    .answers(f, &s, &b)
                    .into_iter()
                    .map(move |b2| (s.clone(), b2))
            })
            .collect()
    }

    fn step(&mut self, st: &Step, configs: Vec<Config>) -> Vec<Config> {
        match &st.kind {
            BodyStep::Action(t) => self.action(t, st.span, configs),
            BodyStep::Internal(t) => match t.functor() {
                Some(".count") => self.with_answers(&Formula::Call(t.clone()), configs),
                _ => configs,
            },
            BodyStep::Library { .. } => configs,
            BodyStep::Achieve { goal, new_focus } => {
                let eff = self
                    .sum
                    .goal(goal.functor().unwrap(), goal.arity())
                    .cloned()
                    .unwrap_or_default();
                if *new_focus {
                    self.volatile.absorb(&eff);
                }
                self.havoc(configs, &eff)
            }
            // Other intentions run meanwhile, as between any two steps.
            BodyStep::Wait { .. } => configs,
            BodyStep::Test(f) => self.with_answers(f, configs),
            BodyStep::Constraint(op, a, b) => {
                self.with_answers(&Formula::Rel(*op, a.clone(), b.clone()), configs)
            }
            BodyStep::AddBel(t) | BodyStep::DelBel(t) | BodyStep::DelAddBel(t) => {
                let mut out = Vec::new();
                for (s, b) in configs {
                    let wild = t.args().iter().any(|a| self.ev.val(a, &b).is_none());
                    let bound: Term = t.map_vars(&mut |v| match b.get(v) {
                        Some(V::Obj(o)) => Term::atom(self.p.universe.object_name(*o)),
                        _ => Term::Var(v.clone()),
                    });
                    let targets: Vec<AtomId> = if wild {
                        matching_atoms(self.p, &bound)
                    } else {
                        matching_atoms(self.p, &bound)
                            .into_iter()
                            .filter(|a| self.ev.match_atom(&bound, *a, &B::new()).is_some())
                            .collect()
                    };
                    let mut starts = vec![(s.clone(), b.clone())];
                    if let BodyStep::DelAddBel(_) = st.kind {
                        let eff = Effects {
                            add: BTreeSet::new(),
                            del: same_predicate_atoms(self.p, t).into_iter().collect(),
                        };
                        starts = self.havoc_any(starts, &eff);
                    }
                    for (s, b) in starts {
                        match (&st.kind, wild) {
                            (BodyStep::DelBel(_), false) => {
                                let mut n = s.clone();
                                targets.iter().for_each(|a| n.remove(*a));
                                out.push((n, b));
                            }
                            (BodyStep::DelBel(_), true) => {
                                let eff = Effects {
                                    add: BTreeSet::new(),
                                    del: targets.iter().copied().collect(),
                                };
                                out.extend(self.havoc_any(vec![(s, b)], &eff));
                            }
                            (_, false) => {
                                let mut n = s.clone();
                                targets.iter().for_each(|a| n.insert(*a));
                                out.push((n, b));
                            }
                            (_, true) => {
                                let eff = Effects {
                                    add: targets.iter().copied().collect(),
                                    del: BTreeSet::new(),
                                };
                                out.extend(self.havoc_any(vec![(s, b)], &eff));
                            }
                        }
                    }
                }
                out.retain(|(s, _)| self.inv(s));
                out
            }
            BodyStep::If {
                branches,
                else_body,
            } => {
                let before: BTreeSet<Var> = configs
                    .iter()
                    .flat_map(|(_, b)| b.keys().cloned())
                    .collect();
                let mut per: Vec<Vec<Config>> = vec![Vec::new(); branches.len() + 1];
                for (s, b) in configs {
                    let mut taken = false;
                    for (k, (c, _)) in branches.iter().enumerate() {
                        let ans = self.ev.answers(c, &s, &b);
                        if !ans.is_empty() {
                            per[k].extend(ans.into_iter().map(|b2| (s.clone(), b2)));
                            taken = true;
                            break;
                        }
                    }
                    if !taken {
                        per[branches.len()].push((s, b));
                    }
                }
                let mut out = Vec::new();
                for (k, cs) in per.into_iter().enumerate() {
                    let body = if k < branches.len() {
                        &branches[k].1
                    } else {
                        else_body
                    };
                    out.extend(self.run(body, cs));
                }
                // Bindings made in a branch do not outlive it (as in lint).
                for (_, b) in &mut out {
                    b.retain(|v, _| before.contains(v));
                }
                out
            }
            BodyStep::While(c, body) | BodyStep::For(c, body) => {
                let mut eff = self.sum.steps(self.p, body);
                eff.absorb(&self.volatile.clone());
                let heads = self.havoc(configs.clone(), &eff);
                let inside = self.with_answers(c, heads);
                self.run(body, inside);
                let after = self.havoc(configs, &eff);
                if let BodyStep::While(..) = st.kind {
                    after
                        .into_iter()
                        .filter(|(s, b)| self.ev.answers(c, s, b).is_empty())
                        .collect()
                } else {
                    after
                }
            }
        }
    }

    /// `havoc` without the invariant filter (the caller filters after the whole step).
    fn havoc_any(&self, configs: Vec<Config>, eff: &Effects) -> Vec<Config> {
        let touched: Vec<AtomId> = eff.touched().into_iter().collect();
        let mut out = Vec::new();
        for (s, b) in configs {
            for bits in 0u64..(1 << touched.len()) {
                let mut t = s.clone();
                let mut ok = true;
                for (i, a) in touched.iter().enumerate() {
                    let v = bits >> i & 1 == 1;
                    let (add, del) = (eff.add.contains(a), eff.del.contains(a));
                    if (add && !del && s.contains(*a) && !v)
                        || (del && !add && !s.contains(*a) && v)
                    {
                        ok = false;
                    }
                    t.set(*a, v);
                }
                if ok {
                    out.push((t, b.clone()));
                }
            }
        }
        out
    }

    fn action(&mut self, t: &Term, span: Span, configs: Vec<Config>) -> Vec<Config> {
        let name = t.functor().unwrap();
        let params = match self.p.vocabulary.action(name) {
            Some((_, a)) if a.params.len() == t.arity() => a.params.clone(),
            _ => return configs,
        };
        let key = self.loc(span);
        let mut out = Vec::new();
        for (s, b) in configs {
            let mut choices: Vec<(B, Vec<ObjectId>)> = vec![(b.clone(), Vec::new())];
            for (i, a) in t.args().iter().enumerate() {
                let mut next = Vec::new();
                for (bb, objs) in choices {
                    match (a, self.ev.val(a, &bb)) {
                        (_, Some(V::Obj(o))) => next.push((bb, [objs, vec![o]].concat())),
                        (_, Some(_)) => next.push((bb, [objs, vec![ObjectId(u16::MAX)]].concat())),
                        (Term::Var(v), None) => {
                            for o in self.p.universe.objects_of(params[i]) {
                                let mut b2 = bb.clone();
                                if !v.is_anonymous() {
                                    b2.insert(v.clone(), V::Obj(*o));
                                }
                                next.push((b2, [objs.clone(), vec![*o]].concat()));
                            }
                        }
                        _ => panic!("action argument {a}"),
                    }
                }
                choices = next;
            }
            for (b2, objs) in choices {
                match self.p.actions.get(name, &objs) {
                    Some(g) if g.applicable(&s) => {
                        let n = g.apply(&s);
                        if self.inv(&n) {
                            out.push((n, b2));
                        }
                    }
                    _ => {
                        self.steps.insert(key.clone());
                    }
                }
            }
        }
        out
    }

    fn truth_of(&mut self) -> Truth {
        let p = self.p;
        let mut failing: Vec<(String, String)> = Vec::new();
        let mut witnesses: BTreeMap<(String, String), Vec<BTreeSet<AtomSet>>> = BTreeMap::new();
        let mut fail = |check: &str, at: String, w: BTreeSet<AtomSet>| {
            failing.push((check.to_string(), at.clone()));
            witnesses
                .entry((check.to_string(), at))
                .or_default()
                .push(w);
        };
        // Groups of plans, as lint forms them.
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (i, plan) in p.plans.plans.iter().enumerate() {
            let t = &plan.trigger;
            let same = |j: &usize| {
                let u = &p.plans.plans[*j].trigger;
                u.op == t.op
                    && u.kind == t.kind
                    && u.literal.functor() == t.literal.functor()
                    && u.literal.arity() == t.literal.arity()
            };
            match groups.iter_mut().find(|g| same(&g[0])) {
                Some(g) => g.push(i),
                None => groups.push(vec![i]),
            }
        }
        let mut alive_plans = Vec::new();
        let mut pre_plans = BTreeMap::new();
        for g in &groups {
            let events = self.events(&p.plans.plans[g[0]]);
            // app[k][(state, event)]: plan g[k] applicable.
            let app: Vec<Vec<bool>> = g
                .iter()
                .map(|&i| {
                    let plan = &p.plans.plans[i];
                    self.states
                        .iter()
                        .flat_map(|s| events.iter().map(move |e| (s, e)))
                        .map(|(s, e)| !self.applicable(plan, e, s).is_empty())
                        .collect()
                })
                .collect();
            let n = self.states.len() * events.len();
            let state_of = |x: usize| self.states[x / events.len().max(1)].clone();
            let dead: Vec<bool> = app.iter().map(|a| !a.iter().any(|&x| x)).collect();
            let mut shadowed = vec![false; g.len()];
            for (k, &i) in g.iter().enumerate() {
                let at = self.loc(p.plans.plans[i].span);
                if dead[k] {
                    fail("dead-plan", at, BTreeSet::new());
                    continue;
                }
                alive_plans.push(i);
                let earlier: Vec<usize> = (0..k).filter(|&e| !dead[e]).collect();
                if p.manifest.bounds.plan_selection == PlanSelection::First
                    && !earlier.is_empty()
                    && (0..n).all(|x| !app[k][x] || earlier.iter().any(|&e| app[e][x]))
                {
                    shadowed[k] = true;
                    let w = (0..n).filter(|&x| app[k][x]).map(state_of).collect();
                    fail("shadowed-plan", at, w);
                }
            }
            for a in 0..g.len() {
                for c in a + 1..g.len() {
                    if dead[a] || dead[c] || shadowed[c] {
                        continue;
                    }
                    let w: BTreeSet<AtomSet> = (0..n)
                        .filter(|&x| app[a][x] && app[c][x])
                        .map(state_of)
                        .collect();
                    if !w.is_empty() {
                        fail("plan-overlap", self.loc(p.plans.plans[g[c]].span), w);
                    }
                }
            }
            let t = &p.plans.plans[g[0]].trigger;
            if t.op == TriggerOp::Add && t.kind == TriggerKind::Achieve {
                let w: BTreeSet<AtomSet> = (0..n)
                    .filter(|&x| (0..g.len()).all(|k| !app[k][x]))
                    .map(state_of)
                    .collect();
                if !w.is_empty() {
                    fail("coverage-gap", self.loc(p.plans.plans[g[0]].span), w);
                }
            }
        }
        // Preconditions along every live plan's body (the states that show a failure are
        // found by running again from one start state: see `precondition_fails`).
        for i in alive_plans {
            for at in self.failing_steps(i, None) {
                fail("precondition", at.clone(), BTreeSet::new());
                pre_plans.insert(at, i);
            }
        }
        // Actions.
        for (schema, decl) in p.domain.actions.iter().enumerate() {
            let at = self.loc(p.vocabulary.action(&decl.name).unwrap().1.span);
            let mut conflict = BTreeSet::new();
            // The states from which some instance breaks the first invariant broken at all
            // (lint shows the state of the first broken invariant).
            let mut breaks = BTreeSet::new();
            for (_, inv) in &p.invariants {
                for g in p.actions.all().iter().filter(|g| g.schema == schema) {
                    for s in self.states.iter().filter(|s| g.applicable(s)) {
                        if !inv.eval(&g.apply(s)) {
                            breaks.insert(s.clone());
                        }
                    }
                }
                if !breaks.is_empty() {
                    break;
                }
            }
            for g in p.actions.all().iter().filter(|g| g.schema == schema) {
                for s in self.states.iter().filter(|s| g.applicable(s)) {
                    let fired: Vec<_> = g.effects.iter().filter(|e| e.when.eval(s)).collect();
                    if fired.iter().any(|e1| {
                        e1.add
                            .iter()
                            .any(|a| fired.iter().any(|e2| e2.del.contains(a)))
                    }) {
                        conflict.insert(s.clone());
                    }
                }
            }
            if !conflict.is_empty() {
                fail("effect-conflict", at.clone(), conflict);
            }
            if !breaks.is_empty() {
                fail("action-breaks-invariant", at, breaks);
            }
        }
        failing.sort();
        Truth {
            failing,
            witnesses,
            pre_plans,
        }
    }

    /// The action steps of plan `i` whose precondition may fail, starting from every state
    /// (or only from those in `from`).
    fn failing_steps(&mut self, i: usize, from: Option<&HashSet<AtomSet>>) -> BTreeSet<String> {
        let plan = &self.p.plans.plans[i];
        self.volatile = Effects::default();
        self.steps.clear();
        let mut start = Vec::new();
        for s in &self.states {
            if from.is_some_and(|f| !f.contains(s)) {
                continue;
            }
            for e in self.events(plan) {
                for b in self.applicable(plan, &e, s) {
                    start.push((s.clone(), b));
                }
            }
        }
        self.run(&plan.body, start);
        std::mem::take(&mut self.steps)
    }
}

/// Parses a counterexample's atoms back into a state.
fn state_of(p: &Project, atoms: &[String]) -> AtomSet {
    let names: HashMap<String, AtomId> = (0..p.atoms.len() as u32)
        .map(|a| (p.atoms.display(AtomId(a), &p.universe), AtomId(a)))
        .collect();
    let mut s = AtomSet::empty(p.atoms.len());
    for a in atoms {
        s.insert(
            *names
                .get(a)
                .unwrap_or_else(|| panic!("`{a}` is not an atom")),
        );
    }
    s
}

const STATE_CHECKS: &[&str] = &[
    "dead-plan",
    "shadowed-plan",
    "coverage-gap",
    "plan-overlap",
    "precondition",
    "effect-conflict",
    "action-breaks-invariant",
];

fn differential(path: &str) {
    let p = project(path);
    let fs = run_lint(&p);
    assert!(
        fs.iter().all(|f| f.finding.status != Status::Unknown),
        "{path}: undecided findings"
    );
    let mut got: Vec<(String, String)> = fs
        .iter()
        .filter(|f| {
            f.finding.status == Status::Fail && STATE_CHECKS.contains(&f.finding.check.as_str())
        })
        .map(|f| {
            (
                f.finding.check.clone(),
                f.finding.location.as_ref().unwrap().to_string(),
            )
        })
        .collect();
    got.sort();
    let mut world = World::new(&p);
    let truth = world.truth_of();
    assert_eq!(
        got, truth.failing,
        "{path}: lint (left) and brute force (right) disagree"
    );
    // Every state lint shows is one brute force finds for that finding, and an initial state
    // whenever one exists.
    let initial: HashSet<AtomSet> = p.initial.states().iter().cloned().collect();
    for f in fs.iter().filter(|f| f.finding.status == Status::Fail) {
        let at = f.finding.location.as_ref().unwrap().to_string();
        let key = (f.finding.check.clone(), at.clone());
        let Some(ws) = truth.witnesses.get(&key) else {
            continue;
        };
        let Some(cx) = &f.finding.counterexample else {
            assert_eq!(f.finding.check, "dead-plan", "{path}: {f:#?}");
            continue;
        };
        let s = state_of(&p, &cx.initial);
        if f.finding.check == "precondition" {
            let plan = truth.pre_plans[&at];
            let only: HashSet<AtomSet> = [s.clone()].into_iter().collect();
            assert!(
                world.failing_steps(plan, Some(&only)).contains(&at),
                "{path}: {} shows a state from which brute force finds no failure: {:?}",
                f.finding.id,
                cx.initial
            );
            let from_initial = world.failing_steps(plan, Some(&initial)).contains(&at);
            assert_eq!(
                initial.contains(&s),
                from_initial,
                "{path}: {} should prefer an initial state",
                f.finding.id
            );
            continue;
        }
        assert!(
            ws.iter().any(|w| w.contains(&s)),
            "{path}: {} shows a state brute force does not: {:?}",
            f.finding.id,
            cx.initial
        );
        let some_initial = ws.iter().any(|w| w.iter().any(|x| initial.contains(x)));
        assert_eq!(
            initial.contains(&s),
            some_initial,
            "{path}: {} should prefer an initial state",
            f.finding.id
        );
    }
}

#[test]
fn lint_agrees_with_brute_force_on_the_paper() {
    differential("specs/paper");
}

#[test]
fn lint_agrees_with_brute_force_on_the_kitchen_with_one_cup() {
    differential("tests/lint/kitchen_one_cup");
}

#[test]
fn lint_agrees_with_brute_force_on_the_kitchen_with_two_cups() {
    differential("specs/kitchen");
}

#[test]
fn lint_agrees_with_brute_force_on_every_construct() {
    differential("tests/lint/constructs");
}

#[test]
fn lint_agrees_with_brute_force_on_subgoals_scopes_and_rules() {
    differential("tests/lint/subgoals");
}

#[test]
fn lint_agrees_with_brute_force_on_the_seeded_defects() {
    for (case, _, _) in SEEDED {
        differential(&format!("tests/lint/{case}"));
    }
    differential("tests/lint/shadowed_by_chosen");
}

#[test]
fn more_atoms_than_lint_encodes_leave_the_solver_checks_undecided() {
    let p = project("tests/lint/too_many_atoms");
    assert!(p.atoms.len() > bdi_check::smt::MAX_LINT_ATOMS);
    let fs = run_lint(&p);
    let wrong: Vec<_> = failing(&fs)
        .into_iter()
        .filter(|f| f.finding.severity != Severity::Note)
        .collect();
    assert!(wrong.is_empty(), "{wrong:#?}");
    let undecided: BTreeSet<&str> = fs
        .iter()
        .filter(|f| f.finding.status == Status::Unknown)
        .map(|f| f.finding.check.as_str())
        .collect();
    for check in [
        "dead-plan",
        "coverage-gap",
        "precondition",
        "effect-conflict",
    ] {
        assert!(
            undecided.contains(check),
            "{check} not undecided: {undecided:?}"
        );
    }
    // The name checks need no solver and still run.
    assert!(fs.iter().any(|f| f.finding.check == "unused-action"));
}
