//! `--format sarif`: the report as SARIF 2.1.0, the format GitHub code scanning and most CI
//! dashboards load.
//!
//! Built with `serde_json` from the [`Report`] alone, so every command that makes a report can
//! write it and the output depends on nothing but the findings: no timings, no absolute
//! paths the report does not already hold. One result per failing or undecided finding;
//! passed checks are not results (SARIF has no "pass" result a dashboard would show).

use crate::findings::{Counterexample, Finding, Report, Status};
use crate::syntax::Severity;
use serde_json::{json, Value};
use std::collections::BTreeSet;

/// The `$schema` that SARIF 2.1.0 files name (the one GitHub's documentation uses).
pub const SCHEMA: &str = "https://json.schemastore.org/sarif-2.1.0.json";

/// The report of `command` (`lint` or `verify`) as a SARIF 2.1.0 log, pretty-printed, with
/// a trailing newline.
pub fn render(report: &Report, command: &str) -> String {
    serde_json::to_string_pretty(&log(report, command)).unwrap_or_default() + "\n"
}

/// The SARIF log as a JSON value.
pub fn log(report: &Report, command: &str) -> Value {
    // Rules: one per check name the report holds, sorted, so `ruleIndex` is stable.
    let checks: Vec<&str> = report
        .findings
        .iter()
        .map(|f| f.check.as_str())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let rules: Vec<Value> = checks
        .iter()
        .map(|c| {
            json!({
                "id": c,
                "name": c,
                "shortDescription": {"text": describe(c)},
            })
        })
        .collect();
    let results: Vec<Value> = report
        .findings
        .iter()
        .filter(|f| f.status != Status::Pass)
        .map(|f| {
            let index = checks.iter().position(|c| *c == f.check).unwrap_or(0);
            result(f, index, &report.project)
        })
        .collect();
    json!({
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": report.tool.name,
                "version": report.tool.version,
                "semanticVersion": report.tool.version,
                "rules": rules,
            }},
            // GitHub code scanning keys alerts by this category: one per command and project,
            // so several projects' logs can be uploaded side by side.
            "automationDetails": {"id": format!("bdi-check/{command}/{}/", report.project)},
            "invocations": [{
                "executionSuccessful": report.verdict != crate::findings::Verdict::Error,
                "exitCode": report.verdict.exit_code(),
                "toolExecutionNotifications": report
                    .warnings
                    .iter()
                    .map(|w| json!({"level": "warning", "message": {"text": w}}))
                    .collect::<Vec<_>>(),
            }],
            "properties": {"project": report.project, "verdict": report.verdict},
            "results": results,
        }],
    })
}

fn result(f: &Finding, rule_index: usize, project: &str) -> Value {
    let mut text = f.message.clone();
    if let Some(c) = &f.counterexample {
        text.push_str(&state_text(c));
    }
    let (file, line, column) = match &f.location {
        Some(l) => (l.file.clone(), l.line.max(1), l.column.max(1)),
        // SARIF consumers (GitHub) need a location: a finding about no place is about the
        // project, whose manifest is the place a user fixes it.
        None => (manifest_of(project), 1, 1),
    };
    let mut r = json!({
        "ruleId": f.check,
        "ruleIndex": rule_index,
        "message": {"text": text},
        "locations": [{"physicalLocation": {
            "artifactLocation": {"uri": uri(&file)},
            "region": {"startLine": line, "startColumn": column},
        }}],
        "partialFingerprints": {"bdiCheckFindingId/v1": f.id},
    });
    if f.status == Status::Unknown {
        // SARIF §3.27.9-10: an undecided check is `kind: open`, whose level must be `none`.
        r["kind"] = json!("open");
        r["level"] = json!("none");
    } else if f.severity == Severity::Note {
        // A note fails nothing (a warning no run reaches, an unused action): informational,
        // so that code scanning opens no alert on a correct library.
        r["kind"] = json!("informational");
        r["level"] = json!("none");
    } else {
        r["kind"] = json!("fail");
        r["level"] = json!(level(f.severity));
    }
    if let Some(why) = &f.suppressed {
        // SARIF §3.35: accepted on purpose in the manifest, a file apart from the source.
        r["suppressions"] =
            json!([{"kind": "external", "status": "accepted", "justification": why}]);
    }
    if let Some(c) = f.counterexample.as_ref().filter(|c| !c.steps.is_empty()) {
        r["codeFlows"] = json!([code_flow(c)]);
    }
    r
}

fn level(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

/// The start of a counterexample, which the code flow's steps do not show.
fn state_text(c: &Counterexample) -> String {
    let mut out = format!("\ninitially: {}", c.initial.join(", "));
    if !c.requests.is_empty() {
        out.push_str(&format!("\nrequests: {}", c.requests.join(", ")));
    }
    out
}

/// The counterexample's steps as one thread flow, each at its plan's `file:line` when known.
fn code_flow(c: &Counterexample) -> Value {
    let locations: Vec<Value> = c
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let mut text = s.text.clone();
            if c.loop_start == Some(i) {
                text.push_str(" (from here the run repeats forever)");
            }
            let mut location = json!({"message": {"text": text}});
            if let Some((file, line)) = s.plan.as_deref().and_then(split_plan) {
                location["physicalLocation"] = json!({
                    "artifactLocation": {"uri": uri(file)},
                    "region": {"startLine": line},
                });
            }
            json!({
                "location": location,
                "kinds": [s.kind.name()],
                "executionOrder": i + 1,
            })
        })
        .collect();
    json!({
        "message": {"text": format!("counterexample ({} steps)", c.steps.len())},
        "threadFlows": [{"locations": locations}],
    })
}

