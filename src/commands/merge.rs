//! `bdi-check merge`: one report and verdict from the JSON reports of the shards of one
//! project (`verify --shard K/N`).

use super::Output;
use crate::findings::Report;
use crate::report::{CiFormat, Format};
use std::path::PathBuf;

/// `merge REPORTS`: the merged report as JSON, SARIF or JUnit (`ci`), or its failing
/// findings and verdict line (`Format::Human`).
pub fn command(reports: &[PathBuf], format: Format, ci: Option<CiFormat>) -> Output {
    let mut values = Vec::new();
    for path in reports {
        let read = crate::syntax::source::read_input(path)
            .map_err(|e| e.to_string())
            .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()));
        match read {
            Ok(v) => values.push(v),
            Err(e) => {
                return Output::refused(format!(
                    "error: cannot read the report `{}`: {e}\n",
                    path.display()
                ))
            }
        }
    }
    match merge(&values) {
        Err(e) => Output::refused(format!("error: {e}\n")),
        Ok(merged) => {
            let verdict = merged["verdict"].as_str().unwrap_or("error").to_string();
            let code = match verdict.as_str() {
                "pass" => 0,
                "fail" => 1,
                "incomplete" => 3,
                _ => 2,
            };
            if let Some(ci) = ci {
                // The merged report is a report like `verify`'s: the same renderers.
                return match serde_json::from_value::<Report>(merged) {
                    Ok(r) => Output::report(ci.render(&r, "verify"), code),
                    Err(e) => Output::refused(format!(
                        "error: the merged report is not a bdi-check report: {e}\n"
                    )),
                };
            }
            let text = match format {
                Format::Json => serde_json::to_string_pretty(&merged).unwrap_or_default() + "\n",
                Format::Human => {
                    // The failing errors, one line each, then the verdict.
                    let mut out = String::new();
                    for f in merged["findings"].as_array().into_iter().flatten() {
                        if f["status"] != "fail" || f["severity"] != "error" {
                            continue;
                        }
                        let l = &f["location"];
                        if let (Some(file), Some(line), Some(col)) =
                            (l["file"].as_str(), l["line"].as_u64(), l["column"].as_u64())
                        {
                            out.push_str(&format!("{file}:{line}:{col}: "));
                        }
                        out.push_str(&format!(
                            "error[{}]: {}\n",
                            f["check"].as_str().unwrap_or(""),
                            f["message"].as_str().unwrap_or("")
                        ));
                    }
                    out.push_str(&format!(
                        "verdict: {verdict} (merged {} reports, {} checks)\n",
                        reports.len(),
                        merged["findings"].as_array().map_or(0, |f| f.len())
                    ));
                    out
                }
            };
            Output::report(text, code)
        }
    }
}

