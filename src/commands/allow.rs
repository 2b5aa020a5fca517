//! `[[allow]]`: failing findings a project accepts on purpose, each with its reason, in
//! the manifest where a reviewer sees them. A suppressed finding stays in the report
//! (marked with its reason, a SARIF suppression, a skipped JUnit test) and does not count
//! toward the verdict. An allow that names a check bdi-check does not have, or a file that
//! is not the project's, is bad input; one that matches nothing is reported, so that a
//! suppression outliving its bug does not go unnoticed.

use crate::findings::{Finding, Status};
use crate::model::project::Project;
use crate::syntax::manifest::Allow;
use crate::syntax::Diagnostic;
use std::path::PathBuf;

/// Whether a check name is one of bdi-check's.
pub fn known_check(name: &str) -> bool {
    crate::smt::lint::CHECKS.contains(&name)
        || crate::check::explanation::CHECKS.contains(&name)
        || crate::check::CHECKS.contains(&name)
        || name == "input"
}

/// The allows' errors: unknown checks and files that are not among the project's.
pub fn check(project: &Project) -> Vec<Diagnostic> {
    let files = project_files(project);
    let mut out = Vec::new();
    for a in &project.manifest.allows {
        if !known_check(&a.check.value) || a.check.value == "input" {
            out.push(
                Diagnostic::error(
                    "input",
                    format!("`{}` is not a check bdi-check has", a.check.value),
                )
                .with_label(a.check.span, "unknown check")
                .with_help("the check names are those of SPEC §3, as reports give them"),
            );
        }
        if let Some(at) = &a.at {
            if resolve(project, &at.value.0).is_none_or(|p| !files.contains(&p)) {
                out.push(
                    Diagnostic::error(
                        "input",
                        format!("`{}` is not a file of the project", at.value.0),
                    )
                    .with_label(at.span, "no such project file")
                    .with_help("give the path relative to the project folder, as `agent.asl:12`"),
                );
            }
        }
    }
    out
}

/// Marks each failing error or warning an allow names as suppressed, with the allow's
/// reason; the returned warnings name the allows of the checks `ran` that matched none.
pub fn apply<'f>(
    project: &Project,
    findings: impl IntoIterator<Item = &'f mut Finding>,
    ran: impl Fn(&str) -> bool,
) -> Vec<String> {
    let allows = &project.manifest.allows;
    if allows.is_empty() {
        return Vec::new();
    }
    // Each project file as the file system names it, looked up once, by file id.
    let canonical: Vec<Option<PathBuf>> = project
        .map
        .files()
        .iter()
        .map(|f| std::fs::canonicalize(&f.path).ok())
        .collect();
    let places: Vec<Option<(PathBuf, Option<usize>)>> = allows
        .iter()
        .map(|a| {
            a.at.as_ref()
                .and_then(|at| Some((resolve(project, &at.value.0)?, at.value.1)))
        })
        .collect();
    let mut used = vec![false; allows.len()];
    for f in findings {
        // A note fails nothing: there is nothing to accept.
        if f.status != Status::Fail || f.severity == crate::syntax::Severity::Note {
            continue;
        }
        let file = f
            .span
            .and_then(|s| canonical.get(s.file.0 as usize).cloned().flatten());
        let line = f.location.as_ref().map(|l| l.line);
        let hit = allows.iter().zip(&places).position(|(a, place)| {
            a.check.value == f.check
                && match (&a.at, place) {
                    (None, _) => true,
                    (Some(_), Some((path, want))) => {
                        file.as_ref() == Some(path) && want.is_none_or(|n| line == Some(n))
                    }
                    (Some(_), None) => false,
                }
        });
        if let Some(k) = hit {
            used[k] = true;
            f.suppressed = Some(allows[k].why.value.clone());
        }
    }
    allows
        .iter()
        .zip(used)
        .filter(|(a, used)| !used && ran(&a.check.value))
        .map(|(a, _)| unused(project, a))
        .collect()
}

fn unused(project: &Project, a: &Allow) -> String {
    let loc = project.map.location(a.span);
    let what = match &a.at {
        Some(at) => {
            format!("`{}` at {}", a.check.value, at.value.0)
                + &at.value.1.map(|n| format!(":{n}")).unwrap_or_default()
        }
        None => format!("`{}`", a.check.value),
    };
    format!(
        "the [[allow]] of {what} ({}:{}) matches no failing finding: remove it if what it allowed is fixed",
        loc.file, loc.line
    )
}

/// A file named relative to the project folder, as the file system names it.
fn resolve(project: &Project, file: &str) -> Option<PathBuf> {
    std::fs::canonicalize(project.manifest.dir.join(file)).ok()
}

/// The project's files, as the file system names them.
fn project_files(project: &Project) -> Vec<PathBuf> {
    project
        .map
        .files()
        .iter()
        .filter_map(|f| std::fs::canonicalize(&f.path).ok())
        .collect()
}
