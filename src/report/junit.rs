//! `--format junit`: the report as JUnit XML, the test-report format CI systems (GitHub
//! Actions reporters, GitLab, Jenkins) show as a list of passed and failed tests.
//!
//! Written by hand: the shape is one suite of flat test cases, and a crate would add build
//! time for forty lines of escaping. One `<testcase>` per finding, passed ones too, so the
//! dashboard counts every check. What fails the verdict is a `<failure>` (an error that
//! failed) or an `<error>` (malformed input); an undecided check and a finding suppressed by `[[allow]]` are `<skipped>`; a failing
//! warning or note is reported in `<system-out>` without failing, as the exit code does.
//! There are no `time` attributes: the output depends on the findings alone.

use super::verify::render_counterexample;
use crate::findings::{Finding, Report, Status};
use crate::syntax::Severity;

/// How a finding shows in JUnit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outcome {
    Passed,
    Failure,
    Error,
    Skipped,
    /// Failed, but only a warning or note: passes, with the message in `<system-out>`.
    Remark,
}

fn outcome(f: &Finding) -> Outcome {
    if f.suppressed.is_some() {
        return Outcome::Skipped;
    }
    match f.status {
        Status::Pass => Outcome::Passed,
        Status::Unknown => Outcome::Skipped,
        Status::Fail if f.severity != Severity::Error => Outcome::Remark,
        Status::Fail if f.check == "input" => Outcome::Error,
        Status::Fail => Outcome::Failure,
    }
}

/// The report of `command` (`lint` or `verify`) as a JUnit XML document with one
/// `<testsuite name="bdi-check COMMAND PROJECT">`: suites of several projects merged into
/// one document stay apart.
pub fn render(report: &Report, command: &str) -> String {
    let outcomes: Vec<Outcome> = report.findings.iter().map(outcome).collect();
    let count = |o: Outcome| outcomes.iter().filter(|x| **x == o).count();
    let tests = report.findings.len();
    let (failures, errors, skipped) = (
        count(Outcome::Failure),
        count(Outcome::Error),
        count(Outcome::Skipped),
    );
    let tool = format!("bdi-check {command}");
    let suite = format!("{tool} {}", report.project);
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    out.push_str(&format!(
        "<testsuites name=\"{}\" tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\" skipped=\"{skipped}\">\n",
        attr(&tool)
    ));
    out.push_str(&format!(
        "  <testsuite name=\"{}\" tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\" skipped=\"{skipped}\">\n",
        attr(&suite)
    ));
    out.push_str("    <properties>\n");
    for (name, value) in [
        ("project", report.project.as_str()),
        ("verdict", verdict(report)),
        ("version", report.tool.version),
    ] {
        out.push_str(&format!(
            "      <property name=\"{name}\" value=\"{}\"/>\n",
            attr(value)
        ));
    }
    out.push_str("    </properties>\n");
    for (f, o) in report.findings.iter().zip(outcomes) {
        out.push_str(&testcase(f, o));
    }
    out.push_str("  </testsuite>\n</testsuites>\n");
    out
}

fn verdict(r: &Report) -> &'static str {
    match r.verdict {
        crate::findings::Verdict::Pass => "pass",
        crate::findings::Verdict::Fail => "fail",
        crate::findings::Verdict::Incomplete => "incomplete",
        crate::findings::Verdict::Error => "error",
    }
}

fn testcase(f: &Finding, o: Outcome) -> String {
    let mut head = format!(
        "    <testcase classname=\"{}\" name=\"{}\"",
        attr(&f.check),
        attr(&f.id)
    );
    if let Some(l) = &f.location {
        head.push_str(&format!(" file=\"{}\" line=\"{}\"", attr(&l.file), l.line));
    }
    if o == Outcome::Passed {
        return head + "/>\n";
    }
    let mut body = String::new();
    if let Some(l) = &f.location {
        body.push_str(&format!("{l}: "));
    }
    body.push_str(&f.message);
    body.push('\n');
    if let Some(c) = &f.counterexample {
        body.push_str(&render_counterexample(c));
    }
    let inner = match o {
        Outcome::Failure | Outcome::Error => {
            let tag = if o == Outcome::Failure {
                "failure"
            } else {
                "error"
            };
            format!(
                "      <{tag} message=\"{}\" type=\"{}\">{}</{tag}>\n",
                attr(&f.message),
                attr(&f.check),
                text(&body)
            )
        }
        Outcome::Skipped => {
            let why = match &f.suppressed {
                Some(why) => format!("suppressed by [[allow]] ({why}): {}", f.message),
                None => format!("undecided: {}", f.message),
            };
            format!("      <skipped message=\"{}\"/>\n", attr(&why))
        }
        Outcome::Remark => format!(
            "      <system-out>{}: {}</system-out>\n",
            f.severity,
            text(&body)
        ),
        Outcome::Passed => String::new(),
    };
    format!("{head}>\n{inner}    </testcase>\n")
}

/// Escapes character data: `&`, `<`, `>` and characters XML 1.0 cannot hold at all.
pub fn text(s: &str) -> String {
    escape(s, false)
}

/// Escapes an attribute value (double-quoted): as [`text`], plus quotes and the whitespace
/// that attribute normalisation would otherwise turn into spaces.
pub fn attr(s: &str) -> String {
    escape(s, true)
}

fn escape(s: &str, attribute: bool) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' if attribute => out.push_str("&quot;"),
            '\'' if attribute => out.push_str("&apos;"),
            '\n' if attribute => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\t' if attribute => out.push_str("&#9;"),
            '\t' | '\n' => out.push(c),
            // XML 1.0 §2.2: no other control characters, not even as references.
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping() {
        assert_eq!(
            attr("a<b & \"c\" 'd'\ne"),
            "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&#10;e"
        );
        assert_eq!(text("x > y\n\"z\"\u{1}"), "x &gt; y\n\"z\"\u{FFFD}");
    }
}
