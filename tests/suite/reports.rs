//! The machine-readable reports CI consumes: SARIF 2.1.0 and JUnit XML carry what the JSON
//! report holds, every format is byte-identical from run to run (timings aside), and every
//! exit code of SPEC §2 is the same whatever the format.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common;
use common::bdi_check;

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("reports are UTF-8")
}

/// `bdi-check COMMAND PROJECT --format FORMAT [extra]`: exit code and stdout.
fn run(command: &str, project: &str, format: &str, extra: &[&str]) -> (i32, String) {
    let mut args = vec![command, project, "--format", format];
    args.extend_from_slice(extra);
    let o = bdi_check(&args);
    (o.status.code().expect("exit code"), stdout(&o))
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("not JSON ({e}):\n{text}"))
}

/// The JSON report without its timings, which are the only part allowed to differ.
fn without_timings(text: &str) -> String {
    let mut v = json(text);
    let stats = v["stats"].as_object_mut().expect("verify reports stats");
    assert!(stats.remove("seconds").is_some());
    assert!(stats.remove("states_per_second").is_some());
    for phase in stats["phases"].as_array_mut().expect("phases") {
        assert!(phase.as_object_mut().unwrap().remove("seconds").is_some());
    }
    serde_json::to_string_pretty(&v).unwrap()
}

fn failing(report: &serde_json::Value) -> Vec<&serde_json::Value> {
    report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["status"] != "pass")
        .collect()
}

#[test]
fn repeated_runs_are_byte_identical_in_every_format() {
    for project in ["specs/kitchen", "specs/paper"] {
        for format in ["json", "sarif", "junit"] {
            let (code1, first) = run("verify", project, format, &[]);
            let (code2, second) = run("verify", project, format, &[]);
            assert_eq!(code1, code2, "{project} {format}");
            assert!(!first.is_empty(), "{project} {format}");
            if format == "json" {
                assert_eq!(
                    without_timings(&first),
                    without_timings(&second),
                    "{project}"
                );
            } else {
                assert_eq!(first, second, "{project} --format {format} differs");
            }
        }
        let (_, a) = run("lint", project, "sarif", &[]);
        let (_, b) = run("lint", project, "sarif", &[]);
        assert_eq!(a, b, "lint {project}");
    }
}

#[test]
fn sarif_and_junit_hold_no_timings() {
    for format in ["sarif", "junit"] {
        let (_, text) = run("verify", "specs/kitchen", format, &[]);
        for word in ["seconds", "time=", "timestamp", "duration"] {
            assert!(!text.contains(word), "{format} holds `{word}`");
        }
    }
}

/// Checks what SARIF 2.1.0 requires (and GitHub code scanning reads) of a log; returns its
/// one run.
fn check_sarif(text: &str) -> serde_json::Value {
    let log = json(text);
    assert_eq!(log["version"], "2.1.0");
    assert!(log["$schema"].as_str().unwrap().contains("sarif-2.1.0"));
    let runs = log["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 1);
    let run = runs[0].clone();
    let driver = &run["tool"]["driver"];
    assert_eq!(driver["name"], "bdi-check");
    assert_eq!(driver["version"], env!("CARGO_PKG_VERSION"));
    let rules: Vec<&str> = driver["rules"]
        .as_array()
        .expect("rules")
        .iter()
        .map(|r| r["id"].as_str().expect("rule id"))
        .collect();
    let mut unique = rules.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique, rules, "rules are sorted and unique");
    for r in run["results"].as_array().expect("results") {
        let rule = r["ruleId"].as_str().expect("ruleId");
        let index = r["ruleIndex"].as_u64().expect("ruleIndex") as usize;
        assert_eq!(rules[index], rule);
        assert!(!r["message"]["text"].as_str().expect("message").is_empty());
        let level = r["level"].as_str().expect("level");
        match r["kind"].as_str().expect("kind") {
            "fail" => assert!(["error", "warning"].contains(&level), "{r}"),
            "open" | "informational" => assert_eq!(level, "none"),
            k => panic!("kind {k}"),
        }
        let loc = &r["locations"][0]["physicalLocation"];
        let uri = loc["artifactLocation"]["uri"].as_str().expect("uri");
        assert!(!uri.is_empty() && !uri.starts_with('/'), "relative: {uri}");
        assert!(loc["region"]["startLine"].as_u64().expect("startLine") >= 1);
        assert!(loc["region"]["startColumn"].as_u64().expect("startColumn") >= 1);
    }
    run
}

