//! `bdi-check replay REPORT.json [--finding ID]`: re-runs the counterexamples of a report
//! against the project as it is now. A kept report is a regression test: exit 1 while a
//! counterexample still reaches its violation, 0 once none does (SPEC §2).

use super::allow::known_check;
use super::Output;
use crate::check::explore::fingerprint;
use crate::check::trace::Builder;
use crate::model::atoms::AtomSet;
use crate::model::formula;
use crate::model::project::{load_system, Project};
use crate::report::replay::{render, Replayed};
use crate::semantics::{Note, Semantics, State};
use crate::syntax::ast::{TriggerKind, TriggerOp};
use crate::syntax::{Diagnostic, SourceMap, Span};
use serde::Deserialize;
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// `replay REPORT [--finding ID]`: exit 1 while a counterexample still reaches its
/// violation, 0 once none does, 2 when the report or project cannot be read.
pub fn command(report: &Path, finding: Option<&str>) -> Output {
    match replay(report, finding) {
        Err((map, errs)) => Output::refused(crate::report::diagnostics(&errs, &map, false)),
        Ok(Replay { results, notice }) => {
            let reached = results.iter().any(|r| r.reached);
            let mut out = Output::report(render(&results), i32::from(reached));
            out.stderr = notice;
            out
        }
    }
}

/// The outcome of a replay: one result per finding, and what the user must know about
/// the report (the project changed since it was made, or it says nothing of that).
pub struct Replay {
    /// One per replayed finding.
    pub results: Vec<Replayed>,
    /// For stderr; empty when the project is the one the report was made from.
    pub notice: String,
}

#[derive(Deserialize)]
struct ReportIn {
    project: String,
    findings: Vec<FindingIn>,
    #[serde(default)]
    tool: Option<ToolIn>,
    #[serde(default)]
    sources: Vec<SourceIn>,
}

#[derive(Deserialize)]
struct ToolIn {
    version: String,
}

#[derive(Deserialize)]
struct SourceIn {
    file: String,
    sha256: String,
}

#[derive(Deserialize)]
struct FindingIn {
    id: String,
    check: String,
    status: String,
    #[serde(default)]
    severity: String,
    #[serde(default)]
    message: String,
    location: Option<LocationIn>,
    counterexample: Option<CounterexampleIn>,
    /// Accepted on purpose (`[[allow]]`): replayed only when named.
    #[serde(default)]
    suppressed: Option<String>,
}

#[derive(Deserialize)]
struct LocationIn {
    file: String,
    line: usize,
}

#[derive(Deserialize)]
struct CounterexampleIn {
    initial: Vec<String>,
    #[serde(default)]
    steps: Vec<StepIn>,
    #[serde(default)]
    loop_start: Option<usize>,
}

#[derive(Deserialize)]
struct StepIn {
    kind: String,
    text: String,
    /// In a project of several agents, whose step it is.
    #[serde(default)]
    agent: Option<String>,
}

/// Bad input, with the files read (the report, or the project) for excerpts.
type Refusal = (SourceMap, Vec<Diagnostic>);

/// A report read, and the project it names loaded as it is now.
struct Opened {
    /// The report's path, as given.
    path: String,
    /// The report's text, for excerpts.
    map: SourceMap,
    report: ReportIn,
    project: Project,
    /// Every agent, when the project has several (`project` is the first).
    agents: Vec<Project>,
    /// For stderr: whether the project changed since the report was made.
    notice: String,
    /// The report names its files and none changed.
    unchanged: bool,
}

/// Reads a report and loads its project. Errors are bad input.
fn open(report: &Path) -> Result<Opened, Refusal> {
    let mut map = SourceMap::new();
    let bad =
        |msg: String| vec![Diagnostic::error("input", msg).in_file(report.display().to_string())];
    let text = crate::syntax::source::read_input(report).map_err(|e| {
        (
            SourceMap::new(),
            bad(format!("cannot read `{}`: {e}", report.display())),
        )
    })?;
    let id = map.add(report, report.display().to_string(), text.clone());
    let r: ReportIn = serde_json::from_str(&text).map_err(|e| {
        // serde_json counts lines and columns from 1; a span of one character there.
        let start: usize = text
            .split_inclusive('\n')
            .take(e.line().saturating_sub(1))
            .map(str::len)
            .sum::<usize>()
            + e.column().saturating_sub(1);
        let start = start.min(text.len());
        let end = (start + 1).min(text.len());
        let d = Diagnostic::error("input", format!("not a bdi-check JSON report: {e}"))
            .with_label(Span::new(id, start, end), "here");
        (map.clone(), vec![d])
    })?;
    if let Some(f) = r.findings.iter().find(|f| !known_check(&f.check)) {
        return Err((
            map,
            bad(format!(
                "the report's finding `{}` has the check `{}`, which bdi-check does not have: the report was altered, or made by another tool",
                f.id, f.check
            )),
        ));
    }
    let agents = load_system(Path::new(&r.project)).map_err(|e| (e.map, e.diagnostics))?;
    let project = agents[0].clone();
    let agents = if agents.len() > 1 { agents } else { Vec::new() };
    // What changed since the report: with its files' digests, an unchanged project must
    // give back every run (a run that no longer reaches its violation on it means the
    // report is not the one the project gave).
    let now = crate::findings::sources_of(&project.map);
    let changed: Vec<&str> = r
        .sources
        .iter()
        .filter(|s| !now.iter().any(|n| n.file == s.file && n.sha256 == s.sha256))
        .map(|s| s.file.as_str())
        .chain(
            now.iter()
                .filter(|n| !r.sources.iter().any(|s| s.file == n.file))
                .map(|n| n.file.as_str()),
        )
        .collect();
    let unchanged = !r.sources.is_empty() && changed.is_empty();
    let notice = if r.sources.is_empty() {
        "note: the report does not name the files it was made from (an older bdi-check made it): whether the project changed since is not known\n".to_string()
    } else if changed.is_empty() {
        String::new()
    } else {
        format!(
            "note: the project changed since the report was made: {}\n",
            changed.join(", ")
        )
    };
    Ok(Opened {
        path: report.display().to_string(),
        map,
        report: r,
        project,
        agents,
        notice,
        unchanged,
    })
}

/// The finding `id` of a report, if it has a run to replay (bad input otherwise: saying
/// "no longer reaches" of a finding that never had a run would call it fixed).
fn with_run<'r>(o: &'r Opened, id: &str) -> Result<&'r FindingIn, Refusal> {
    let bad = |msg: String| {
        let d = Diagnostic::error("input", msg).in_file(o.path.clone());
        (o.map.clone(), vec![d])
    };
    let Some(f) = o.report.findings.iter().find(|f| f.id == id) else {
        return Err(bad(format!("the report has no finding `{id}`")));
    };
    if let Err(why) = has_run(f) {
        return Err(bad(format!(
            "the finding `{id}` has no run to replay: {why}; run `verify` again to re-check it"
        )));
    }
    Ok(f)
}

