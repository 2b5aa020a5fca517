//! Rendering only: the JSON report of SPEC §3, its human text, SARIF, JUnit, DOT and
//! scenario files, written from what the commands hand over ([`crate::findings::Report`],
//! runs and source maps). Nothing here runs a stage.

pub mod domain;
pub mod explain;
pub mod graph;
pub mod html;
pub mod junit;
pub mod lint;
pub mod outline;
pub mod replay;
pub mod sarif;
pub mod trace;
pub mod verify;

use crate::findings::Report;
use crate::syntax::{Diagnostic, SourceMap};

/// Every diagnostic with its excerpt, as rustc prints them, each followed by a blank line.
pub fn diagnostics(diagnostics: &[Diagnostic], map: &SourceMap, color: bool) -> String {
    diagnostics
        .iter()
        .map(|d| format!("{}\n", d.render(map, color)))
        .collect()
}

/// Output formats of `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Format {
    /// Text for people (the default).
    #[default]
    Human,
    /// The JSON report of SPEC §3.
    Json,
}

/// The CI formats of `--format` (SPEC §2), for `lint` and `verify`: written from the
/// [`Report`] alone, so they need no source map and hold no timings.
///
/// Kept apart from [`Format`] because every renderer matches `Format` exhaustively and only
/// these two commands have a report whose findings map onto SARIF results or JUnit tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CiFormat {
    /// SARIF 2.1.0 ([`sarif`]).
    Sarif,
    /// JUnit XML ([`junit`]).
    Junit,
}

impl CiFormat {
    /// The report of `command` (`lint`, `verify`) in this format.
    pub fn render(self, report: &Report, command: &str) -> String {
        match self {
            CiFormat::Sarif => sarif::render(report, command),
            CiFormat::Junit => junit::render(report, command),
        }
    }
}
