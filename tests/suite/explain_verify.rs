//! The explanation properties of SPEC §4 in `verify`: they hold on the kitchen for both
//! users, each seeded defect is found at its place with a run that shows the explanation
//! given and replays, and the paper's syntactic test misleads where the semantic one does
//! not.

use std::path::PathBuf;

use crate::common;
use common::{agent_steps, bdi_check, replay_finding, steps, verify_json};

const CHECKS: [&str; 5] = [
    "demand-exact",
    "demand-adoption",
    "content-covers",
    "content-concise",
    "content-truthful",
];

/// `verify --format json` on a project: the exit code, the report and its file.
fn verify(project: &str) -> (i32, serde_json::Value, PathBuf) {
    verify_json(
        project,
        &format!("explain-{}", project.replace(['/', '.'], "_")),
    )
}

fn explanation_findings(r: &serde_json::Value) -> Vec<&serde_json::Value> {
    r["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| {
            CHECKS.contains(&f["check"].as_str().unwrap())
                || f["check"].as_str().unwrap().ends_with("-conformance")
        })
        .collect()
}

fn failures(r: &serde_json::Value) -> Vec<(&str, &serde_json::Value)> {
    explanation_findings(r)
        .into_iter()
        .filter(|f| f["status"] == "fail")
        .map(|f| (f["check"].as_str().unwrap(), f))
        .collect()
}

#[test]
fn every_explanation_property_holds_on_the_kitchen_for_both_users() {
    let (code, r, _) = verify("specs/kitchen");
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["stats"]["complete"], true);
    let found = explanation_findings(&r);
    for user in ["newcomer", "owner"] {
        for check in CHECKS {
            let id = format!("{check}:{user}");
            let f = found
                .iter()
                .find(|f| f["id"] == id.as_str())
                .unwrap_or_else(|| panic!("no finding {id}: {found:#?}"));
            assert_eq!(f["status"], "pass", "{f:#}");
            // The search really gave explanations to check.
            let msg = f["message"].as_str().unwrap();
            assert!(msg.contains("holds on every run"), "{msg}");
            assert!(!msg.contains(" 0 explanations"), "{msg}");
        }
    }
    // No agent-side explanations: no conformance checks.
    assert!(!found.iter().any(|f| f["check"] == "demand-conformance"));
}

#[test]
fn the_papers_algorithm_at_adoption_misses_the_action_after_a_subgoal() {
    // storeUsedCup's body runs openDishwasherIfNeed's actions before navigateTo(table):
    // adopting it, the paper's Algorithm 1 pairs navigateTo(table) with the request, which
    // the owner expects, but the owner sees it after openDoor(dishwasher).
    let (code, r, file) = verify("specs/paper");
    assert_eq!(code, 1);
    let fails = failures(&r);
    let (_, f) = fails
        .iter()
        .find(|(c, _)| *c == "demand-adoption")
        .expect("demand-adoption fails");
    assert_eq!(f["id"], "demand-adoption:owner:specs/paper/paper.asl:13");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("navigateTo(table) after openDoor(dishwasher)"),
        "{msg}"
    );
    assert!(msg.contains("did not mark"), "{msg}");
    let s = steps(f);
    // The run shows the explanations the owner got, the last one for the action at fault.
    let last_two = &s[s.len() - 2..];
    assert!(
        last_two[0].starts_with("explanation to owner: I go to the table"),
        "{s:#?}"
    );
    assert_eq!(last_two[1], "action navigateTo(table)");
    assert!(s
        .iter()
        .any(|t| t.starts_with("explanation to owner: I go to the dishwasher")));
    assert_eq!(replay_finding(&file, f["id"].as_str().unwrap()).0, 1);
    // The paper's content for navigateTo(dishwasher) covers the action that opens the door.
    assert!(
        !fails.iter().any(|(c, _)| c.starts_with("content")),
        "{fails:#?}"
    );
}

