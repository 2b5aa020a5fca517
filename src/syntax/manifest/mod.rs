//! The project manifest `bdi-check.toml` (SPEC §1) and scenario files (SPEC §2).
//!
//! Both are read with `toml`'s spanned document tree ([`toml::de::DeTable`]) rather than with
//! serde derive, because strict validation needs what serde hides: every key and value with its
//! byte range, and every error collected instead of stopping at the first. Each diagnostic points
//! into the TOML text, so it renders as `bdi-check.toml:LINE:COLUMN` with a caret.
//!
//! Formulas written as TOML strings are parsed with the AgentSpeak parser, and their AST spans
//! point *into the TOML file* (one [`FileId`] for the manifest and everything in it), so a
//! syntax error in `always = "not cupAt(C,, floor)"` shows the manifest line with a caret under
//! the second comma. See `StrMap` (private) for how string contents are mapped back to the file.
//!
//! # Defaults
//!
//! Only `[agent]` with `plans` and `actions` is required, plus `name` and one kind in each
//! `[[property]]`. Everything else has a default, listed on each field: no objects, no facts,
//! no varying predicates, no constraints, no requests, [`DEFAULT_MAX_REQUESTS`] request per run
//! arriving when the agent is idle, no invariants, no properties, no explanation checks,
//! [`DEFAULT_MAX_STATES`] states, [`DEFAULT_MAX_DEPTH`] depth, no symmetry, first-plan
//! selection.
//!
//! The parsed values are in `types` (re-exported here); `validate` reads TOML values and
//! formulas, `sections` each section of the manifest and of a scenario, and `spans` maps
//! the spans of a string's contents back into the TOML text.

pub mod ltl;
mod sections;
mod spans;
#[cfg(test)]
mod tests;
mod types;
mod validate;

pub use ltl::{LtlBinary, LtlExpr, LtlKind, LtlUnary};
pub use types::{
    AgentEntry, AgentSection, Allow, Arrival, Bounds, ExpectedPair, ExplanationSection, FileRef,
    Formula, InitialSection, Invariant, Located, Manifest, Modifies, ObjectType, Phrase,
    PlanSelection, Property, PropertyKind, RequestsSection, Scenario, StepFormula, User,
    MAX_NUMBERS,
};

use super::diagnostic::Diagnostic;
use super::source::{FileId, SourceMap};
use std::path::Path;
use validate::Cx;

/// The manifest's file name inside a project folder.
pub const MANIFEST_NAME: &str = "bdi-check.toml";
/// Default of `[requests] max`: one request per run. The number of ground goal instances is not
/// known before the PDDL objects are resolved, and one request already exercises every plan.
pub const DEFAULT_MAX_REQUESTS: u32 = 1;
/// Default of `[bounds] max_states`.
pub const DEFAULT_MAX_STATES: u64 = 5_000_000;
/// Default of `[bounds] max_depth`.
pub const DEFAULT_MAX_DEPTH: u64 = 2_000;

/// Reads and validates a manifest. `path` is the project folder or the manifest file itself
/// (SPEC: every command that takes PROJECT accepts either). The text is added to `map`.
/// Returns every error found, sorted by position.
pub fn load_manifest(path: &Path, map: &mut SourceMap) -> Result<Manifest, Vec<Diagnostic>> {
    let file_path = if path.is_dir() {
        let p = path.join(MANIFEST_NAME);
        if !p.is_file() {
            return Err(vec![Diagnostic::error(
                "input",
                format!(
                    "`{}` is not a project: it has no `{MANIFEST_NAME}`",
                    path.display()
                ),
            )
            .in_file(path.display().to_string())]);
        }
        p
    } else {
        // An agent or a domain given for the project: say what PROJECT is, rather than
        // report its text as broken TOML.
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if path.is_file() && ["asl", "mas2j", "pddl"].contains(&ext) {
            return Err(vec![Diagnostic::error(
                "input",
                format!(
                    "`{}` is not a project: PROJECT is a folder holding a `{MANIFEST_NAME}`, or that `{MANIFEST_NAME}` itself",
                    path.display()
                ),
            )
            .in_file(path.display().to_string())
            .with_help(format!(
                "name the folder (`{}`), whose `{MANIFEST_NAME}` lists the agent and its PDDL domain",
                path.parent()
                    .map(|d| d.display().to_string())
                    .filter(|d| !d.is_empty())
                    .unwrap_or_else(|| ".".into())
            ))]);
        }
        path.to_path_buf()
    };
    let file = read_into(&file_path, map)?;
    let mut manifest = parse_manifest(file, &map.file(file).text, &file_path)?;
    if let Some(mas) = manifest.agent.mas.clone() {
        read_mas(&mas, &mut manifest.agent, map)?;
    }
    Ok(manifest)
}