/// The findings to replay: the one named (bad input when it has no run), or every failing
/// one with a run that is not suppressed.
fn selected<'o>(o: &'o Opened, finding: Option<&str>) -> Result<Vec<&'o FindingIn>, Refusal> {
    Ok(match finding {
        Some(id) => vec![with_run(o, id)?],
        None => o
            .report
            .findings
            .iter()
            .filter(|f| has_run(f).is_ok() && f.suppressed.is_none())
            .collect(),
    })
}

/// On a project whose files are unchanged since the report, every run must come back:
/// a lost one means the report was altered (or made by another version).
fn check_unchanged(o: &Opened, results: &[&Replayed]) -> Result<(), Refusal> {
    if !o.unchanged {
        return Ok(());
    }
    let Some(lost) = results.iter().find(|x| !x.reached) else {
        return Ok(());
    };
    let other = match o.report.tool.as_ref().map(|t| t.version.as_str()) {
        Some(v) if v != env!("CARGO_PKG_VERSION") => {
            format!(
                " (it was made by bdi-check {v}; this is {})",
                env!("CARGO_PKG_VERSION")
            )
        }
        _ => String::new(),
    };
    let d = Diagnostic::error(
        "input",
        format!(
            "the report does not match the project it was made from: its files are unchanged, yet `{}` no longer reaches its violation ({}){other}; the report was altered",
            lost.id, lost.detail
        ),
    );
    Err((o.map.clone(), vec![d.in_file(o.path.clone())]))
}

/// Replays the failing findings of a report (or the one named). Errors are bad input.
pub fn replay(report: &Path, finding: Option<&str>) -> Result<Replay, Refusal> {
    let o = open(report)?;
    if !o.agents.is_empty() {
        return replay_system(&o, finding);
    }
    let sem = Semantics::new(&o.project).map_err(|d| (o.project.map.clone(), d))?;
    let results: Vec<Replayed> = selected(&o, finding)?
        .into_iter()
        .map(|f| replay_one(&o.project, &sem, f, &mut Vec::new()))
        .collect();
    check_unchanged(&o, &results.iter().collect::<Vec<_>>())?;
    Ok(Replay {
        results,
        notice: o.notice,
    })
}

/// One transition of a replayed run: what it showed and the agent's state after it.
pub struct Walked {
    /// The transition's notes.
    pub notes: Vec<Note>,
    /// The state it led to.
    pub state: State,
}

/// A finding's run as replayed on the project as it is now.
pub struct Walk<'a> {
    /// The finding's id, check and message, as the report gives them.
    pub id: &'a str,
    /// Its check.
    pub check: &'a str,
    /// Its message.
    pub message: &'a str,
    /// The state the run starts from.
    pub initial: State,
    /// The transitions taken, in order.
    pub walked: Vec<Walked>,
    /// Whether it still reaches its violation.
    pub result: Replayed,
}

/// Replays the finding `id` of a report and hands its run to `f` with the project it ran
/// on (`bdi-check trace`); also returns the notice for stderr. Errors are bad input.
pub fn walk<R>(
    report: &Path,
    id: &str,
    f: impl FnOnce(&Project, &Semantics, &Walk) -> R,
) -> Result<(R, String), Refusal> {
    let o = open(report)?;
    if !o.agents.is_empty() {
        let d = Diagnostic::error(
            "input",
            "`trace` of a project of several agents is not supported yet; `replay` re-runs its counterexamples",
        );
        return Err((o.map.clone(), vec![d.in_file(o.path.clone())]));
    }
    let sem = Semantics::new(&o.project).map_err(|d| (o.project.map.clone(), d))?;
    let finding = with_run(&o, id)?;
    let mut walked = Vec::new();
    let result = replay_one(&o.project, &sem, finding, &mut walked);
    check_unchanged(&o, &[&result])?;
    let Some(initial) = initial_state(&o.project, &sem, finding) else {
        // `replay_one` found none either: nothing was walked.
        let d = Diagnostic::error(
            "input",
            format!("`{id}` cannot be traced: {}", result.detail),
        );
        return Err((o.map.clone(), vec![d.in_file(o.path.clone())]));
    };
    let w = Walk {
        id: &finding.id,
        check: &finding.check,
        message: &finding.message,
        initial,
        walked,
        result,
    };
    Ok((f(&o.project, &sem, &w), o.notice.clone()))
}

/// Whether a finding comes with a run that reaches its violation, or why not: a note
/// is a state no run reaches, a warning of the static checks a state lint found that no
/// run was seen to reach (only an error of theirs carries a run), and a passing finding
/// has nothing to reach.
fn has_run(f: &FindingIn) -> Result<(), &'static str> {
    if f.status != "fail" {
        return Err("it does not fail");
    }
    if f.counterexample.is_none() {
        return Err("it has no counterexample (a static finding)");
    }
    if f.severity == "note" {
        return Err("it is a note: no run reaches it");
    }
    let check = f.check.as_str();
    let steps = f.counterexample.as_ref().map_or(0, |c| c.steps.len());
    if STATIC_WITNESSES.contains(&check) {
        // Lint's own witness is a state (no steps); a run `verify` saw has steps.
        if f.severity != "error" || steps == 0 {
            return Err(
                "its counterexample is a state the static checks found, which no run was seen to reach",
            );
        }
    } else if crate::smt::lint::CHECKS.contains(&check) {
        return Err("it is a static finding: its counterexample is a state, not a run");
    }
    Ok(())
}

/// Static checks whose counterexample is a run once `verify` saw one reach it (the
/// finding is then an error, and its counterexample has steps).
const STATIC_WITNESSES: &[&str] = &["precondition", "coverage-gap", "action-breaks-invariant"];

/// The initial state a finding's run starts from, or why the project no longer has it.
fn start_of(project: &Project, sem: &Semantics, f: &FindingIn) -> Result<State, &'static str> {
    let atoms = initial_atoms(project, f)?;
    sem.initial_states()
        .into_iter()
        .find(|s| s.beliefs == atoms)
        .ok_or("its initial state is no longer an initial state of the project")
}

/// The atoms true at the start of a finding's run, or why the project no longer has them.
fn initial_atoms(project: &Project, f: &FindingIn) -> Result<AtomSet, &'static str> {
    let Some(c) = &f.counterexample else {
        return Err("the finding has no counterexample");
    };
    let mut atoms = AtomSet::empty(project.atoms.len());
    let names: HashSet<&str> = c.initial.iter().map(String::as_str).collect();
    for a in 0..project.atoms.len() as u32 {
        let a = crate::model::atoms::AtomId(a);
        if names.contains(project.atoms.display(a, &project.universe).as_str()) {
            atoms.insert(a);
        }
    }
    if atoms.count() != names.len() {
        return Err("its initial state mentions atoms the project no longer has");
    }
    Ok(atoms)
}