#[test]
fn a_context_the_plan_falsifies_is_an_untruthful_explanation() {
    let (code, r, file) = verify("tests/verify/explain_untruthful");
    assert_eq!(code, 1);
    let fails = failures(&r);
    assert_eq!(fails.len(), 1, "{fails:#?}");
    let (check, f) = fails[0];
    assert_eq!(check, "content-truthful");
    assert_eq!(
        f["id"],
        "content-truthful:newcomer:tests/verify/explain_untruthful/agent.asl:6"
    );
    let msg = f["message"].as_str().unwrap();
    assert!(msg.contains("robotAt(cupboard) is not believed"), "{msg}");
    let s = steps(f);
    assert_eq!(s.last().unwrap(), "action wipe(table)");
    assert!(
        s[s.len() - 2].starts_with("explanation to newcomer: "),
        "{s:#?}"
    );
    assert_eq!(replay_finding(&file, f["id"].as_str().unwrap()).0, 1);
}

#[test]
fn a_change_inside_a_subgoal_ends_the_content_there() {
    let (code, r, file) = verify("tests/verify/explain_verbose");
    assert_eq!(code, 1);
    let fails = failures(&r);
    let (_, f) = fails
        .iter()
        .find(|(c, _)| *c == "content-concise")
        .expect("content-concise fails");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains(
            "given: (navigateTo(table), !wipeIt, navigateTo(cupboard)); demanded: up to !wipeIt"
        ),
        "{msg}"
    );
    assert!(!fails.iter().any(|(c, _)| *c == "content-covers"));
    assert_eq!(replay_finding(&file, f["id"].as_str().unwrap()).0, 1);
}

#[test]
fn the_syntactic_test_misleads_where_the_semantic_one_does_not() {
    let (code, r, file) = verify("specs/misleading-content");
    assert_eq!(code, 1);
    let fails = failures(&r);
    assert_eq!(fails.len(), 1, "{fails:#?}");
    let (check, f) = fails[0];
    assert_eq!(check, "content-covers");
    let msg = f["message"].as_str().unwrap();
    assert!(msg.contains("ends at navigateTo(table)"), "{msg}");
    assert!(
        msg.contains("the context first changes at wipe(table)"),
        "{msg}"
    );
    assert_eq!(replay_finding(&file, f["id"].as_str().unwrap()).0, 1);

    let (code, r, _) = verify("specs/misleading-content/semantic.toml");
    assert_eq!(code, 0, "{r:#}");
    assert!(failures(&r).is_empty());
    assert_eq!(
        explanation_findings(&r)
            .iter()
            .filter(|f| f["status"] == "pass")
            .count(),
        CHECKS.len()
    );
}

/// A copy of specs/kitchen-explaining with `edit` applied to its agent.
fn kitchen_explaining_with(tag: &str, edit: impl Fn(&str) -> String) -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = common::temp_dir(&format!("kitchen-explaining-{tag}"));
    let src = root.join("specs/kitchen-explaining");
    let asl = std::fs::read_to_string(src.join("kitchen.asl")).unwrap();
    let edited = edit(&asl);
    assert_ne!(edited, asl, "the edit changes the agent");
    std::fs::write(dir.join("kitchen.asl"), edited).unwrap();
    let pddl = root.join("specs/kitchen/kitchen.pddl");
    let manifest = std::fs::read_to_string(src.join("bdi-check.toml"))
        .unwrap()
        .replace("../kitchen/kitchen.pddl", pddl.to_str().unwrap());
    std::fs::write(dir.join("bdi-check.toml"), manifest).unwrap();
    dir.to_str().unwrap().to_string()
}

#[test]
fn the_agents_own_explanations_conform_to_the_reference() {
    let (code, r, _) = verify("specs/kitchen-explaining");
    assert_eq!(code, 0, "{r:#}");
    let found = explanation_findings(&r);
    for check in CHECKS
        .iter()
        .chain(&["demand-conformance", "content-conformance"])
    {
        let id = format!("{check}:owner");
        let f = found
            .iter()
            .find(|f| f["id"] == id.as_str())
            .unwrap_or_else(|| panic!("no finding {id}"));
        assert_eq!(f["status"], "pass", "{f:#}");
    }
}