#[test]
fn sarif_of_the_paper_has_its_goal_failure_with_a_code_flow() {
    let (code, text) = run("verify", "specs/paper", "sarif", &[]);
    assert_eq!(code, 1);
    let run = check_sarif(&text);
    let (_, report) = run_json("specs/paper");
    // One result per finding that did not pass, in report order.
    let expected: Vec<&str> = failing(&report)
        .iter()
        .map(|f| f["check"].as_str().unwrap())
        .collect();
    let results = run["results"].as_array().unwrap();
    let got: Vec<&str> = results
        .iter()
        .map(|r| r["ruleId"].as_str().unwrap())
        .collect();
    assert_eq!(got, expected);
    let finding = failing(&report)
        .into_iter()
        .find(|f| f["check"] == "goal-failure")
        .expect("the paper's goal failure");
    let result = results
        .iter()
        .find(|r| r["ruleId"] == "goal-failure")
        .unwrap();
    assert_eq!(result["level"], "error");
    let loc = &result["locations"][0]["physicalLocation"];
    assert_eq!(loc["artifactLocation"]["uri"], finding["location"]["file"]);
    assert_eq!(loc["region"]["startLine"], finding["location"]["line"]);
    assert_eq!(loc["region"]["startColumn"], finding["location"]["column"]);
    let steps = finding["counterexample"]["steps"].as_array().unwrap();
    let flow = result["codeFlows"][0]["threadFlows"][0]["locations"]
        .as_array()
        .expect("a thread flow");
    assert!(!steps.is_empty());
    assert_eq!(flow.len(), steps.len());
    for (l, s) in flow.iter().zip(steps) {
        assert_eq!(l["location"]["message"]["text"], s["text"]);
        let physical = &l["location"]["physicalLocation"];
        match s["plan"].as_str() {
            Some(plan) => {
                let (file, line) = plan.rsplit_once(':').unwrap();
                assert_eq!(physical["artifactLocation"]["uri"], file);
                assert_eq!(
                    physical["region"]["startLine"],
                    line.parse::<u64>().unwrap()
                );
            }
            None => assert!(physical.is_null()),
        }
    }
    // Notes (warnings no run reaches, unused actions) are results too, but informational:
    // code scanning opens no alert for them.
    assert!(results.iter().any(|r| r["ruleId"] == "unused-action"
        && r["kind"] == "informational"
        && r["level"] == "none"));
}

fn run_json(project: &str) -> (i32, serde_json::Value) {
    let (code, text) = run("verify", project, "json", &[]);
    (code, json(&text))
}

#[test]
fn sarif_of_a_passing_project_and_of_bad_input() {
    let (code, text) = run("verify", "specs/kitchen", "sarif", &[]);
    assert_eq!(code, 0);
    let run = check_sarif(&text);
    assert!(run["results"]
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["level"] != "error"));

    let (code, text) = run_sarif_bad_input();
    assert_eq!(code, 2);
    let run = check_sarif(&text);
    let results = run["results"].as_array().unwrap();
    assert_eq!(results.len(), 1);
    assert_eq!(results[0]["ruleId"], "input");
    assert_eq!(results[0]["level"], "error");
    assert_eq!(
        results[0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
        "tests/project/unknown_type/bdi-check.toml"
    );
    assert_eq!(run["invocations"][0]["executionSuccessful"], false);
}

fn run_sarif_bad_input() -> (i32, String) {
    run("verify", "tests/project/unknown_type", "sarif", &[])
}