/// The initial state of a finding's run, if the project still has it.
fn initial_state(project: &Project, sem: &Semantics, f: &FindingIn) -> Option<State> {
    start_of(project, sem, f).ok()
}

/// Replays one finding's run, appending each transition taken to `walked`.
fn replay_one(
    project: &Project,
    sem: &Semantics,
    f: &FindingIn,
    walked: &mut Vec<Walked>,
) -> Replayed {
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let mut state = match start_of(project, sem, f) {
        Ok(s) => s,
        Err(why) => return no(why),
    };
    let Some(c) = &f.counterexample else {
        return no("the finding has no counterexample");
    };
    if crate::check::explanation::CHECKS.contains(&f.check.as_str()) {
        return replay_explained(project, sem, f, c, state, walked);
    }
    if f.check == "property" {
        if let Some(p) = run_property(project, f) {
            if p.user.is_some() {
                return replay_run_explained(project, sem, f, c, &p, state);
            }
            return replay_run(project, sem, f, c, &p, state, walked);
        }
    }
    let check = Check::of(project, f, &[]);
    let mut builder = Builder::new(project, sem);
    let mut seen: HashSet<u64> = HashSet::from([fingerprint(&state)]);
    let recorded: Vec<(&str, &str)> = c
        .steps
        .iter()
        .map(|s| (s.kind.as_str(), s.text.as_str()))
        .collect();
    let loop_len = c
        .loop_start
        .map(|l| recorded.len().saturating_sub(l))
        .unwrap_or(0);
    // Follow the recorded steps while the current project produces them, then let the
    // agent run on (as far as the recorded run went, plus a loop's length) to see whether
    // the violation still happens.
    let budget = recorded.len() + loop_len + 64;
    let next = |s: &State| -> Vec<(Vec<Note>, State)> {
        sem.successors(s)
            .into_iter()
            .map(|t| (t.notes, t.next))
            .collect()
    };
    let run = find_run(&state, &recorded, &next, &|n: &Vec<Note>| {
        shown(project, sem, n)
    });
    let followed = run.as_ref().map_or(0, Vec::len);
    let budget = budget + followed;
    for turn in 0..budget {
        if check.settles(&state) {
            return no("the property now holds on this run");
        }
        // The user may stop asking at any point: a run of an `eventually` property may end
        // where the agent is idle, once the recorded run is followed.
        if matches!(check, Check::Eventually(_)) && state.is_idle() && turn >= followed {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!(
                    "the run ends after {} steps without the property (the agent idle, the user asking nothing more)",
                    builder.steps().len()
                ),
            };
        }
        if check.state_violated(&state) {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {} steps", builder.steps().len()),
            };
        }
        let succ = sem.successors(&state);
        if succ.is_empty() {
            if matches!(check, Check::Deadlock) && !state.is_idle() {
                return Replayed {
                    id: f.id.clone(),
                    reached: true,
                    detail: format!("the agent is stuck after {} steps", builder.steps().len()),
                };
            }
            if matches!(check, Check::Eventually(_)) {
                return Replayed {
                    id: f.id.clone(),
                    reached: true,
                    detail: format!(
                        "the run ends after {} steps without the property",
                        builder.steps().len()
                    ),
                };
            }
            break;
        }
        let at = builder.steps().len();
        let pick = match run.as_ref().and_then(|r| r.get(turn)) {
            Some(&k) => k,
            // The recorded run is over, or the project no longer gives it: follow it as
            // far as it goes, then the first successor.
            None => succ
                .iter()
                .position(|t| follows(project, sem, &t.notes, &recorded[at.min(recorded.len())..]))
                .unwrap_or(0),
        };
        let t = &succ[pick];
        walked.push(Walked {
            notes: t.notes.clone(),
            state: t.next.clone(),
        });
        if t.notes.iter().any(|n| check.note_violates(n, project)) {
            builder.push(t.notes.clone());
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {} steps", builder.steps().len()),
            };
        }
        builder.push(t.notes.clone());
        state = t.next.clone();
        if !seen.insert(fingerprint(&state)) && check.is_liveness() {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("the run loops again after {} steps", builder.steps().len()),
            };
        }
    }
    no("the run no longer reaches the violation")
}

/// The finding's property, when it is decided on runs (`ltl`, or a modality).
fn run_property(project: &Project, f: &FindingIn) -> Option<crate::model::property::RunProperty> {
    let name = f.id.strip_prefix("property:")?;
    let (props, _) = crate::model::property::compile(project).ok()?;
    props.into_iter().find(|p| p.name == name)
}

/// Replays a finding of a property decided on runs: follows the recorded steps, then
/// closes the run into a lasso (the recorded loop when the run comes back to its entry;
/// otherwise the run ends where the agent is idle or stuck, or goes on by first successors
/// until a state repeats), and decides the formula on that lasso with LTL's own semantics
/// (not the automaton the search used).
fn replay_run(
    project: &Project,
    sem: &Semantics,
    f: &FindingIn,
    c: &CounterexampleIn,
    p: &crate::model::property::RunProperty,
    start: State,
    walked: &mut Vec<Walked>,
) -> Replayed {
    use crate::check::runs::RunAtoms;
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    if p.kind == crate::syntax::manifest::PropertyKind::Reachable {
        return no("a `reachable` property's run is a witness, not a violation");
    }
    let Ok((_, atomics)) = crate::model::property::compile(project) else {
        return no("the project's properties no longer compile");
    };
    let atoms = RunAtoms::new(&atomics, sem);
    let recorded: Vec<(&str, &str)> = c
        .steps
        .iter()
        .map(|s| (s.kind.as_str(), s.text.as_str()))
        .collect();
    let next = |s: &State| -> Vec<(Vec<Note>, State)> {
        sem.successors(s)
            .into_iter()
            .map(|t| (t.notes, t.next))
            .collect()
    };
    let picks = find_run(&start, &recorded, &next, &|n: &Vec<Note>| {
        shown(project, sem, n)
    })
    .unwrap_or_default();
    let lasso = close_lasso(
        start,
        &picks,
        &next,
        &|s: &State, succ: usize| s.is_idle() || succ == 0,
        &|s: &State| atoms.state_letter(s),
        &|n: &Vec<Note>| atoms.step_letter(0, n.iter()),
        &mut |n: &Vec<Note>, s: &State| {
            walked.push(Walked {
                notes: n.clone(),
                state: s.clone(),
            })
        },
    );
    decide_lasso(f, p, lasso)
}