#[test]
fn an_explanation_the_agent_leaves_out_or_gets_wrong_is_found() {
    // Going to the dishwasher to open it, which surprises the owner, is not explained:
    // demand-conformance.
    let open = "explain(navigateTo(dishwasher), [neg(dishwasherDoor(open)), holding(none) | Ctx], [navigateTo(dishwasher), openDoor(dishwasher)]);";
    let silent = kitchen_explaining_with("silent", |a| a.replace(open, ".print(\"opening\");"));
    let (code, r, file) = verify(&silent);
    assert_eq!(code, 1);
    let fails = failures(&r);
    assert_eq!(fails.len(), 1, "{fails:#?}");
    let (check, f) = fails[0];
    assert_eq!(check, "demand-conformance");
    let msg = f["message"].as_str().unwrap();
    assert!(msg.contains("navigateTo(dishwasher) after !"), "{msg}");
    assert!(
        msg.contains("is surprising, but the agent gives no explanation"),
        "{msg}"
    );
    assert_eq!(replay_finding(&file, f["id"].as_str().unwrap()).0, 1);

    // It is explained without the closed door: content-conformance.
    let vague = kitchen_explaining_with("vague", |a| {
        a.replace(open, &open.replace("neg(dishwasherDoor(open)), ", ""))
    });
    let (code, r, _) = verify(&vague);
    assert_eq!(code, 1);
    let fails = failures(&r);
    assert_eq!(fails.len(), 1, "{fails:#?}");
    let (check, f) = fails[0];
    assert_eq!(check, "content-conformance");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("explain(navigateTo(dishwasher),[holding(none),"),
        "{msg}"
    );
    assert!(msg.contains("not dishwasherDoor(open)"), "{msg}");
}