/// A tiny XML checker for the JUnit we write: every tag closes in order, attribute values
/// are quoted and hold no raw `<`, `&` only starts a known entity or character reference,
/// and nothing follows the root. Returns each element's name and attributes, in order.
fn parse_xml(doc: &str) -> Vec<(String, Vec<(String, String)>)> {
    let body = doc
        .strip_prefix("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n")
        .expect("XML declaration");
    let mut elements = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    let mut rest = body;
    let check_entities = |s: &str| {
        for (i, _) in s.match_indices('&') {
            let tail = &s[i..];
            let ok = ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"]
                .iter()
                .any(|e| tail.starts_with(e))
                || (tail.starts_with("&#")
                    && tail[2..].find(';').is_some_and(|j| {
                        j > 0 && tail[2..2 + j].bytes().all(|b| b.is_ascii_digit())
                    }));
            assert!(ok, "bare `&` in {s:?}");
        }
    };
    let mut seen_root = false;
    while let Some(open) = rest.find('<') {
        let text = &rest[..open];
        check_entities(text);
        assert!(!text.contains('>'), "raw `>` in text {text:?}");
        if stack.is_empty() {
            assert!(text.trim().is_empty(), "text outside the root: {text:?}");
        }
        rest = &rest[open + 1..];
        // A tag ends at the first `>` outside quotes.
        let mut quoted = false;
        let end = rest
            .char_indices()
            .find(|&(_, c)| {
                if c == '"' {
                    quoted = !quoted;
                }
                c == '>' && !quoted
            })
            .map(|(i, _)| i)
            .expect("tag closes");
        let tag = &rest[..end];
        rest = &rest[end + 1..];
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "mismatched </{name}>");
            continue;
        }
        assert!(!seen_root || !stack.is_empty(), "a second root <{tag}>");
        seen_root = true;
        let self_closing = tag.ends_with('/');
        let tag = tag.trim_end_matches('/');
        let (name, mut attrs_text) = tag.split_once(' ').unwrap_or((tag, ""));
        let mut attrs = Vec::new();
        while !attrs_text.trim().is_empty() {
            let (key, after) = attrs_text.trim_start().split_once("=\"").expect("key=\"");
            let close = after.find('"').expect("closing quote");
            let value = &after[..close];
            assert!(!value.contains('<'), "raw `<` in {key}={value:?}");
            assert!(!value.contains('\n'), "raw newline in {key}={value:?}");
            check_entities(value);
            assert!(
                attrs.iter().all(|(k, _): &(String, String)| k != key),
                "duplicate {key}"
            );
            attrs.push((key.to_string(), value.to_string()));
            attrs_text = &after[close + 1..];
        }
        elements.push((name.to_string(), attrs));
        if !self_closing {
            stack.push(name.to_string());
        }
    }
    assert!(stack.is_empty(), "unclosed: {stack:?}");
    assert!(rest.trim().is_empty(), "text after the root: {rest:?}");
    elements
}

fn attr<'a>(e: &'a (String, Vec<(String, String)>), key: &str) -> &'a str {
    e.1.iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("<{}> has no {key}", e.0))
}