/// Replays a run property about a user's explanations (`explained`) on that user's
/// explanation search, as [`replay_run`] does on the agent's.
fn replay_run_explained(
    project: &Project,
    sem: &Semantics,
    f: &FindingIn,
    c: &CounterexampleIn,
    p: &crate::model::property::RunProperty,
    start: State,
) -> Replayed {
    use crate::check::explanation::{Explained, ExplainedState};
    use crate::check::model::Model;
    use crate::check::runs::RunAtoms;
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(user) = p.user.as_deref() else {
        return no("the property names no user");
    };
    let (Ok(users), Ok((_, atomics))) = (
        crate::explain::agent::users(project, Some(user)),
        crate::model::property::compile(project),
    ) else {
        return no("the project no longer has the property's user or properties");
    };
    let atoms = RunAtoms::new(&atomics, sem);
    let ex = crate::explain::agent::Explainer::new(project, sem);
    let model = Explained::new(sem, &ex, &users[0], None);
    let Some(first) = model.init_states().find(|s| s.state == start) else {
        return no("its initial state is no longer an initial state of the project");
    };
    // Explanations are the checker's: follow the agent's steps only.
    let recorded: Vec<(&str, &str)> = c
        .steps
        .iter()
        .filter(|s| s.kind != "explanation")
        .map(|s| (s.kind.as_str(), s.text.as_str()))
        .collect();
    let next = |s: &ExplainedState| model.next_states(s);
    let picks = find_run(&first, &recorded, &next, &|step: &ExplainedStep| {
        shown(project, sem, &step.notes)
    })
    .unwrap_or_default();
    let step_letter = |l: &ExplainedStep| atoms.explained_step_letter(l);
    let lasso = close_lasso(
        first,
        &picks,
        &next,
        &|s: &ExplainedState, succ: usize| s.state.is_idle() || succ == 0,
        &|s: &ExplainedState| atoms.state_letter(&s.state),
        &step_letter,
        &mut |_, _| {},
    );
    decide_lasso(f, p, lasso)
}

/// Most steps a replayed run of a run property is extended by (first successors) to close
/// a loop after its recorded steps.
const MAX_EXTENSION: usize = 10_000;

/// A run of a run property replayed: from `start`, the transitions `picks` (positions among
/// `next`'s), then closed into a lasso: the run comes back to a state it was in (the
/// recorded loop), or ends where `ends` says a run may (it repeats its last state), or goes
/// on by first successors until a state repeats. The letters of its positions (each
/// state's with its step's) and the position the repetition starts at.
#[allow(clippy::type_complexity)]
fn close_lasso<S: Clone + std::hash::Hash, L>(
    start: S,
    picks: &[usize],
    next: &dyn Fn(&S) -> Vec<(L, S)>,
    ends: &dyn Fn(&S, usize) -> bool,
    letter: &dyn Fn(&S) -> crate::check::runs::Letter,
    step: &dyn Fn(&L) -> Option<crate::check::runs::Letter>,
    on_step: &mut dyn FnMut(&L, &S),
) -> Result<(Vec<crate::check::runs::Letter>, usize), &'static str> {
    let mut letters = vec![letter(&start)];
    let mut seen: HashMap<u64, usize> = HashMap::from([(fingerprint(&start), 0)]);
    let mut state = start;
    let mut taken = 0usize;
    let followed = picks.len();
    loop {
        let mut succ = next(&state);
        let pick = match picks.get(taken) {
            Some(&k) => k,
            None => {
                if ends(&state, succ.len()) {
                    // The run ends here and stays: its last state repeats.
                    letters.push(letter(&state));
                    let at = letters.len() - 1;
                    return Ok((letters, at));
                }
                if taken >= followed + MAX_EXTENSION {
                    return Err("the run does not close into a loop within the replay's bound");
                }
                0
            }
        };
        if pick >= succ.len() {
            return Err("the recorded run is no longer possible");
        }
        let (label, t) = succ.swap_remove(pick);
        let mut l = letter(&t);
        if let Some(d) = step(&label) {
            for (w, x) in l.iter_mut().zip(d) {
                *w |= x;
            }
        }
        letters.push(l);
        on_step(&label, &t);
        state = t;
        taken += 1;
        let fp = fingerprint(&state);
        if let Some(&e) = seen.get(&fp) {
            if taken >= followed {
                // Back in the state of position `e`: from here the run repeats positions
                // e+1 ..= this one (the step into this one is the loop's last).
                return Ok((letters, e + 1));
            }
        }
        seen.entry(fp).or_insert(letters.len() - 1);
    }
}

/// Whether the replayed lasso violates the run property.
fn decide_lasso(
    f: &FindingIn,
    p: &crate::model::property::RunProperty,
    lasso: Result<(Vec<crate::check::runs::Letter>, usize), &'static str>,
) -> Replayed {
    let (letters, loop_at) = match lasso {
        Ok(x) => x,
        Err(why) => return Replayed::missed(&f.id, why),
    };
    match crate::check::runs::violated_on(p, &letters, loop_at) {
        Some(binding) => Replayed {
            id: f.id.clone(),
            reached: true,
            detail: if binding.is_empty() {
                format!("violated on a run of {} steps", letters.len() - 1)
            } else {
                format!(
                    "violated for {binding} on a run of {} steps",
                    letters.len() - 1
                )
            },
        },
        None => Replayed::missed(&f.id, "the property now holds on this run"),
    }
}

/// Replays an explanation finding: the run as the finding's user sees it (the id is
/// `check:user:file:line`), until a transition violates the same property at the same place.
fn replay_explained(
    project: &Project,
    sem: &Semantics,
    f: &FindingIn,
    c: &CounterexampleIn,
    agent: State,
    walked: &mut Vec<Walked>,
) -> Replayed {
    use crate::check::explanation::Explained;
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(user_name) = f.id.split(':').nth(1) else {
        return no("the finding's id names no user");
    };
    let Ok(users) = crate::explain::agent::users(project, Some(user_name)) else {
        return no("the project no longer has the finding's user");
    };
    let ex = crate::explain::agent::Explainer::new(project, sem);
    let model = Explained::new(sem, &ex, &users[0], None);
    // Explanations are the checker's, not the agent's: follow the agent's steps only.
    let recorded: Vec<(&str, &str)> = c
        .steps
        .iter()
        .filter(|s| s.kind != "explanation")
        .map(|s| (s.kind.as_str(), s.text.as_str()))
        .collect();
    let shown = |step: &ExplainedStep| shown(project, sem, &step.notes);
    replay_explained_in(
        project,
        &model,
        f,
        agent,
        &recorded,
        &shown,
        |step, next| {
            walked.push(Walked {
                notes: step.notes.clone(),
                state: next.state.clone(),
            })
        },
    )
}

