//! No hostile input brings bdi-check down (issue 18): each project here ends with an exit
//! code of 0 to 3 under a limit on its address space (`ulimit -v`, which is setrlimit's
//! RLIMIT_AS, in the shell that starts it) and the tool's own bounds, never by a signal.
//! The limit is far below what these inputs took before the tool bounded them (20 GB for
//! the 28-object `vary`), and far above what a bounded run needs.

use crate::common;

use common::temp_dir;
use std::process::Command;

/// 4 GiB of address space, in KiB.
const LIMIT_KIB: u64 = 4 << 20;

/// Runs bdi-check with `args` under the limit: its exit code (`None`: ended by a signal)
/// and what it printed.
fn limited(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {LIMIT_KIB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_bdi-check"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("sh runs");
    let mut said = String::from_utf8_lossy(&out.stdout).into_owned();
    said.push_str(&String::from_utf8_lossy(&out.stderr));
    (out.status.code(), said)
}

/// A project of `asl` over `objects` things, a predicate `r` of `arity` things that
/// `vary` names when `vary` is set, requesting `go`.
fn project(tag: &str, asl: &str, objects: usize, arity: usize, vary: bool) -> String {
    let d = temp_dir(&format!("resources-{tag}"));
    let params: Vec<String> = (0..arity).map(|i| format!("?x{i}")).collect();
    std::fs::write(
        d.join("domain.pddl"),
        format!(
            "(define (domain d) (:types thing)\n  (:predicates (r {} - thing))\n  \
             (:action act :parameters (?x - thing) :precondition (and) :effect (and)))\n",
            params.join(" ")
        ),
    )
    .unwrap();
    std::fs::write(d.join("agent.asl"), asl).unwrap();
    let things: Vec<String> = (0..objects).map(|i| format!("\"o{i}\"")).collect();
    std::fs::write(
        d.join("bdi-check.toml"),
        format!(
            "[agent]\nplans = \"agent.asl\"\nactions = \"domain.pddl\"\n\n\
             [objects]\nthing = [{}]\n\n[initial]\nvary = [{}]\n\n\
             [requests]\ngoals = [\"go\"]\nmax = 1\n",
            things.join(", "),
            if vary { "\"r\"" } else { "" }
        ),
    )
    .unwrap();
    d.to_str().expect("UTF-8").to_string()
}

/// Asserts that the run ended by itself with `want` (or any of 0 to 3) and says `says`.
fn ends(what: &str, (code, err): (Option<i32>, String), want: Option<i32>, says: &str) {
    let Some(code) = code else {
        panic!("{what}: ended by a signal\n{err}");
    };
    assert!(code <= 3, "{what}: exit {code}\n{err}");
    if let Some(w) = want {
        assert_eq!(code, w, "{what}\n{err}");
    }
    assert!(err.contains(says), "{what}: {err}");
}

#[test]
fn many_varying_atoms_are_searched_within_bounds() {
    // 40 objects and a 3-ary predicate: 64,000 varying atoms (once a stack overflow);
    // 28 objects: 21,952 (once 20 GB of memory before any answer). The initial states are
    // made as the search takes them, and the memory bound (within `ulimit -v`) stops it.
    for n in [40, 28] {
        let p = project(&format!("vary-{n}"), "+!go <- act(o1).\n", n, 3, true);
        ends(
            &format!("{n} objects"),
            limited(&["verify", &p]),
            Some(3),
            "the search is incomplete",
        );
    }
}

#[test]
fn a_long_library_is_parsed_and_verified_within_bounds() {
    // 20,000 plans in a chain of subgoals: `parse` reads them all; `verify` lints within
    // its time limit (the checks it could not begin say unknown) and searches a bounded
    // number of states.
    let n = 20_000;
    let mut asl: String = (0..n)
        .map(|i| format!("+!g{i} <- act(o1); !g{}.\n", i + 1))
        .collect();
    asl.push_str(&format!("+!g{n} <- act(o0).\n+!go <- !g0.\n"));
    let p = project("long-library", &asl, 2, 1, false);
    let manifest = format!("{p}/bdi-check.toml");
    ends(
        "parse",
        limited(&["parse", &manifest]),
        Some(0),
        "no errors",
    );
    let verify = limited(&["verify", &p, "--timeout", "5", "--max-states", "2000"]);
    ends("verify", verify, Some(3), "");
}

#[test]
fn hostile_agents_end_with_an_answer() {
    let deep = format!(
        "p({}a{}).\n+!go <- act(o1).\n",
        "(".repeat(100_000),
        ")".repeat(100_000)
    );
    let cases = [
        ("deep nesting", deep, Some(2)),
        (
            "overflowing arithmetic",
            "+!go : X = -9223372036854775807 - 1 & Y = X div -1 <- act(o1).\n".to_string(),
            None,
        ),
        (
            "an endless include",
            "{ include(\"/dev/zero\") }\n+!go <- act(o1).\n".to_string(),
            Some(2),
        ),
    ];
    for (what, asl, want) in cases {
        let p = project(&what.replace(' ', "-"), &asl, 2, 1, false);
        ends(what, limited(&["verify", &p]), want, "");
    }
}

#[test]
fn a_timeout_bounds_lint_too() {
    // `verify --timeout` covers its lint: with no time at all, no z3 check is begun and
    // each says why it is undecided; the verdict is incomplete, never a pass.
    let out = common::bdi_check(&[
        "verify",
        "specs/kitchen",
        "--timeout",
        "0",
        "--format",
        "json",
    ]);
    assert_eq!(out.status.code(), Some(3));
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(r["verdict"], "incomplete");
    let findings = r["findings"].as_array().expect("findings");
    let lint_unknown = findings.iter().filter(|f| {
        f["check"] == "dead-plan"
            && f["status"] == "unknown"
            && f["message"]
                .as_str()
                .is_some_and(|m| m.contains("the time limit (--timeout) ran out"))
    });
    assert!(lint_unknown.count() > 0, "{r}");
    assert!(findings.iter().all(|f| f["status"] != "fail"), "{r}");
}