/// Checks a JUnit document against the JSON report of the same run.
fn check_junit(doc: &str, report: &serde_json::Value, suite: &str) {
    let elements = parse_xml(doc);
    let count = |name: &str| elements.iter().filter(|e| e.0 == name).count();
    let findings = report["findings"].as_array().unwrap();
    let failed_errors = findings
        .iter()
        .filter(|f| f["status"] == "fail" && f["severity"] == "error")
        .count();
    let suites: Vec<_> = elements.iter().filter(|e| e.0 == "testsuite").collect();
    assert_eq!(suites.len(), 1);
    let s = suites[0];
    // Suites are named by project, so documents of several projects merge apart.
    let name = format!("{suite} {}", report["project"].as_str().unwrap())
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    assert_eq!(attr(s, "name"), name);
    assert_eq!(attr(s, "tests"), count("testcase").to_string());
    assert_eq!(count("testcase"), findings.len());
    assert_eq!(attr(s, "failures"), count("failure").to_string());
    assert_eq!(attr(s, "errors"), count("error").to_string());
    assert_eq!(attr(s, "skipped"), count("skipped").to_string());
    assert_eq!(count("failure") + count("error"), failed_errors);
    // Test cases name their findings, in report order.
    let cases: Vec<_> = elements.iter().filter(|e| e.0 == "testcase").collect();
    for (c, f) in cases.iter().zip(findings) {
        assert_eq!(attr(c, "classname"), f["check"].as_str().unwrap());
        let id = f["id"].as_str().unwrap();
        let escaped = id
            .replace('&', "&amp;")
            .replace('"', "&quot;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        assert_eq!(attr(c, "name"), escaped);
    }
}

#[test]
fn junit_of_the_paper_fails_its_goal_failure_with_the_counterexample() {
    let (code, doc) = run("verify", "specs/paper", "junit", &[]);
    assert_eq!(code, 1);
    let (_, report) = run_json("specs/paper");
    check_junit(&doc, &report, "bdi-check verify");
    assert!(doc.contains("<testcase classname=\"goal-failure\""));
    let start = doc.find("<testcase classname=\"goal-failure\"").unwrap();
    let case = &doc[start..start + doc[start..].find("</testcase>").unwrap()];
    assert!(case.contains("<failure message=\""), "{case}");
    assert!(case.contains("counterexample (5 steps)"), "{case}");
    assert!(case.contains("request  !storeCup(cup1)"), "{case}");
    // A message holding `&` is escaped in character data.
    assert!(doc.contains("robotAt(dishwasher) &amp; not dishwasherDoor(open)"));
}

#[test]
fn junit_of_a_passing_project_bad_input_and_lint() {
    let (code, doc) = run("verify", "specs/kitchen", "junit", &[]);
    assert_eq!(code, 0);
    let (_, report) = run_json("specs/kitchen");
    check_junit(&doc, &report, "bdi-check verify");
    assert!(!doc.contains("<failure"));

    let (code, doc) = run("verify", "tests/project/unknown_type", "junit", &[]);
    assert_eq!(code, 2);
    let elements = parse_xml(&doc);
    let errors: Vec<_> = elements.iter().filter(|e| e.0 == "error").collect();
    assert_eq!(errors.len(), 1);
    assert_eq!(attr(errors[0], "type"), "input");

    let (code, doc) = run("lint", "specs/paper", "junit", &[]);
    assert_eq!(code, 0);
    let (_, text) = run("lint", "specs/paper", "json", &[]);
    check_junit(&doc, &json(&text), "bdi-check lint");
}

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir(&format!("reports-{name}"))
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn paths_with_markup_characters_are_escaped_in_junit_and_encoded_in_sarif() {
    let root = temp_dir("markup");
    let project = root.join("a&b \"c\" <d>");
    copy_dir(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/paper"),
        &project,
    );
    let p = project.to_str().unwrap();
    let (code, doc) = run("verify", p, "junit", &[]);
    assert_eq!(code, 1, "{doc}");
    let (_, report) = run_json(p);
    check_junit(&doc, &report, "bdi-check verify");
    assert!(doc.contains("a&amp;b &quot;c&quot; &lt;d&gt;"), "{doc}");

    let (code, text) = run("verify", p, "sarif", &[]);
    assert_eq!(code, 1);
    let log = json(&text);
    let uri = log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]
        ["uri"]
        .as_str()
        .unwrap();
    assert!(uri.starts_with("file:///"), "{uri}");
    assert!(uri.contains("a%26b%20%22c%22%20%3Cd%3E/"), "{uri}");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn exit_codes_are_the_same_in_every_format() {
    let cases: [(&[&str], i32); 7] = [
        (&["lint", "specs/kitchen"], 0),
        (&["lint", "specs/kitchen", "--deny", "warnings"], 1),
        (&["verify", "specs/kitchen"], 0),
        (&["verify", "specs/paper"], 1),
        (&["verify", "specs/kitchen", "--max-states", "100"], 3),
        (&["verify", "tests/project/unknown_type"], 2),
        (&["lint", "tests/project/unknown_type"], 2),
    ];
    for (args, expected) in cases {
        for format in ["human", "json", "sarif", "junit"] {
            let mut a = args.to_vec();
            a.extend(["--format", format]);
            let o = bdi_check(&a);
            assert_eq!(
                o.status.code(),
                Some(expected),
                "{a:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
    }
    // `--deny warnings` makes lint's warnings errors, in SARIF too.
    let (_, text) = run("lint", "specs/kitchen", "sarif", &["--deny", "warnings"]);
    let results = check_sarif(&text)["results"].clone();
    assert!(results
        .as_array()
        .unwrap()
        .iter()
        .any(|r| r["level"] == "error"));
    // The bound stops the search: SARIF says so with undecided (open) results.
    let (_, text) = run("verify", "specs/kitchen", "sarif", &["--max-states", "100"]);
    let run = check_sarif(&text);
    assert!(run["results"]
        .as_array()
        .unwrap()
        .iter()
        .any(|r| r["kind"] == "open"));
    let (_, doc) = self::run("verify", "specs/kitchen", "junit", &["--max-states", "100"]);
    assert!(doc.contains("<skipped message=\"undecided: "), "{doc}");
}

#[test]
fn commands_without_findings_refuse_the_ci_formats() {
    for args in [
        &["parse", "specs/paper/paper.asl", "--format", "sarif"][..],
        &["explain", "specs/paper", "--format", "junit"][..],
    ] {
        let o = bdi_check(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(o.stdout.is_empty());
        assert!(String::from_utf8_lossy(&o.stderr).contains("is for `lint` and `verify`"));
    }
}

#[test]
fn output_files_hold_the_same_bytes_as_stdout() {
    let dir = temp_dir("output");
    for format in ["sarif", "junit"] {
        let file = dir.join(format!("report.{format}"));
        let o = bdi_check(&[
            "verify",
            "specs/paper",
            "--format",
            format,
            "-o",
            file.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1));
        assert!(o.stdout.is_empty());
        let (_, text) = run("verify", "specs/paper", format, &[]);
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_xml_checker_rejects_malformed_documents() {
    let decl = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    let good = format!("{decl}<a x=\"1 &amp; 2\"><b/><c>t &lt; u</c></a>\n");
    assert_eq!(parse_xml(&good).len(), 3);
    for bad in [
        "<a><b></a></b>",         // crossed tags
        "<a><b></a>",             // unclosed
        "<a x=\"1 & 2\"/>",       // bare ampersand
        "<a x=\"<\"/>",           // raw `<` in an attribute
        "<a x=\"say \"hi\"\"/>",  // unescaped quote
        "<a>t & u</a>",           // bare ampersand in text
        "<a/><b/>",               // two roots
        "<a x=\"1\" x=\"2\"/>",   // duplicate attribute
        "<a x=\"line\nbreak\"/>", // raw newline in an attribute
    ] {
        let doc = format!("{decl}{bad}\n");
        let result = std::panic::catch_unwind(|| parse_xml(&doc));
        assert!(result.is_err(), "accepted {bad:?}");
    }
}

/// The headless browser the HTML tests drive: Debian's `chromium` (`.ci/run` installs
/// it). `None` only when `BDI_CHECK_NO_BROWSER=1` says to do without one.
fn browser() -> Option<&'static str> {
    for b in ["chromium", "chromium-browser", "google-chrome"] {
        let found = std::process::Command::new("sh")
            .args(["-c", &format!("command -v {b}")])
            .output()
            .is_ok_and(|o| o.status.success());
        if found {
            return Some(b);
        }
    }
    assert!(
        std::env::var_os("BDI_CHECK_NO_BROWSER").is_some(),
        "the HTML tests need chromium (`apt-get install chromium`; `.ci/run` installs it), or BDI_CHECK_NO_BROWSER=1 to skip them"
    );
    None
}

/// Runs the headless browser on a page: `--dump-dom` gives the DOM after its script ran.
fn chromium(browser: &str, args: &[&str]) -> std::process::Output {
    let profile = common::temp_dir("chromium-profile");
    std::process::Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            // The machine's network is closed: no background connections.
            "--disable-quic",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            &format!("--user-data-dir={}", profile.display()),
        ])
        .args(args)
        .output()
        .expect("the browser runs")
}

#[test]
fn the_html_page_is_self_contained_and_shows_each_step_in_a_real_browser() {
    let dir = common::temp_dir("html");
    let page = dir.join("paper.html");
    let o = bdi_check(&[
        "verify",
        "specs/paper",
        "--format",
        "html",
        "-o",
        page.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "the exit code is verify's in every format"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"), "{html}");
    // No network, no external assets.
    for outside in ["http://", "https://", "<link", "src=", "@import", "url("] {
        assert!(!html.contains(outside), "the page loads `{outside}`");
    }
    // Every failing error of the JSON report is on the page.
    let (_, report) = run("verify", "specs/paper", "json", &[]);
    let report = json(&report);
    for f in report["findings"].as_array().unwrap() {
        if f["status"] == "fail" && f["severity"] == "error" {
            let id = f["id"].as_str().unwrap();
            assert!(html.contains(&format!("data-id=\"{id}\"")), "{id}");
        }
    }
    let Some(b) = browser() else { return };
    // Step 3 of the first run is a plan: selecting it (from the address, as a click does)
    // shows the beliefs after it and highlights its plan in the goal-plan tree.
    let url = format!("file://{}#run-1-step-3", page.display());
    let o = chromium(b, &["--dump-dom", &url]);
    let dom = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(dom.contains("id=\"verdict\">fail<"), "{dom}");
    let step = dom
        .split("<li ")
        .find(|l| l.contains("id=\"run-1-step-3\""))
        .expect("the step is on the page");
    assert!(step.contains("class=\"step k-plan selected\""), "{step}");
    let plan = step
        .split("data-plan=\"")
        .nth(1)
        .and_then(|r| r.split('"').next())
        .expect("a plan step names its plan");
    assert!(
        dom.contains(&format!("class=\"plan running\" data-plan=\"{plan}\"")),
        "the running plan {plan} is not highlighted"
    );
    let pane = dom
        .split("id=\"state-1\">")
        .nth(1)
        .and_then(|r| r.split("</div>").next())
        .unwrap();
    assert!(pane.starts_with("after step 3:"), "{pane}");
    let first = &report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["status"] == "fail" && f["severity"] == "error")
        .unwrap()["counterexample"];
    for atom in first["initial"].as_array().unwrap() {
        assert!(pane.contains(atom.as_str().unwrap()), "{pane}");
    }
    // A screenshot: the page renders.
    let shot = dir.join("paper.png");
    let o = chromium(
        b,
        &[
            "--window-size=1400,1000",
            &format!("--screenshot={}", shot.display()),
            &format!("file://{}", page.display()),
        ],
    );
    let png =
        std::fs::read(&shot).unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    assert!(
        png.starts_with(b"\x89PNG") && png.len() > 10_000,
        "{} bytes",
        png.len()
    );
    // explain's page: the scenario's run with its explanations in place.
    let o = bdi_check(&[
        "explain",
        "specs/paper",
        "--scenario",
        "tests/scenarios/paper_door_closed.toml",
        "--format",
        "html",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let page = dir.join("explain.html");
    std::fs::write(&page, &o.stdout).unwrap();
    let o = chromium(
        b,
        &[
            "--dump-dom",
            &format!("file://{}#run-1-step-1", page.display()),
        ],
    );
    let dom = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(dom.contains("class=\"step k-explanation\""), "{dom}");
    assert!(dom.contains("class=\"step k-request selected\""), "{dom}");
    // Commands with no page refuse the format.
    let o = bdi_check(&["explain", "specs/paper", "--format", "html"]);
    assert_eq!(o.status.code(), Some(2));
    let o = bdi_check(&["parse", "specs/paper/paper.asl", "--format", "html"]);
    assert_eq!(o.status.code(), Some(2));
}