/// Replays an explanation finding of a project of several agents: the run as the
/// finding's user, watching the robot, sees it, every step by its agent.
fn replay_system_explained(
    agents: &[Project],
    system: &crate::semantics::System,
    f: &FindingIn,
    c: &CounterexampleIn,
    start: crate::semantics::SystemState,
) -> Replayed {
    use crate::check::explanation::{robot_of, Among, Explained};
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(user_name) = f.id.split(':').nth(1) else {
        return no("the finding's id names no user");
    };
    let robot = robot_of(agents);
    let project = &agents[robot];
    let Ok(users) = crate::explain::agent::users(project, Some(user_name)) else {
        return no("the project no longer has the finding's user");
    };
    let ex = crate::explain::agent::Explainer::new(project, &system.agents[robot]);
    let model = Explained::watching(Among { system, robot }, &ex, &users[0]);
    let kinds: Vec<String> = c
        .steps
        .iter()
        .filter(|s| s.kind != "explanation")
        .map(|s| format!("{}:{}", s.agent.as_deref().unwrap_or(""), s.kind))
        .collect();
    let recorded: Vec<(&str, &str)> = kinds
        .iter()
        .zip(c.steps.iter().filter(|s| s.kind != "explanation"))
        .map(|(k, s)| (k.as_str(), s.text.as_str()))
        .collect();
    let shown = |step: &ExplainedStep| {
        let k = step.agent as usize;
        let name = &system.names()[k];
        let mut b = Builder::new(&agents[k], &system.agents[k]);
        b.push(step.notes.clone());
        b.steps()
            .iter()
            .map(|s| (format!("{name}:{}", s.kind.name()), s.text.clone()))
            .collect()
    };
    replay_explained_in(project, &model, f, start, &recorded, &shown, |_, _| {})
}

/// [`replay_run_explained`] among several agents: on the user's explanation search of
/// every interleaving. (The loop's fairness to the agents is the search's; it is not
/// checked again here.)
fn replay_system_run_explained(
    agents: &[Project],
    system: &crate::semantics::System,
    f: &FindingIn,
    c: &CounterexampleIn,
    p: &crate::model::property::RunProperty,
    start: crate::semantics::SystemState,
) -> Replayed {
    use crate::check::explanation::{robot_of, Among, Explained, ExplainedState};
    use crate::check::model::Model;
    use crate::check::runs::RunAtoms;
    use crate::semantics::SystemState;
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(user) = p.user.as_deref() else {
        return no("the property names no user");
    };
    let robot = robot_of(agents);
    let (Ok(users), Ok((_, atomics))) = (
        crate::explain::agent::users(&agents[robot], Some(user)),
        crate::model::property::compile_in(&agents[0], system.names()),
    ) else {
        return no("the project no longer has the property's user or properties");
    };
    let atoms = RunAtoms::new(&atomics, &system.agents[0]);
    let ex = crate::explain::agent::Explainer::new(&agents[robot], &system.agents[robot]);
    let model = Explained::watching(Among { system, robot }, &ex, &users[0]);
    let Some(first) = model.init_states().find(|s| s.state == start) else {
        return no("its initial state is no longer an initial state of the project");
    };
    let kinds: Vec<String> = c
        .steps
        .iter()
        .filter(|s| s.kind != "explanation")
        .map(|s| format!("{}:{}", s.agent.as_deref().unwrap_or(""), s.kind))
        .collect();
    let recorded: Vec<(&str, &str)> = kinds
        .iter()
        .zip(c.steps.iter().filter(|s| s.kind != "explanation"))
        .map(|(k, s)| (k.as_str(), s.text.as_str()))
        .collect();
    let shown = |step: &ExplainedStep| {
        let k = step.agent as usize;
        let name = &system.names()[k];
        let mut b = Builder::new(&agents[k], &system.agents[k]);
        b.push(step.notes.clone());
        b.steps()
            .iter()
            .map(|s| (format!("{name}:{}", s.kind.name()), s.text.clone()))
            .collect()
    };
    let next = |s: &ExplainedState<SystemState>| model.next_states(s);
    let picks = find_run(&first, &recorded, &next, &shown).unwrap_or_default();
    let step_letter = |l: &ExplainedStep| atoms.explained_step_letter(l);
    let done = |s: &ExplainedState<SystemState>, succ: usize| {
        succ == 0
            || (s.state.agents.iter().all(|a| a.is_idle())
                && s.state.mail.iter().all(|m| m.is_empty()))
    };
    let lasso = close_lasso(
        first,
        &picks,
        &next,
        &done,
        &|s: &ExplainedState<SystemState>| {
            atoms.system_letter(&system.everything(&s.state), &s.state.agents)
        },
        &step_letter,
        &mut |_, _| {},
    );
    decide_lasso(f, p, lasso)
}

/// A transition of the runs as a user sees them.
type ExplainedStep = crate::check::explanation::Step;

/// Follows the recorded run (`recorded`, explanations left out) from `start` on `model`,
/// then lets it run on, until a transition violates the finding's property at its place.
/// `shown`: the steps a transition shows, as the report records them; `on_step`: each
/// transition taken, with the state it leads to.
fn replay_explained_in<W: crate::check::explanation::Runs<Notes = Vec<Note>>>(
    project: &Project,
    model: &crate::check::explanation::Explained<W>,
    f: &FindingIn,
    start: W::State,
    recorded: &[(&str, &str)],
    shown: &dyn Fn(&ExplainedStep) -> Vec<(String, String)>,
    mut on_step: impl FnMut(&ExplainedStep, &crate::check::explanation::ExplainedState<W::State>),
) -> Replayed {
    use crate::check::model::Model;
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(mut state) = model.init_states().into_iter().find(|s| s.state == start) else {
        return no("its initial state is no longer an initial state of the project");
    };
    let place = f.location.as_ref().map(|l| (l.file.as_str(), l.line));
    let mut seen: HashSet<u64> = HashSet::from([fingerprint(&state)]);
    let next = |s: &crate::check::explanation::ExplainedState<W::State>| model.next_states(s);
    let run = find_run(&state, recorded, &next, shown);
    // Steps shown so far.
    let mut at = 0;
    for turn in 0..recorded.len() + 64 + run.as_ref().map_or(0, Vec::len) {
        let succ = model.next_states(&state);
        if succ.is_empty() {
            break;
        }
        let pick = match run.as_ref().and_then(|r| r.get(turn)) {
            Some(&k) => k,
            None => {
                let rest = &recorded[at.min(recorded.len())..];
                succ.iter()
                    .position(|(step, _)| {
                        let steps = shown(step);
                        !steps.is_empty()
                            && steps.iter().enumerate().all(|(i, (kind, text))| {
                                rest.get(i).is_some_and(|(k, t)| kind == k && text == t)
                            })
                    })
                    .unwrap_or(0)
            }
        };
        let (step, next) = succ.into_iter().nth(pick).expect("a successor was picked");
        at += shown(&step).len();
        on_step(&step, &next);
        let hit = step.violations.iter().any(|v| {
            let loc = project.map.location(v.span);
            v.check == f.check
                && place.is_none_or(|(file, line)| loc.file == file && loc.line == line)
        });
        if hit {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {at} steps"),
            };
        }
        state = next;
        if !seen.insert(fingerprint(&state)) {
            break;
        }
    }
    no("the run no longer reaches the violation")
}

/// Most transitions in a row that show no step (a cycle whose act only posts a subgoal,
/// say) which a recorded run may hide between two of its steps.
const MAX_SILENT: usize = 4;

/// A state's successors with their labels.
type Next<'a, S, L> = &'a dyn Fn(&S) -> Vec<(L, S)>;
/// The steps a label shows, as `(kind, text)`.
type Shown<'a, L> = &'a dyn Fn(&L) -> Vec<(String, String)>;