#[test]
fn the_agent_written_mechanism_says_what_the_kitchen_says() {
    // specs/kitchen-explaining is specs/kitchen with the mechanism in the agent: the owner's
    // catalogue (every explanation some run gives) is the same in both, text aside.
    let catalogue = |project: &str| {
        let o = bdi_check(&["explain", project, "--user", "owner", "--format", "json"]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let mut entries: Vec<String> = r["explanations"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| {
                format!(
                    "{} after {} | {} | {}",
                    e["action"], e["after"], e["context"], e["actions"]
                )
            })
            .collect();
        entries.sort();
        entries
    };
    let kitchen = catalogue("specs/kitchen");
    assert!(kitchen.len() > 10, "{kitchen:#?}");
    assert_eq!(kitchen, catalogue("specs/kitchen-explaining"));
}

#[test]
fn the_semantic_test_agrees_with_the_runs_on_the_kitchen() {
    // Algorithm 2 with `modifies = "semantic"` predicts, from the state, where the context
    // changes; content-covers and content-concise find it in the runs: on the kitchen,
    // whose bodies change their context only through actions, the two must agree.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = common::temp_dir("kitchen-semantic");
    for f in ["kitchen.asl", "kitchen.pddl"] {
        std::fs::copy(root.join("specs/kitchen").join(f), dir.join(f)).unwrap();
    }
    let manifest = std::fs::read_to_string(root.join("specs/kitchen/bdi-check.toml"))
        .unwrap()
        .replace(r#"modifies = "syntactic""#, r#"modifies = "semantic""#);
    assert!(manifest.contains(r#"modifies = "semantic""#));
    std::fs::write(dir.join("bdi-check.toml"), manifest).unwrap();
    let (code, r, _) = verify(dir.to_str().unwrap());
    assert_eq!(code, 0, "{r:#}");
    let passed: Vec<&str> = explanation_findings(&r)
        .iter()
        .filter(|f| f["status"] == "pass")
        .map(|f| f["id"].as_str().unwrap())
        .collect();
    for id in ["content-covers:owner", "content-concise:newcomer"] {
        assert!(passed.contains(&id), "{passed:?}");
    }
}

// ----- Several agents: the users watch one robot (`[explanation] robot`) ----------------

/// Two robots sharing the dishwasher, the fetcher explained to a newcomer and the owner.
const TWO: &str = "tests/verify/mas-explained";

/// A copy of a project of several agents (`base`: tests/verify/mas-explained or
/// specs/two-robots-explaining) with its fetcher edited (each `(old, new)` once) and its
/// manifest too; the files it shares with specs/two-robots are named absolutely.
fn two_robots_with(
    base: &str,
    tag: &str,
    fetcher: &[(&str, &str)],
    manifest: &[(&str, &str)],
) -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = common::temp_dir(&format!("two-robots-{tag}"));
    let src = root.join(base);
    let edit = |mut text: String, edits: &[(&str, &str)]| {
        for (old, new) in edits {
            assert!(text.contains(old), "{old}");
            text = text.replacen(old, new, 1);
        }
        text
    };
    let asl = std::fs::read_to_string(src.join("fetcher.asl")).unwrap();
    std::fs::write(dir.join("fetcher.asl"), edit(asl, fetcher)).unwrap();
    let shared = format!("\"{}/", root.join("specs/two-robots").display());
    let toml = std::fs::read_to_string(src.join("bdi-check.toml"))
        .unwrap()
        .replace("\"../../../specs/two-robots/", &shared)
        .replace("\"../two-robots/", &shared);
    std::fs::write(dir.join("bdi-check.toml"), edit(toml, manifest)).unwrap();
    dir.to_str().unwrap().to_string()
}

/// The failing finding of `check` for `user` in the report of `project` (exit 1), whose
/// run names the agent of every step, gives the user an explanation, and replays.
fn failing(project: &str, check: &str, user: &str) -> serde_json::Value {
    let (code, r, file) = verify(project);
    assert_eq!(code, 1, "{r:#}");
    let f = failures(&r)
        .into_iter()
        .map(|(_, f)| f)
        .find(|f| f["check"] == check && f["id"].as_str().unwrap().contains(&format!(":{user}:")))
        .unwrap_or_else(|| panic!("no failing {check} for {user}: {:#?}", failures(&r)))
        .clone();
    let s = agent_steps(&f);
    assert!(
        s.iter()
            .all(|t| t.starts_with("fetcher ") || t.starts_with("loader ")),
        "{s:#?}"
    );
    assert_eq!(
        replay_finding(&file, f["id"].as_str().unwrap()).0,
        1,
        "{f:#}"
    );
    f
}

#[test]
fn every_explanation_property_holds_for_the_robot_the_users_watch_among_two() {
    let (code, r, _) = verify(TWO);
    assert_eq!(code, 0, "{r:#}");
    let found = explanation_findings(&r);
    for user in ["newcomer", "owner"] {
        for check in CHECKS {
            let id = format!("{check}:{user}");
            let f = found
                .iter()
                .find(|f| f["id"] == id.as_str())
                .unwrap_or_else(|| panic!("no finding {id}: {found:#?}"));
            assert_eq!(f["status"], "pass", "{f:#}");
            let msg = f["message"].as_str().unwrap();
            assert!(
                msg.starts_with(&format!("for {user}, watching fetcher: holds on every run")),
                "{msg}"
            );
            // The owner knows the fetcher's routine: nothing it does surprises them, and
            // they see none of the loader's actions, which would make novel pairs (and
            // pairs the paper's marking at the fetcher's plan adoption never marks).
            let none = msg.contains(" 0 explanations given");
            assert_eq!(none, user == "owner", "{msg}");
        }
    }
}

#[test]
fn a_user_sees_the_requests_to_the_robot_and_its_actions_and_nothing_of_the_others() {
    use bdi_check::check::explanation::{robot_of, Among, Explained};
    use bdi_check::check::explore::fingerprint;
    use bdi_check::check::model::Model;
    use bdi_check::explain::agent::{users, Explainer};
    use bdi_check::explain::Observation;
    use bdi_check::model::project::load_system;
    use bdi_check::semantics::{Note, System};
    // Watching the fetcher (which the requests go to), then the loader.
    let loader = two_robots_with(
        TWO,
        "watch-loader",
        &[],
        &[(r#"robot = "fetcher""#, r#"robot = "loader""#)],
    );
    for (dir, watched, other) in [(TWO, "fetcher", "loader"), (&loader, "loader", "fetcher")] {
        let projects = load_system(std::path::Path::new(dir)).unwrap();
        let system = System::new(&projects).unwrap();
        let robot = robot_of(&projects);
        assert_eq!(projects[robot].name, watched);
        let ex = Explainer::new(&projects[robot], &system.agents[robot]);
        // Every action of this domain names its robot first.
        let by_robot = |o: &Observation| match o {
            Observation::Action(t) => t.args()[0].to_string() == watched,
            Observation::Request(_) => watched == "fetcher",
        };
        for user in users(&projects[robot], None).unwrap() {
            let model = Explained::watching(
                Among {
                    system: &system,
                    robot,
                },
                &ex,
                &user,
            );
            let mut queue: Vec<_> = model.init_states().collect();
            let mut seen: std::collections::HashSet<u64> = queue.iter().map(fingerprint).collect();
            let (mut others_acted, mut explained) = (0, 0);
            while let Some(s) = queue.pop() {
                let n = model.expected(&s);
                for p in n.learned() {
                    assert!(p.prev.iter().chain([&p.next]).all(by_robot), "{p}");
                }
                if let Some(o) = model.last_observed(&s) {
                    assert!(by_robot(o), "{} saw {o}", user.name);
                }
                for (step, t) in model.next_states(&s) {
                    let name = &system.names()[step.agent as usize];
                    if name == other {
                        // Another agent's step changes nothing the user has seen.
                        assert!(step
                            .given
                            .iter()
                            .flat_map(|g| g.iter())
                            .all(Option::is_none));
                        assert_eq!(model.last_observed(&t), model.last_observed(&s));
                        assert_eq!(model.expected(&t).learned(), n.learned());
                        others_acted += step
                            .notes
                            .iter()
                            .filter(|n| matches!(n, Note::Action { .. }))
                            .count();
                    }
                    explained += step.given.iter().flat_map(|g| g.iter()).flatten().count();
                    if seen.insert(fingerprint(&t)) {
                        queue.push(t);
                    }
                }
            }
            // The other robot really acts in these runs, and the newcomer is surprised.
            assert!(others_acted > 0, "{watched}");
            assert_eq!(
                explained > 0,
                user.name == "newcomer" || watched == "loader"
            );
        }
    }
}

#[test]
fn the_papers_marking_at_adoption_misses_an_action_after_a_subgoal_among_two() {
    // The fetcher carries the cup itself after `!fetch`: adopting `clear`, the paper's
    // Algorithm 1 pairs move(fetcher, counter) with the request, but the owner sees it
    // after pick(fetcher, C), which they expect.
    let d = two_robots_with(
        TWO,
        "adoption",
        &[(
            "!fetch(C);\n      !bring(C);",
            "!fetch(C);\n      move(fetcher, counter);\n      put(fetcher, C);",
        )],
        &[],
    );
    let f = failing(&d, "demand-adoption", "owner");
    assert!(
        f["id"].as_str().unwrap().ends_with("fetcher.asl:9"),
        "{f:#}"
    );
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("for owner, watching fetcher: move(fetcher,counter) after pick(fetcher,cup1) is expected by the observed sequence, but Algorithm 1 at plan adoption marked it"),
        "{msg}"
    );
}

#[test]
fn a_context_the_robot_no_longer_believes_is_untruthful_once_it_perceives_it() {
    // `bring` asks that the fetcher be at the table, and its first action leaves it: the
    // fetcher perceives its move at the start of the cycle that puts the cup down, so when
    // put is explained (to the newcomer) `at(fetcher, table)` is no longer believed.
    let d = two_robots_with(
        TWO,
        "truthful",
        &[(
            "+!bring(C) : holding(fetcher, C)",
            "+!bring(C) : holding(fetcher, C) & at(fetcher, table)",
        )],
        &[],
    );
    let f = failing(&d, "content-truthful", "newcomer");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("the explanation of put(fetcher,cup1)"),
        "{msg}"
    );
    assert!(
        msg.contains("but at(fetcher,table) is not believed"),
        "{msg}"
    );
    let s = agent_steps(&f);
    assert_eq!(
        s.last().unwrap(),
        "fetcher action put(fetcher,cup1)",
        "{s:#?}"
    );
    assert!(
        s[s.len() - 2].starts_with("fetcher explanation to newcomer: I perform put(fetcher,cup1)")
    );
}

#[test]
fn the_syntactic_test_misleads_among_two_as_with_one() {
    // move(fetcher, table) may delete at(fetcher, dishwasher), so the paper's test ends
    // the content there; the context really changes at pick.
    let d = two_robots_with(
        TWO,
        "covers",
        &[(
            "+!fetch(C) : cupAt(C, table)",
            "+!fetch(C) : cupAt(C, table) & not at(fetcher, dishwasher)",
        )],
        &[],
    );
    let f = failing(&d, "content-covers", "newcomer");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains(
            "ends at move(fetcher,table), but the context first changes at pick(fetcher,cup1)"
        ),
        "{msg}"
    );
}

#[test]
fn a_change_inside_a_subgoal_ends_the_content_there_among_two() {
    let d = two_robots_with(
        TWO,
        "concise",
        &[
            (
                "pick(fetcher, C).",
                "!take(C);\n      move(fetcher, counter).\n\n+!take(C) <- pick(fetcher, C).",
            ),
            ("<- move(fetcher, counter);\n      put", "<- put"),
        ],
        &[],
    );
    let f = failing(&d, "content-concise", "newcomer");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("given: (move(fetcher,table), !take(cup1), move(fetcher,counter)); demanded: up to !take(cup1)"),
        "{msg}"
    );
}

#[test]
fn what_another_robot_changes_counts_where_the_watched_one_perceives_it() {
    // The fetcher's context asks for a closed dishwasher, which the loader opens to load
    // the first cup while the fetcher goes for the second: the context changes while
    // move(fetcher, table) runs, so the content that runs on to the pick says too much.
    let d = two_robots_with(
        TWO,
        "interference",
        &[(
            "+!fetch(C) : cupAt(C, table)",
            "+!fetch(C) : cupAt(C, table) & door(closed)",
        )],
        &[],
    );
    let f = failing(&d, "content-concise", "newcomer");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains(
            "runs on to pick(fetcher,cup2), but the context first changes at move(fetcher,table)"
        ),
        "{msg}"
    );
    // The loader opens the door after the explanation was given.
    let s = agent_steps(&f);
    let given = s
        .iter()
        .rposition(|t| {
            t.starts_with("fetcher explanation to newcomer: I perform move(fetcher,table)")
        })
        .expect("the explanation");
    assert!(
        s[given..].contains(&"loader action openDoor(loader)".to_string()),
        "{s:#?}"
    );
}

