//! `bdi-check parse`: load files, report every error, and outline what they hold
//! (rendered by [`crate::report::outline`]).

use super::{Output, Style};
use crate::findings::{verdict_of, Finding, Tool};
use crate::model::project::load_system;
use crate::report::domain::{domain_outline, project_outline};
use crate::report::outline::{
    render, Entry, FileOutline, FileReport, ParseReport, ParseRun, PlanOutline,
};
use crate::report::Format;
use crate::syntax::ast::{Item, Plan};
use crate::syntax::loader::load_agent_with;
use crate::syntax::pddl::parse_domain;
use crate::syntax::printer::{print_expr, print_literal, print_step, print_trigger};
use crate::syntax::{Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

/// `parse FILES [-I DIR]`: the outline (or, with `--quiet`, its last line) and every error.
pub fn command(files: &[PathBuf], include: &[PathBuf], quiet: bool, style: &Style) -> Output {
    if let Some(refused) = style.refuse_ci_format("parse") {
        return refused;
    }
    let run = parse_files_with(files, include);
    let (mut text, stderr) = render(&run, style.format, style.color);
    if quiet && style.format == Format::Human {
        text = text
            .lines()
            .last()
            .map(|l| format!("{l}\n"))
            .unwrap_or_default();
    }
    Output {
        report: Some(text),
        stderr,
        code: run.report.verdict.exit_code(),
    }
}

/// Parses every file: `.asl` agents (with their includes), `.mas2j` projects (their
/// agents), `.pddl` domains, and manifests
/// (`.toml`: the whole project is loaded, checked and grounded). Other files are refused.
pub fn parse_files(paths: &[PathBuf]) -> ParseRun {
    parse_files_with(paths, &[])
}

/// [`parse_files`], with folders where an agent's `include` also looks (`-I DIR`).
pub fn parse_files_with(paths: &[PathBuf], source_path: &[PathBuf]) -> ParseRun {
    let mut map = SourceMap::new();
    let mut diagnostics = Vec::new();
    let mut files = Vec::new();
    for path in paths {
        let name = path.display().to_string();
        match path.extension().and_then(|e| e.to_str()) {
            Some("asl") => match load_agent_with(path, &mut map, source_path) {
                Ok(agent) => files.push(FileReport::Agent(outline(path, &agent, &map))),
                Err(errs) => diagnostics.extend(errs),
            },
            Some("pddl") => match crate::syntax::source::read_input(path) {
                Ok(text) => {
                    let id = map.add(path, name.clone(), text);
                    let text = map.file(id).text.clone();
                    match parse_domain(id, &text) {
                        (Some(d), errs) if errs.is_empty() => {
                            files.push(FileReport::Domain(domain_outline(&name, &d, &map)))
                        }
                        (_, errs) => diagnostics.extend(errs),
                    }
                }
                Err(e) => diagnostics.push(
                    Diagnostic::error("input", format!("cannot read `{name}`: {e}")).in_file(name),
                ),
            },
            // A Jason project file: its agents, each parsed with its includes.
            Some("mas2j") => match crate::syntax::source::read_input(path) {
                Ok(text) => {
                    let id = map.add(path, name.clone(), text);
                    let text = map.file(id).text.clone();
                    match crate::syntax::mas2j::parse_mas2j(id, &text) {
                        Ok(mas) => {
                            let dir = path.parent().unwrap_or(Path::new("."));
                            for a in &mas.agents {
                                let found = std::iter::once(dir.join(&a.source))
                                    .chain(mas.source_path.iter().map(|p| dir.join(p).join(&a.source)))
                                    .find(|p| p.is_file());
                                let Some(file) = found else {
                                    diagnostics.push(
                                        Diagnostic::error(
                                            "input",
                                            format!("the source of agent `{}`, `{}`, does not exist", a.name, a.source),
                                        )
                                        .with_label(a.span, "no such file"),
                                    );
                                    continue;
                                };
                                match load_agent_with(&file, &mut map, source_path) {
                                    Ok(agent) => files.push(FileReport::Agent(outline(&file, &agent, &map))),
                                    Err(errs) => diagnostics.extend(errs),
                                }
                            }
                        }
                        Err(errs) => diagnostics.extend(errs),
                    }
                }
                Err(e) => diagnostics.push(
                    Diagnostic::error("input", format!("cannot read `{name}`: {e}")).in_file(name),
                ),
            },
            Some("toml") => match load_system(path) {
                Ok(agents) => {
                    let several = agents.len() > 1;
                    let mut kept = None;
                    for p in agents {
                        let shown = if several {
                            format!("{name} ({})", p.name)
                        } else {
                            name.clone()
                        };
                        files.push(FileReport::Project(project_outline(&shown, &p)));
                        kept.get_or_insert(p.map);
                    }
                    // Keep the project's files so that later diagnostics still render.
                    if let Some(m) = kept {
                        absorb(&mut map, m);
                    }
                }
                Err(e) => {
                    // Diagnostics point into the project's own source map: re-home them.
                    let base = map.files().len() as u32;
                    absorb(&mut map, e.map);
                    diagnostics.extend(e.diagnostics.into_iter().map(|d| rebase(d, base)));
                }
            },
            _ => diagnostics.push(
                Diagnostic::error(
                    "input",
                    format!("`{name}` is not an AgentSpeak file, a Jason project, a PDDL domain or a manifest"),
                )
                .in_file(name)
                .with_help("`parse` reads `.asl`, `.mas2j`, `.pddl` and `bdi-check.toml` files"),
            ),
        }
    }
    let findings: Vec<Finding> = diagnostics
        .iter()
        .map(|d| Finding::from_input_diagnostic(d, &map))
        .collect();
    let report = ParseReport {
        tool: Tool::default(),
        command: "parse",
        verdict: verdict_of(&findings),
        files,
        findings,
    };
    ParseRun {
        map,
        diagnostics,
        report,
    }
}

/// Appends another map's files to `map` (their ids shift by `map`'s length).
fn absorb(map: &mut SourceMap, other: SourceMap) {
    for f in other.files() {
        map.add(&f.path, f.name.clone(), f.text.clone());
    }
}

/// Shifts a diagnostic's file ids by `base`, after [`absorb`].
fn rebase(mut d: Diagnostic, base: u32) -> Diagnostic {
    let shift = |s: &mut crate::syntax::Span| s.file = crate::syntax::FileId(s.file.0 + base);
    if let Some(s) = &mut d.span {
        shift(s);
    }
    for l in &mut d.secondary {
        shift(&mut l.span);
    }
    d
}

fn outline(path: &Path, agent: &crate::syntax::LoadedAgent, map: &SourceMap) -> FileOutline {
    let loc = |span| map.location(span);
    let mut o = FileOutline {
        file: path.display().to_string(),
        includes: agent
            .included
            .iter()
            .map(|i| map.file(i.file).name.clone())
            .collect(),
        beliefs: Vec::new(),
        rules: Vec::new(),
        initial_goals: Vec::new(),
        plans: Vec::new(),
    };
    for item in agent.items() {
        match item {
            Item::Belief(b) => o.beliefs.push(Entry {
                text: print_literal(&b.literal),
                location: loc(b.span),
            }),
            Item::Rule(r) => o.rules.push(Entry {
                text: format!("{} :- {}", print_literal(&r.head), print_expr(&r.body)),
                location: loc(r.span),
            }),
            Item::InitialGoal(g) => o.initial_goals.push(Entry {
                text: format!("!{}", print_literal(&g.literal)),
                location: loc(g.span),
            }),
            Item::Plan(p) => push_plan(&mut o.plans, p, map),
            // `items()` has already replaced directives by what they stand for.
            Item::Directive(_) => {}
        }
    }
    o
}

fn push_plan(out: &mut Vec<PlanOutline>, p: &Plan, map: &SourceMap) {
    out.push(PlanOutline {
        label: p.label.as_ref().and_then(|l| l.name.clone()),
        trigger: print_trigger(&p.trigger),
        context: p.context.as_ref().map(print_expr),
        body: p
            .body
            .as_ref()
            .map(|b| b.steps.iter().map(print_step).collect())
            .unwrap_or_default(),
        location: map.location(p.span),
    });
    for sub in &p.sub_plans {
        push_plan(out, sub, map);
    }
}