/// The successor to take at each transition so that the run shows exactly the recorded
/// steps, silent transitions taken where the recording hides them (a depth-first search:
/// a request and a silent cycle may both fit the next step, and only the rest of the run
/// tells them apart). `None` when the project no longer gives that run.
fn find_run<S: Clone, L>(
    start: &S,
    recorded: &[(&str, &str)],
    next: Next<'_, S, L>,
    shown: Shown<'_, L>,
) -> Option<Vec<usize>> {
    fn go<S: Clone, L>(
        s: &S,
        pos: usize,
        silent: usize,
        recorded: &[(&str, &str)],
        next: Next<'_, S, L>,
        shown: Shown<'_, L>,
        path: &mut Vec<usize>,
    ) -> bool {
        if pos == recorded.len() {
            return true;
        }
        for (k, (label, t)) in next(s).into_iter().enumerate() {
            let steps = shown(&label);
            let fits = steps.len() <= recorded.len() - pos
                && steps
                    .iter()
                    .zip(&recorded[pos..])
                    .all(|((a, b), (c, d))| a == c && b == d);
            if !fits || (steps.is_empty() && silent == MAX_SILENT) {
                continue;
            }
            path.push(k);
            let silent = if steps.is_empty() { silent + 1 } else { 0 };
            if go(&t, pos + steps.len(), silent, recorded, next, shown, path) {
                return true;
            }
            path.pop();
        }
        false
    }
    let mut path = Vec::new();
    go(start, 0, 0, recorded, next, shown, &mut path).then_some(path)
}

/// The steps notes show, as `(kind, text)`.
fn shown(project: &Project, sem: &Semantics, notes: &[Note]) -> Vec<(String, String)> {
    let mut b = Builder::new(project, sem);
    b.push(notes.to_vec());
    b.steps()
        .iter()
        .map(|s| (s.kind.name().to_string(), s.text.clone()))
        .collect()
}

/// Whether a transition's notes render as the next recorded steps (`(kind, text)`).
fn follows(project: &Project, sem: &Semantics, notes: &[Note], recorded: &[(&str, &str)]) -> bool {
    let mut b = Builder::new(project, sem);
    b.push(notes.to_vec());
    let steps = b.steps();
    !steps.is_empty()
        && steps.iter().enumerate().all(|(i, s)| {
            recorded
                .get(i)
                .is_some_and(|(k, text)| s.kind.name() == *k && s.text == *text)
        })
}

/// What counts as reaching a finding's violation.
enum Check {
    State(crate::model::cond::Cond, bool),
    /// `eventually p`: violated by a run that ends or loops while `p` never held.
    Eventually(crate::model::cond::Cond),
    Note {
        kind: &'static str,
        place: Option<(String, usize)>,
    },
    /// `coverage-gap`: an event for the goal of the plans at this place has no
    /// applicable plan.
    Coverage(Option<(TriggerOp, TriggerKind, String, usize)>),
    /// `deadlock`: a state with no step that is not a finished run.
    Deadlock,
    Liveness,
    Unknown,
}

impl Check {
    /// `agents`: with several, the agents a formula may name (`agent::b`).
    fn of(project: &Project, f: &FindingIn, agents: &[String]) -> Check {
        let place = f.location.as_ref().map(|l| (l.file.clone(), l.line));
        let name = f.id.split_once(':').map_or("", |(_, n)| n);
        match f.check.as_str() {
            "action-failure" => Check::Note {
                kind: "action",
                place,
            },
            "goal-failure" => Check::Note {
                kind: "goal",
                place,
            },
            // A precondition that does not hold, reached: the action fails there.
            "precondition" => Check::Note {
                kind: "action",
                place,
            },
            "coverage-gap" => Check::Coverage(place.and_then(|(file, line)| {
                let p = project.plans.plans.iter().find(|p| {
                    let loc = project.map.location(p.span);
                    loc.file == file && loc.line == line
                })?;
                let t = &p.trigger;
                Some((
                    t.op,
                    t.kind,
                    t.literal.functor()?.to_string(),
                    t.literal.arity(),
                ))
            })),
            "deadlock" => Check::Deadlock,
            // The invariants the action breaks are named in the message (`name`): the run
            // reaches the violation when one of them is false.
            "action-breaks-invariant" => {
                let named: Vec<crate::model::cond::Cond> = project
                    .invariants
                    .iter()
                    .filter(|(n, _)| f.message.contains(&format!("`{n}`")))
                    .map(|(_, c)| c.clone())
                    .collect();
                if named.is_empty() {
                    Check::Unknown
                } else {
                    Check::State(crate::model::cond::Cond::and(named), true)
                }
            }
            "livelock" | "request-not-completed" => Check::Liveness,
            "invariant" => project
                .invariants
                .iter()
                .find(|(n, _)| n == name)
                .map_or(Check::Unknown, |(_, c)| Check::State(c.clone(), true)),
            "property" => {
                let Some(p) = project
                    .manifest
                    .properties
                    .iter()
                    .find(|p| p.name.value == name)
                else {
                    return Check::Unknown;
                };
                match (
                    p.kind,
                    formula::compile_in(&p.formula.expr, &project.atoms, &project.universe, agents),
                ) {
                    (crate::syntax::manifest::PropertyKind::Always, Ok(c)) => Check::State(c, true),
                    (crate::syntax::manifest::PropertyKind::Eventually, Ok(c)) => {
                        Check::Eventually(c)
                    }
                    _ => Check::Unknown,
                }
            }
            _ => Check::Unknown,
        }
    }

    fn is_liveness(&self) -> bool {
        matches!(self, Check::Liveness | Check::Eventually(_))
    }

    /// For `eventually p`: whether `p` holds in `s` (which settles the run as not violating).
    fn settles(&self, s: &State) -> bool {
        matches!(self, Check::Eventually(c) if c.eval(&s.beliefs))
    }

    fn state_violated(&self, s: &State) -> bool {
        self.atoms_violate(&s.beliefs)
    }

    /// Whether a state with these atoms violates the finding's state property.
    fn atoms_violate(&self, atoms: &AtomSet) -> bool {
        match self {
            Check::State(c, must_hold) => c.eval(atoms) != *must_hold,
            _ => false,
        }
    }

    /// A failure of the finding's kind at the finding's place (`file:line`).
    fn note_violates(&self, n: &Note, project: &Project) -> bool {
        if let (Check::Coverage(goal), Note::NoApplicablePlan(t)) = (self, n) {
            return goal.as_ref().is_some_and(|(op, kind, f, arity)| {
                t.op == *op
                    && t.kind == *kind
                    && t.literal.functor() == Some(f.as_str())
                    && t.literal.arity() == *arity
            });
        }
        let Check::Note { kind, place } = self else {
            return false;
        };
        let span = match (*kind, n) {
            ("action", Note::ActionFailed { span, .. }) => Some(*span),
            ("goal", Note::GoalFailed { span, .. }) => *span,
            _ => return false,
        };
        match (place, span) {
            (Some((file, line)), Some(sp)) => {
                let loc = project.map.location(sp);
                &loc.file == file && loc.line == *line
            }
            // A failure with no step to point at is located at the manifest: any such
            // failure of this kind counts.
            _ => true,
        }
    }
}