#[test]
fn the_fetchers_own_explanations_conform_on_every_interleaving() {
    let (code, r, _) = verify("specs/two-robots-explaining");
    assert_eq!(code, 0, "{r:#}");
    let found = explanation_findings(&r);
    for check in CHECKS
        .iter()
        .chain(&["demand-conformance", "content-conformance"])
    {
        let id = format!("{check}:owner");
        let f = found
            .iter()
            .find(|f| f["id"] == id.as_str())
            .unwrap_or_else(|| panic!("no finding {id}"));
        assert_eq!(f["status"], "pass", "{f:#}");
        assert!(!f["message"].as_str().unwrap().contains(" 0 explanations"));
    }
    // An explanation left out, then one without the fetcher's hands.
    let put = "explain(put(fetcher, C), [holding(fetcher, C) | Ctx], [put(fetcher, C)]);";
    let silent = two_robots_with(
        "specs/two-robots-explaining",
        "silent",
        &[(put, ".print(\"putting it down\");")],
        &[],
    );
    let f = failing(&silent, "demand-conformance", "owner");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("put(fetcher,cup1) after move(fetcher,counter) is surprising, but the agent gives no explanation"),
        "{msg}"
    );
    let vague = two_robots_with(
        "specs/two-robots-explaining",
        "vague",
        &[(
            "explain(move(fetcher, counter), [holding(fetcher, C) | Ctx],",
            "explain(move(fetcher, counter), Ctx,",
        )],
        &[],
    );
    let f = failing(&vague, "content-conformance", "owner");
    let msg = f["message"].as_str().unwrap();
    assert!(
        msg.contains("with explain(move(fetcher,counter),[neg(cupAt(cup1,counter))],"),
        "{msg}"
    );
    // Fixed, the report of the defect no longer replays.
    let (_, _, file) = verify(&vague);
    std::fs::copy(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("specs/two-robots-explaining/fetcher.asl"),
        std::path::Path::new(&vague).join("fetcher.asl"),
    )
    .unwrap();
    let o = bdi_check(&["replay", file.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}

#[test]
fn one_agent_gets_the_same_explanation_findings_compiled_and_through_the_interleavings() {
    // The checks on the compiled cycle give the reference cycle's findings, runs and all.
    // The checks of several agents, run on a project of one: the agent perceives its
    // actions' effects at its next sense there, not as it acts, and every finding (its
    // id, status, message and run) is the one the single-agent checks give.
    use bdi_check::check::explanation::{verify, verify_among};
    use bdi_check::check::explore::{Limits, Options};
    use bdi_check::model::project::load_system;
    use bdi_check::semantics::{Semantics, System};
    let limits = Limits {
        max_states: 2_000_000,
        max_depth: 10_000,
        timeout: None,
    };
    let opts = Options {
        threads: 2,
        keep_edges: false,
        ..Options::default()
    };
    let open = "explain(navigateTo(dishwasher), [neg(dishwasherDoor(open)), holding(none) | Ctx], [navigateTo(dishwasher), openDoor(dishwasher)]);";
    let silent =
        kitchen_explaining_with("same-silent", |a| a.replace(open, ".print(\"opening\");"));
    let vague = kitchen_explaining_with("same-vague", |a| {
        a.replace(open, &open.replace("neg(dishwasherDoor(open)), ", ""))
    });
    let (mut failed, mut passed) = (0, 0);
    for dir in [
        "specs/kitchen",
        "specs/paper",
        "specs/kitchen-explaining",
        "specs/misleading-content",
        "specs/misleading-content/semantic.toml",
        "tests/verify/explain_untruthful",
        "tests/verify/explain_verbose",
        "tests/verify/explain_shared_q",
        "tests/verify/explain_shared_not_q",
        &silent,
        &vague,
    ] {
        let projects = load_system(std::path::Path::new(dir)).unwrap();
        assert_eq!(projects.len(), 1, "{dir}");
        let sem = Semantics::new(&projects[0]).unwrap();
        let (alone, complete, _) = verify(
            &projects[0],
            &sem,
            (None, None),
            None,
            limits,
            &opts,
            &mut |_, _, _, _| {},
            &|| {},
        )
        .unwrap();
        // On the compiled cycle: the same findings, counterexamples and all.
        let compiled = bdi_check::semantics::Compiled::new(&sem);
        assert!(compiled.is_some(), "{dir}");
        let (fast, fast_complete, _) = verify(
            &projects[0],
            &sem,
            (compiled.as_ref(), None),
            None,
            limits,
            &opts,
            &mut |_, _, _, _| {},
            &|| {},
        )
        .unwrap();
        assert!(fast_complete, "{dir}");
        assert_eq!(fast, alone, "{dir}");
        let system = System::new(&projects).unwrap();
        let (among, among_complete, _) =
            verify_among(&projects, &system, limits, &opts, &mut |_, _, _, _| {}).unwrap();
        assert!(complete && among_complete, "{dir}");
        // A pass counts the states and explanations of its own search.
        let view = |f: &bdi_check::findings::Finding| match f.status {
            bdi_check::findings::Status::Fail => format!("{} fail: {}", f.id, f.message),
            status => format!("{} {status:?}", f.id),
        };
        let (alone_view, among_view): (Vec<String>, Vec<String>) = (
            alone.iter().map(view).collect(),
            among.iter().map(view).collect(),
        );
        assert_eq!(alone_view, among_view, "{dir}");
        // The same run, from the same state; through the interleavings it goes on to the
        // end of the cycle in which the agent perceives what shows the violation.
        for (a, b) in alone.iter().zip(&among) {
            let (Some(a), Some(b)) = (&a.counterexample, &b.counterexample) else {
                assert!(a.counterexample.is_none() && b.counterexample.is_none());
                continue;
            };
            let steps = |c: &bdi_check::findings::Counterexample| -> Vec<String> {
                c.steps
                    .iter()
                    .map(|s| format!("{:?} {}", s.kind, s.text))
                    .collect()
            };
            let (x, y) = (steps(a), steps(b));
            assert_eq!(a.initial, b.initial, "{dir}");
            assert!(y.starts_with(&x), "{dir}: {x:#?} {y:#?}");
        }
        assert!(!alone.is_empty(), "{dir}");
        for f in &alone {
            if f.status == bdi_check::findings::Status::Fail {
                failed += 1;
            } else {
                passed += 1;
            }
        }
    }
    assert!(
        failed >= 6 && passed > 40,
        "{failed} failed, {passed} passed"
    );
}

/// `verify` of a project that should be refused: its stdout and stderr.
fn refused(d: &str) -> String {
    let o = bdi_check(&["verify", d, "--color", "never"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

#[test]
fn the_robot_is_named_and_must_be_an_agent_of_the_project() {
    // Several agents: the manifest must say whom its users watch.
    let unnamed = two_robots_with(TWO, "unnamed", &[], &[("robot = \"fetcher\"\n", "")]);
    let out = refused(&unnamed);
    assert!(
        out.contains("`[explanation]` of a project of several agents must name the robot whose actions its users watch"),
        "{out}"
    );
    assert!(out.contains("bdi-check.toml:30:2"), "{out}");
    assert!(
        out.contains("add `robot = \"fetcher\"` (the agents are `fetcher`, `loader`)"),
        "{out}"
    );
    let unknown = two_robots_with(
        TWO,
        "unknown",
        &[],
        &[("robot = \"fetcher\"", "robot = \"waiter\"")],
    );
    let out = refused(&unknown);
    assert!(out.contains("no agent is named `waiter`"), "{out}");
    assert!(out.contains("bdi-check.toml:31:9"), "{out}");
    let bad = two_robots_with(
        TWO,
        "bad-name",
        &[],
        &[("robot = \"fetcher\"", "robot = \"Fetcher\"")],
    );
    assert!(refused(&bad).contains("`Fetcher` is not an agent name"));
    // One agent: `robot` may name it (the plans file's stem), and nothing else.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (robot, ok) in [("agent", true), ("robot", false)] {
        let dir = common::temp_dir(&format!("one-robot-{robot}"));
        let src = root.join("tests/verify/explain_untruthful");
        std::fs::copy(src.join("agent.asl"), dir.join("agent.asl")).unwrap();
        let pddl = root.join("specs/kitchen/kitchen.pddl");
        let toml = std::fs::read_to_string(src.join("bdi-check.toml"))
            .unwrap()
            .replace(
                "../../../specs/kitchen/kitchen.pddl",
                pddl.to_str().unwrap(),
            )
            .replace(
                "[explanation]\n",
                &format!("[explanation]\nrobot = \"{robot}\"\n"),
            );
        std::fs::write(dir.join("bdi-check.toml"), toml).unwrap();
        let d = dir.to_str().unwrap();
        if ok {
            // The same finding as without `robot`.
            let f = failing_one(d);
            assert!(f.ends_with("agent.asl:6"), "{f}");
        } else {
            let out = refused(d);
            assert!(out.contains("no agent is named `robot`"), "{out}");
            assert!(out.contains("the agents are `agent`"), "{out}");
        }
    }
}

/// The id of the one failing explanation finding of a project of one agent.
fn failing_one(d: &str) -> String {
    let (code, r, _) = verify(d);
    assert_eq!(code, 1, "{r:#}");
    let fails = failures(&r);
    assert_eq!(fails.len(), 1, "{fails:#?}");
    fails[0].1["id"].as_str().unwrap().to_string()
}

/// The users' searches judge whether an explanation's context changed through the atoms
/// each context atom unifies with (`Explainer::instances`, kept per atom); Algorithm 2
/// asks `Explainer::holds`, which unifies with every atom of the predicate. They agree on
/// every literal shape of the kitchen's predicates (ground, partly and wholly open) in
/// every state of its first steps.
#[test]
fn a_context_atom_holds_where_one_of_its_instances_is_believed() {
    use bdi_check::explain::agent::Explainer;
    use bdi_check::model::project::load_project;
    use bdi_check::model::{term_from_expr, Term};
    use bdi_check::semantics::Semantics;
    use bdi_check::syntax::{parser::parse_expr, FileId};
    let p = load_project(std::path::Path::new("specs/kitchen")).expect("the kitchen loads");
    let sem = Semantics::new(&p).expect("the semantics");
    let ex = Explainer::new(&p, &sem);
    let term = |s: &str| -> Term { term_from_expr(&parse_expr(FileId(0), s).unwrap()).unwrap() };
    let literals: Vec<Term> = [
        "cupAt(C, P)",
        "cupAt(cup1, P)",
        "cupAt(C, dishwasher)",
        "cupAt(cup2, cupboard)",
        "robotAt(X)",
        "robotAt(cupboard)",
        "holding(X)",
        "holding(none)",
        "dishwasherDoor(open)",
        "dishwasherDoor(S)",
        "used(C)",
        "~robotAt(X)",
        "nosuch(X)",
    ]
    .iter()
    .map(|s| term(s))
    .collect();
    let mut states = sem.initial_states();
    for _ in 0..3 {
        let next: Vec<_> = states
            .iter()
            .flat_map(|s| sem.successors(s))
            .map(|t| t.next)
            .collect();
        states.extend(next);
    }
    let mut held = 0;
    for s in &states {
        for l in &literals {
            let by_instances = ex.instances(l).iter().any(|&a| s.beliefs.contains(a));
            assert_eq!(ex.holds(&s.beliefs, l), by_instances, "{l}");
            held += usize::from(by_instances);
        }
    }
    assert!(held > 0 && held < states.len() * literals.len());
}
