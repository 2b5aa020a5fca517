//! The commands of SPEC §2, one file each: load the project, run the stages, and hand the
//! result to [`crate::report`] for rendering. `main.rs` parses the command line into these
//! calls and writes what they return; nothing here prints.

pub mod allow;
pub mod explain;
pub mod graph;
pub mod lint;
pub mod merge;
pub mod parse;
pub mod replay;
pub mod trace;
pub mod verify;

use crate::findings::{Finding, Report, Verdict};
use crate::report::verify::Detail;
use crate::report::{CiFormat, Format};
use crate::syntax::{Diagnostic, SourceMap};

/// What a command gives back: its report text, what goes to stderr, and the exit code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    /// The report, for stdout or `-o FILE`; `None` when the command stopped before it had
    /// one (nothing is written then, not even an empty file).
    pub report: Option<String>,
    /// Diagnostics and notes for stderr, written before the report.
    pub stderr: String,
    /// The exit status of SPEC §2.
    pub code: i32,
}

impl Output {
    /// A report and its exit code, nothing on stderr.
    pub fn report(text: String, code: i32) -> Output {
        Output {
            report: Some(text),
            stderr: String::new(),
            code,
        }
    }

    /// No report: a message on stderr and exit 2 (bad input or a usage error).
    pub fn refused(stderr: String) -> Output {
        Output {
            report: None,
            stderr,
            code: 2,
        }
    }
}

/// How the report is to be written: `--format`, `--quiet`/`--verbose`, and colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Style {
    /// Human or JSON (the CI formats are in `ci`, and then this is `Json`).
    pub format: Format,
    /// SARIF or JUnit, when asked for.
    pub ci: Option<CiFormat>,
    /// What the human output shows.
    pub detail: Detail,
    /// `--format html` (then `format` is `Human` and `ci` is `None`).
    pub html: bool,
    /// Colour in the report (stdout is a terminal and no `-o`).
    pub color: bool,
    /// Colour in stderr's diagnostics (stderr is a terminal).
    pub stderr_color: bool,
}

impl Style {
    /// A usage error when a command that writes no page is asked for `--format html`.
    pub fn refuse_html(&self, command: &str) -> Option<Output> {
        self.html.then(|| {
            Output::refused(format!(
                "error: `--format html` is for `lint`, `verify`, `simulate` and `explain --scenario`; `{command}` writes `human` or `json`\n"
            ))
        })
    }

    /// A usage error (exit 2, as clap's) when a command that has no findings to report is
    /// asked for SARIF or JUnit (or, with no page to write, HTML).
    pub fn refuse_ci_format(&self, command: &str) -> Option<Output> {
        let name = match self.ci {
            Some(CiFormat::Sarif) => "sarif",
            Some(CiFormat::Junit) => "junit",
            None if self.html => return self.refuse_html(command),
            None => return None,
        };
        Some(Output::refused(format!(
            "error: `--format {name}` is for `lint` and `verify`; `{command}` writes `human` or `json`\n"
        )))
    }
}

/// The report of a project that is bad input: its diagnostics as `input` findings, and
/// the verdict `error` (the same for `lint` and `verify`).
fn input_report(name: String, map: &SourceMap, diagnostics: &[Diagnostic]) -> Report {
    let findings: Vec<Finding> = diagnostics
        .iter()
        .map(|d| Finding::from_input_diagnostic(d, map))
        .collect();
    let mut report = Report::new(name, findings);
    report.verdict = Verdict::Error;
    report
}