/// Replays the failing findings of a report of several agents (or the one named): each
/// run is followed as recorded, every step by its agent, then checked for its violation.
fn replay_system(o: &Opened, finding: Option<&str>) -> Result<Replay, Refusal> {
    let system =
        crate::semantics::System::new(&o.agents).map_err(|d| (o.project.map.clone(), d))?;
    let results: Vec<Replayed> = selected(o, finding)?
        .into_iter()
        .map(|f| replay_system_one(&o.agents, &system, f))
        .collect();
    check_unchanged(o, &results.iter().collect::<Vec<_>>())?;
    Ok(Replay {
        results,
        notice: o.notice.clone(),
    })
}

/// Whether a run among several agents (its `states`, one more than its `labels`; `before`:
/// how many trace steps come before each transition) still shows the finding's violation
/// that goes on for ever: a loop back to the state it starts in (at trace step
/// `loop_start`) that is fair to every agent (one that can move in each of its states
/// moves in it), in which the agent is busy and moves (`livelock`), the request stays
/// pending (`request-not-completed`), and along which the property never held
/// (`eventually`; or a run that ends there).
fn system_lasso(
    system: &crate::semantics::System,
    f: &FindingIn,
    check: &Check,
    states: &[crate::semantics::SystemState],
    labels: &[crate::semantics::Step],
    before: &[usize],
    loop_start: Option<usize>,
) -> Result<(), &'static str> {
    use crate::semantics::Note;
    let last = states.last().expect("a state");
    let name = f.id.split_once(':').map_or("", |(_, n)| n);
    let never =
        |c: &crate::model::cond::Cond| states.iter().all(|s| !c.eval(&system.everything(s)));
    let Some(ls) = loop_start else {
        // An `eventually` property may fail on a run that ends.
        return match check {
            // Where every agent is done the user may stop asking: the run may end there.
            Check::Eventually(c)
                if (system.successors(last).is_empty()
                    || (last.agents.iter().all(|a| a.is_idle())
                        && last.mail.iter().all(|m| m.is_empty())))
                    && never(c) =>
            {
                Ok(())
            }
            _ => Err("the run no longer reaches the violation"),
        };
    };
    let t0 = (0..labels.len())
        .find(|&t| before[t] == ls && states[t] == *last)
        .ok_or("the run no longer goes round its loop")?;
    let lo = &states[t0..];
    let moves = &labels[t0..];
    let mover = |l: &crate::semantics::Step| match l.notes.as_slice() {
        [Note::Request { .. }] => None,
        _ => Some(l.agent as usize),
    };
    // Fair to every agent (unless the manifest leaves that out).
    let fair = system
        .agents
        .first()
        .is_none_or(|a| a.project.manifest.bounds.fair_agents);
    for j in (0..system.names().len()).filter(|_| fair) {
        let always = lo.iter().all(|s| {
            system
                .successors(s)
                .iter()
                .any(|(l, _)| mover(l) == Some(j))
        });
        if always && !moves.iter().any(|l| mover(l) == Some(j)) {
            return Err("its loop leaves out an agent that could move");
        }
    }
    let holds = match check {
        Check::Eventually(c) => never(c),
        _ if f.check == "livelock" => match system.names().iter().position(|n| n == name) {
            Some(k) => {
                lo.iter()
                    .all(|s| !s.agents[k].is_idle() || !s.mail[k].is_empty())
                    && moves.iter().any(|l| mover(l) == Some(k))
            }
            None => false,
        },
        _ => match system.agents[0]
            .requests
            .iter()
            .position(|g| g.to_string() == name)
        {
            Some(r) => lo
                .iter()
                .all(|s| s.agents[0].pending_requests() >> r & 1 == 1),
            None => false,
        },
    };
    if holds {
        Ok(())
    } else {
        Err("the run no longer reaches the violation")
    }
}

/// The finding's property, when it is decided on runs, in a project of several agents.
fn system_run_property(
    project: &Project,
    system: &crate::semantics::System,
    f: &FindingIn,
) -> Option<crate::model::property::RunProperty> {
    let name = f.id.strip_prefix("property:")?;
    let (props, _) = crate::model::property::compile_in(project, system.names()).ok()?;
    props.into_iter().find(|p| p.name == name)
}