/// Reads the agents of the `.mas2j` that `[agent] mas` names into `agent`: each agent's
/// source is found as Jason finds it (`SourcePath.fixPath`: the file itself, relative to
/// the project file's folder, then in each `aslSourcePath` folder), and those folders are
/// added to where `include` looks.
fn read_mas(
    mas: &FileRef,
    agent: &mut AgentSection,
    map: &mut SourceMap,
) -> Result<(), Vec<Diagnostic>> {
    let file = read_into(&mas.path, map)?;
    let text = map.file(file).text.clone();
    let project = crate::syntax::mas2j::parse_mas2j(file, &text)?;
    let dir = mas.path.parent().map(Path::to_path_buf).unwrap_or_default();
    let folders: Vec<std::path::PathBuf> = project
        .source_path
        .iter()
        .map(|p| dir.join(p.trim_end_matches('/')))
        .collect();
    let mut errors = Vec::new();
    for a in &project.agents {
        let found = std::iter::once(dir.join(&a.source))
            .chain(folders.iter().map(|f| f.join(&a.source)))
            .find(|p| p.is_file());
        match found {
            Some(path) => agent.agents.push(AgentEntry {
                name: Located {
                    value: a.name.clone(),
                    span: a.span,
                },
                plans: FileRef {
                    written: Located {
                        value: a.source.clone(),
                        span: a.span,
                    },
                    path,
                },
                instances: a.instances,
            }),
            None => errors.push(
                Diagnostic::error(
                    "input",
                    format!(
                        "the source of agent `{}`, `{}`, does not exist",
                        a.name, a.source
                    ),
                )
                .with_label(a.span, "no such file")
                .with_help(format!(
                    "Jason looks for it in `{}` and in the `aslSourcePath` folders",
                    dir.display()
                )),
            ),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    for f in folders.into_iter().filter(|f| f.is_dir()) {
        if !agent.source_path.contains(&f) {
            agent.source_path.push(f);
        }
    }
    agent.plans = agent.agents[0].plans.clone();
    Ok(())
}

/// Validates a manifest text already in a [`SourceMap`] under `file`; `path` is where it was
/// read from, against whose folder `plans` and `actions` are resolved and checked to exist.
pub fn parse_manifest(file: FileId, text: &str, path: &Path) -> Result<Manifest, Vec<Diagnostic>> {
    let mut cx = Cx::new(file, text);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let manifest = cx
        .parse_root()
        .and_then(|root| cx.manifest(&root, path, &dir));
    cx.finish(manifest)
}

/// Reads and validates a scenario file (SPEC §2: `initial` and `requests`, nothing else).
pub fn load_scenario(path: &Path, map: &mut SourceMap) -> Result<Scenario, Vec<Diagnostic>> {
    let file = read_into(path, map)?;
    parse_scenario(file, &map.file(file).text, path)
}

/// Validates a scenario text already in a [`SourceMap`] under `file`.
pub fn parse_scenario(file: FileId, text: &str, path: &Path) -> Result<Scenario, Vec<Diagnostic>> {
    let mut cx = Cx::new(file, text);
    let scenario = cx.parse_root().and_then(|root| cx.scenario(&root, path));
    cx.finish(scenario)
}

fn read_into(path: &Path, map: &mut SourceMap) -> Result<FileId, Vec<Diagnostic>> {
    match crate::syntax::source::read_input(path) {
        Ok(text) => Ok(map.add(path, path.display().to_string(), text)),
        Err(e) => Err(vec![Diagnostic::error(
            "input",
            format!("cannot read `{}`: {e}", path.display()),
        )
        .in_file(path.display().to_string())]),
    }
}