/// Merges the JSON reports of the shards of one project (`verify --shard K/N`) into one
/// report, as a JSON value. Every check holds on all runs only if it holds in every shard,
/// and is reached if some shard reaches it; per finding id:
///
/// * a passing finding with a run (a `reachable` witness) in some shard wins;
/// * else a failing one with a run (a violation, or a lint warning some run reaches): of
///   those, the one with the shortest run, then the first report given;
/// * else the findings agree up to their counts: a failing one wins, then an undecided one,
///   then the first;
/// * a `<check>:all` finding (no place fails the check) goes when a shard found a place
///   that fails it, and so does an explanation property's `<check>:<user>` finding when a
///   shard found a place (`<check>:<user>:<file>:<line>`) where it fails for that user.
///
/// Statistics add up (states reached by several shards count once per shard), the depth
/// and seconds are the largest, and the search is complete when every shard's was. Fails
/// with a message when a report cannot be read or the reports are of different projects.
pub fn merge(reports: &[serde_json::Value]) -> Result<serde_json::Value, String> {
    use serde_json::{json, Value};
    let Some(first) = reports.first() else {
        return Err("merge needs at least one report".into());
    };
    let project = first.get("project").cloned().unwrap_or(Value::Null);
    let mut order: Vec<String> = Vec::new();
    let mut by_id: std::collections::HashMap<String, Vec<&Value>> = Default::default();
    let (mut initial, mut states, mut transitions) = (0u64, 0u64, 0u64);
    let (mut depth, mut seconds, mut complete) = (0u64, 0f64, true);
    for (n, r) in reports.iter().enumerate() {
        let findings = r
            .get("findings")
            .and_then(Value::as_array)
            .ok_or_else(|| format!("report {} has no `findings` array", n + 1))?;
        if r.get("project") != Some(&project) {
            return Err(format!(
                "report {} is of project {}, report 1 of {}: merge the shards of one project",
                n + 1,
                r.get("project").unwrap_or(&Value::Null),
                project
            ));
        }
        if r.get("sources") != first.get("sources") {
            return Err(format!(
                "report {} was made from other files than report 1 (the project changed between the shards): merge the shards of one run",
                n + 1
            ));
        }
        for f in findings {
            let id = f
                .get("id")
                .and_then(Value::as_str)
                .ok_or_else(|| format!("a finding of report {} has no `id`", n + 1))?;
            if !by_id.contains_key(id) {
                order.push(id.to_string());
            }
            by_id.entry(id.to_string()).or_default().push(f);
        }
        if let Some(st) = r.get("stats") {
            let num = |k: &str| st.get(k).and_then(Value::as_u64).unwrap_or(0);
            initial += num("initial_states");
            states += num("states");
            transitions += num("transitions");
            depth = depth.max(num("depth"));
            seconds = seconds.max(st.get("seconds").and_then(Value::as_f64).unwrap_or(0.0));
            complete &= st.get("complete").and_then(Value::as_bool).unwrap_or(false);
        } else {
            complete = false;
        }
    }
    check_shards(reports)?;
    let status = |f: &Value| {
        f.get("status")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string()
    };
    let run_len = |f: &Value| {
        f.get("counterexample")
            .and_then(|c| c.get("steps"))
            .and_then(Value::as_array)
            .map(|s| s.len())
    };
    // A lint warning one shard settles as reached (an error) beats the same warning
    // another shard settles as unreached (a note).
    let rank = |f: &Value| match f.get("severity").and_then(Value::as_str) {
        Some("error") => 0,
        Some("warning") => 1,
        _ => 2,
    };
    let mut findings = Vec::new();
    for id in &order {
        let all = &by_id[id];
        let with_run = |st: &str| {
            all.iter()
                .filter(|f| status(f) == st && run_len(f).is_some())
                .min_by_key(|f| (rank(f), run_len(f)))
                .copied()
        };
        let chosen = with_run("pass")
            .or_else(|| with_run("fail"))
            .or_else(|| all.iter().find(|f| status(f) == "fail").copied())
            .or_else(|| all.iter().find(|f| status(f) == "unknown").copied())
            .unwrap_or(all[0]);
        findings.push(chosen.clone());
    }
    // `<check>:all` says that no place failed the check: not so when a shard found one.
    let check_of = |f: &Value| {
        f.get("check")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string()
    };
    let failing: std::collections::HashSet<String> = findings
        .iter()
        .filter(|f| status(f) == "fail")
        .map(check_of)
        .collect();
    let failing_ids: Vec<String> = findings
        .iter()
        .filter(|f| status(f) == "fail")
        .filter_map(|f| f.get("id").and_then(Value::as_str).map(str::to_string))
        .collect();
    findings.retain(|f| {
        let id = f.get("id").and_then(Value::as_str).unwrap_or("");
        let prefix = format!("{id}:");
        status(f) == "fail"
            || !((id.ends_with(":all") && failing.contains(&check_of(f)))
                || failing_ids.iter().any(|x| x.starts_with(&prefix)))
    });
    let failed = |f: &Value, check: Option<&str>| {
        f.get("severity").and_then(Value::as_str) == Some("error")
            && status(f) == "fail"
            && check.is_none_or(|c| f.get("check").and_then(Value::as_str) == Some(c))
    };
    let verdict = if findings.iter().any(|f| failed(f, Some("input"))) {
        "error"
    } else if findings.iter().any(|f| failed(f, None)) {
        "fail"
    } else if !complete || findings.iter().any(|f| status(f) == "unknown") {
        "incomplete"
    } else {
        "pass"
    };
    let mut warnings: Vec<Value> = Vec::new();
    for w in reports
        .iter()
        .filter_map(|r| r.get("warnings")?.as_array())
        .flatten()
    {
        // A shard that held no initial state says so; the merged run covers them all.
        let empty_shard = w
            .as_str()
            .is_some_and(|t| t.contains(super::verify::EMPTY_SHARD));
        if !empty_shard && !warnings.contains(w) {
            warnings.push(w.clone());
        }
    }
    let mut out = first.clone();
    out["verdict"] = json!(verdict);
    out["findings"] = Value::Array(findings);
    if let Some(o) = out.as_object_mut() {
        o.remove("warnings");
        o.remove("shard");
        if !warnings.is_empty() {
            o.insert("warnings".into(), Value::Array(warnings));
        }
    }
    out["stats"] = json!({
        "initial_states": initial,
        "states": states,
        "transitions": transitions,
        "depth": depth,
        "seconds": seconds,
        "states_per_second": if seconds > 0.0 { states as f64 / seconds } else { 0.0 },
        "complete": complete,
    });
    Ok(out)
}

/// The reports must be the parts 1..N of one sharded run, each once (a report without a
/// `shard` is the whole run, 1/1).
fn check_shards(reports: &[serde_json::Value]) -> Result<(), String> {
    let part = |r: &serde_json::Value| -> (u64, u64) {
        let s = &r["shard"];
        match (s["index"].as_u64(), s["count"].as_u64()) {
            (Some(k), Some(n)) => (k, n),
            _ => (1, 1),
        }
    };
    let (_, n) = part(&reports[0]);
    if n == 0 || n > reports.len() as u64 {
        return Err(format!(
            "report 1 is one of {n} shards, but {} reports are given: merge every shard of the run, each once",
            reports.len()
        ));
    }
    let mut seen = vec![false; n as usize];
    for (i, r) in reports.iter().enumerate() {
        let (k, m) = part(r);
        if m != n {
            return Err(format!(
                "report {} is shard {k}/{m}, report 1 is of {n} shards: merge the shards of one run",
                i + 1
            ));
        }
        let slot = seen
            .get_mut((k as usize).wrapping_sub(1))
            .ok_or_else(|| format!("report {} names shard {k}/{m}, which does not exist", i + 1))?;
        if std::mem::replace(slot, true) {
            return Err(format!("shard {k}/{n} is given twice (report {})", i + 1));
        }
    }
    let missing: Vec<String> = (1..=n)
        .filter(|k| !seen[*k as usize - 1])
        .map(|k| format!("{k}/{n}"))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "shard{} {} missing: merge every shard of the run",
            if missing.len() == 1 { " is" } else { "s are" },
            missing.join(", ")
        ));
    }
    Ok(())
}