/// [`replay_run`] among several agents: the recorded steps (`picks`), closed into a lasso
/// (the recorded loop, which must be fair to the agents when the manifest assumes so; else
/// the run ends where every agent is done or nothing can happen; else it goes on by first
/// successors until a state repeats), decided by LTL's own semantics.
fn replay_system_run(
    system: &crate::semantics::System,
    f: &FindingIn,
    c: &CounterexampleIn,
    p: &crate::model::property::RunProperty,
    start: crate::semantics::SystemState,
    picks: &[usize],
    shown: &dyn Fn(&crate::semantics::Step) -> Vec<(String, String)>,
) -> Replayed {
    use crate::check::runs::{violated_on, RunAtoms};
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    if p.kind == crate::syntax::manifest::PropertyKind::Reachable {
        return no("a `reachable` property's run is a witness, not a violation");
    }
    let project = system.agents[0].project;
    let Ok((_, atomics)) = crate::model::property::compile_in(project, system.names()) else {
        return no("the project's properties no longer compile");
    };
    let atoms = RunAtoms::new(&atomics, &system.agents[0]);
    let letter =
        |s: &crate::semantics::SystemState| atoms.system_letter(&system.everything(s), &s.agents);
    let mut states = vec![start.clone()];
    let mut letters = vec![letter(&start)];
    // Trace steps before each transition, and each transition's agent (`None`: the user).
    let mut before = Vec::new();
    let mut movers: Vec<Option<usize>> = Vec::new();
    let mut shown_steps = 0;
    let mut state = start;
    let take = |state: &crate::semantics::SystemState, k: usize| {
        system.successors(state).into_iter().nth(k)
    };
    for &k in picks {
        let Some((label, t)) = take(&state, k) else {
            return no("the recorded run is no longer possible");
        };
        before.push(shown_steps);
        shown_steps += shown(&label).len();
        let mut l = letter(&t);
        if let Some(d) = atoms.step_letter(label.agent, label.notes.iter()) {
            for (w, x) in l.iter_mut().zip(d) {
                *w |= x;
            }
        }
        movers.push(match label.notes.as_slice() {
            [Note::Request { .. }] => None,
            _ => Some(label.agent as usize),
        });
        letters.push(l);
        state = t;
        states.push(state.clone());
    }
    let fair = project.manifest.bounds.fair_agents;
    let done = |s: &crate::semantics::SystemState| {
        system.successors(s).is_empty()
            || (s.agents.iter().all(|a| a.is_idle()) && s.mail.iter().all(|m| m.is_empty()))
    };
    // The recorded loop: from the transition where its steps begin, back to the last state.
    let last = states.last().cloned();
    let recorded_loop = c.loop_start.and_then(|ls| {
        (0..before.len()).find(|&t| before[t] == ls && Some(&states[t]) == last.as_ref())
    });
    let loop_at = match recorded_loop {
        Some(t0) => {
            if fair {
                let lo = &states[t0..states.len() - 1];
                for j in 0..system.names().len() {
                    let always = lo.iter().all(|s| {
                        system.successors(s).iter().any(|(l, _)| {
                            !matches!(l.notes.as_slice(), [Note::Request { .. }])
                                && l.agent as usize == j
                        })
                    });
                    if always && !movers[t0..].contains(&Some(j)) {
                        return no("its loop leaves out an agent that could move");
                    }
                }
            }
            t0 + 1
        }
        None => {
            let mut seen: HashMap<u64, usize> = HashMap::new();
            for (i, s) in states.iter().enumerate() {
                seen.entry(fingerprint(s)).or_insert(i);
            }
            let mut extended = 0;
            loop {
                let last = states.last().cloned().unwrap_or_else(|| state.clone());
                if done(&last) {
                    letters.push(letter(&last));
                    break letters.len() - 1;
                }
                if extended >= MAX_EXTENSION {
                    return no("the run does not close into a loop within the replay's bound");
                }
                let Some((label, t)) = take(&last, 0) else {
                    return no("the run cannot go on");
                };
                let mut l = letter(&t);
                if let Some(d) = atoms.step_letter(label.agent, label.notes.iter()) {
                    for (w, x) in l.iter_mut().zip(d) {
                        *w |= x;
                    }
                }
                letters.push(l);
                extended += 1;
                let fp = fingerprint(&t);
                states.push(t);
                if let Some(&e) = seen.get(&fp) {
                    break e + 1;
                }
                seen.insert(fp, states.len() - 1);
            }
        }
    };
    match violated_on(p, &letters, loop_at) {
        Some(binding) => Replayed {
            id: f.id.clone(),
            reached: true,
            detail: if binding.is_empty() {
                format!("violated on a run of {} steps", letters.len() - 1)
            } else {
                format!(
                    "violated for {binding} on a run of {} steps",
                    letters.len() - 1
                )
            },
        },
        None => no("the property now holds on this run"),
    }
}

/// Replays one finding's run among several agents.
fn replay_system_one(
    agents: &[Project],
    system: &crate::semantics::System,
    f: &FindingIn,
) -> Replayed {
    use crate::semantics::{Step, SystemState};
    let project = &agents[0];
    let no = |detail: &str| Replayed::missed(&f.id, detail);
    let Some(c) = &f.counterexample else {
        return no("the finding has no counterexample");
    };
    let atoms = match initial_atoms(project, f) {
        Ok(a) => a,
        Err(why) => return no(why),
    };
    let Some(mut state) = system
        .initial_states()
        .into_iter()
        .find(|s| s.world == atoms)
    else {
        return no("its initial state is no longer an initial state of the project");
    };
    if crate::check::explanation::CHECKS.contains(&f.check.as_str()) {
        return replay_system_explained(agents, system, f, c, state);
    }
    if let Some(p) = (f.check == "property")
        .then(|| system_run_property(project, system, f))
        .flatten()
        .filter(|p| p.user.is_some())
    {
        return replay_system_run_explained(agents, system, f, c, &p, state);
    }
    let check = Check::of(project, f, system.names());
    let kinds: Vec<String> = c
        .steps
        .iter()
        .map(|s| format!("{}:{}", s.agent.as_deref().unwrap_or(""), s.kind))
        .collect();
    let recorded: Vec<(&str, &str)> = kinds
        .iter()
        .zip(&c.steps)
        .map(|(k, s)| (k.as_str(), s.text.as_str()))
        .collect();
    let shown = |l: &Step| -> Vec<(String, String)> {
        let k = l.agent as usize;
        let name = &system.names()[k];
        let mut b = Builder::new(&agents[k], &system.agents[k]);
        b.push(l.notes.clone());
        b.steps()
            .iter()
            .map(|s| (format!("{name}:{}", s.kind.name()), s.text.clone()))
            .collect()
    };
    let next = |s: &SystemState| system.successors(s);
    let Some(run) = find_run(&state, &recorded, &next, &shown) else {
        return no("the project no longer gives this run");
    };
    if let Some(p) = (f.check == "property")
        .then(|| system_run_property(project, system, f))
        .flatten()
    {
        return replay_system_run(system, f, c, &p, state, &run, &shown);
    }
    let mut steps = 0;
    // The run's states and steps, and how many trace steps come before each transition.
    let mut states = vec![state.clone()];
    let mut labels: Vec<Step> = Vec::new();
    let mut before: Vec<usize> = Vec::new();
    for &k in &run {
        let (label, t) = system.successors(&state).swap_remove(k);
        before.push(steps);
        steps += shown(&label).len();
        if label.notes.iter().any(|n| check.note_violates(n, project)) {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {steps} steps"),
            };
        }
        state = t;
        states.push(state.clone());
        labels.push(label);
    }
    if check.is_liveness() {
        return match system_lasso(system, f, &check, &states, &labels, &before, c.loop_start) {
            Ok(()) => Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {steps} steps"),
            },
            Err(why) => no(why),
        };
    }
    // A deadlock of one agent: it can never take a step again (a run that cannot be told
    // is counted as reaching it: replay never calls a finding fixed that it cannot decide).
    let stuck =
        f.id.split_once(':')
            .and_then(|(_, name)| system.names().iter().position(|n| n == name));
    // The recorded run may end in cycles that show no step (an agent perceiving): the
    // violation is looked for after up to MAX_SILENT of them.
    let violated = |s: &SystemState| {
        let busy = (0..s.agents.len()).any(|k| !s.agents[k].is_idle() || !s.mail[k].is_empty());
        let deadlock = match (&check, stuck) {
            (Check::Deadlock, Some(k)) => {
                crate::check::system::stuck_from(system, s, k) != Some(false)
            }
            (Check::Deadlock, None) => busy && system.successors(s).is_empty(),
            _ => false,
        };
        check.atoms_violate(&system.everything(s)) || deadlock
    };
    let mut frontier = vec![state];
    for _ in 0..=MAX_SILENT {
        if frontier.iter().any(violated) {
            return Replayed {
                id: f.id.clone(),
                reached: true,
                detail: format!("reached after {steps} steps"),
            };
        }
        frontier = frontier
            .iter()
            .flat_map(|s| system.successors(s))
            .filter(|(l, _)| shown(l).is_empty())
            .map(|(_, t)| t)
            .collect();
    }
    no("the run no longer reaches the violation")
}