/// `file:line` of a step's plan, split at the last colon (a file name may hold colons).
fn split_plan(p: &str) -> Option<(&str, usize)> {
    let (file, line) = p.rsplit_once(':')?;
    let line: usize = line.parse().ok()?;
    (!file.is_empty() && line > 0).then_some((file, line))
}

/// The manifest of a project named as on the command line (folder or manifest).
fn manifest_of(project: &str) -> String {
    if project.ends_with(".toml") {
        project.to_string()
    } else {
        format!("{}/bdi-check.toml", project.trim_end_matches('/'))
    }
}

/// A path as a SARIF URI reference: relative paths stay relative (consumers resolve them
/// against the checkout), with `/` separators and every byte outside RFC 3986's unreserved
/// characters percent-encoded; absolute paths become `file://` URIs.
pub fn uri(path: &str) -> String {
    // Only Windows separates with `\`; elsewhere it is a character of a file name.
    let path = if cfg!(windows) {
        path.replace('\\', "/")
    } else {
        path.to_string()
    };
    let mut out = String::new();
    // A Windows drive path, `C:/...`, whose colon stays as it is.
    let drive = cfg!(windows)
        && path.as_bytes().first().is_some_and(u8::is_ascii_alphabetic)
        && path.as_bytes().get(1) == Some(&b':');
    if path.starts_with('/') {
        out.push_str("file://");
    } else if drive {
        out.push_str("file:///");
    }
    for (i, b) in path.bytes().enumerate() {
        let keep = b.is_ascii_alphanumeric()
            || matches!(b, b'-' | b'.' | b'_' | b'~' | b'/')
            || (b == b':' && i == 1 && drive);
        if keep {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// What each check of SPEC §3 looks for, as a rule's short description.
fn describe(check: &str) -> &'static str {
    match check {
        "input" => "The input is malformed (syntax, types, manifest, missing file)",
        "dead-plan" => "A plan's context is unsatisfiable under the invariants",
        "shadowed-plan" => {
            "An earlier plan for the same trigger is applicable whenever this one is"
        }
        "coverage-gap" => "A goal can be posted in a state where no plan for it is applicable",
        "plan-overlap" => "Two plans for the same trigger are applicable in one state",
        "precondition" => "A body action's precondition may not hold when it runs",
        "effect-conflict" => "An action adds and deletes the same atom",
        "action-breaks-invariant" => {
            "An action can lead from a state to one that breaks an invariant"
        }
        "undefined-action" => "A plan calls an action that nothing defines",
        "undefined-predicate" => "A test goal asks a predicate that nothing defines",
        "unused-action" => "A PDDL action that no plan calls",
        "no-plan-for-goal" => "A goal is posted or requested that no plan handles",
        "invariant" => "An invariant fails in a reachable state",
        "property" => "A property of the manifest fails",
        "action-failure" => "An action runs when its precondition does not hold",
        "goal-failure" => "An achievement goal fails and its intention is dropped",
        "deadlock" => "A reachable state where requests are pending and nothing can happen",
        "livelock" => "A run that cycles forever without completing its requests",
        "request-not-completed" => "A request that some run never completes",
        "demand-exact" => {
            "Explanations are given exactly at the novel action pairs, and N grows by exactly them"
        }
        "demand-adoption" => {
            "Algorithm 1 as the paper writes it flags the same actions as the observed sequence"
        }
        "content-covers" => {
            "An explanation's content ends at the step that first changes a literal of its context"
        }
        "content-concise" => "An explanation's content holds no step after that one",
        "content-truthful" => "Every literal of an explanation's context is believed when given",
        "demand-conformance" => "The agent explains exactly when the reference algorithm does",
        "content-conformance" => "The agent's explanations equal the reference ones",
        _ => "A bdi-check check",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_are_relative_and_encoded() {
        assert_eq!(uri("specs/paper/paper.asl"), "specs/paper/paper.asl");
        assert_eq!(uri("my specs/a#b.asl"), "my%20specs/a%23b.asl");
        assert_eq!(uri("/abs/x.asl"), "file:///abs/x.asl");
        if cfg!(windows) {
            assert_eq!(uri("dir\\x.asl"), "dir/x.asl");
            assert_eq!(uri("C:\\specs\\a.asl"), "file:///C:/specs/a.asl");
        } else {
            assert_eq!(uri("dir\\x.asl"), "dir%5Cx.asl");
            assert_eq!(uri("C:x.asl"), "C%3Ax.asl");
        }
        assert_eq!(uri("küche.asl"), "k%C3%BCche.asl");
    }

    #[test]
    fn plan_locations_split_at_the_last_colon() {
        assert_eq!(
            split_plan("specs/paper/paper.asl:11"),
            Some(("specs/paper/paper.asl", 11))
        );
        assert_eq!(split_plan("a:b.asl:3"), Some(("a:b.asl", 3)));
        assert_eq!(split_plan("paper.asl"), None);
        assert_eq!(split_plan(":4"), None);
    }
}
