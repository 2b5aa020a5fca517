//! What every stage reports: findings, their counterexample runs, search statistics, and
//! the report of SPEC §3 that holds them.
//!
//! This module sits below the stages that find things (`smt`, `check`) and above `syntax`
//! only (for locations and diagnostics), so that lint, the model checker and the renderers
//! share one vocabulary without importing one another. Exit codes follow SPEC §2 and are
//! derived from the findings alone ([`Verdict::exit_code`], [`verdict_of`]), so a verdict and
//! its exit code can never disagree.

use crate::syntax::{Diagnostic, Location, Severity, SourceMap};
use serde::{Deserialize, Serialize};

/// The tool's name and version, as reports name it.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct Tool {
    /// `bdi-check`
    pub name: &'static str,
    /// The crate version.
    pub version: &'static str,
}

impl Default for Tool {
    fn default() -> Tool {
        Tool {
            name: "bdi-check",
            version: env!("CARGO_PKG_VERSION"),
        }
    }
}

/// The overall outcome of a command.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Every check holds and the search was complete.
    Pass,
    /// Something was not decided (a bound, a solver `unknown`), nothing failed.
    Incomplete,
    /// At least one check failed.
    Fail,
    /// The input is malformed.
    Error,
}

impl Verdict {
    /// The exit status of SPEC §2: 0 pass, 1 fail, 2 bad input, 3 undecided.
    pub fn exit_code(self) -> i32 {
        match self {
            Verdict::Pass => 0,
            Verdict::Fail => 1,
            Verdict::Error => 2,
            Verdict::Incomplete => 3,
        }
    }
}

/// Whether a finding's check held.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The check failed.
    Fail,
    /// The check held.
    Pass,
    /// The check could not be decided.
    Unknown,
}

/// One finding of SPEC §3.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Finding {
    /// A stable id: `check:file:line`.
    pub id: String,
    /// The check's fixed name (`input`, `dead-plan`, `invariant`, ...).
    pub check: String,
    /// error, warning or note.
    pub severity: Severity,
    /// fail, pass or unknown.
    pub status: Status,
    /// What is wrong, in one sentence.
    pub message: String,
    /// Where, if it is about a place.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub location: Option<Location>,
    /// A concrete run (or, for static checks, a state) that shows the violation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counterexample: Option<Counterexample>,
    /// The span behind `location`, for source excerpts in human output.
    #[serde(skip)]
    pub span: Option<crate::syntax::Span>,
    /// Other places the finding names (e.g. the earlier of two overlapping plans).
    #[serde(skip)]
    pub related: Vec<crate::syntax::Span>,
    /// Why the project accepts this failing finding on purpose: the `why` of the
    /// manifest's `[[allow]]` that names it. A suppressed finding does not count toward the
    /// verdict.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suppressed: Option<String>,
}

impl Finding {
    /// The first related place, if any.
    pub fn secondary_plan_span(&self) -> Option<crate::syntax::Span> {
        self.related.first().copied()
    }
}

/// A counterexample of SPEC §3: where it starts, what the user asked, and what happened.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
pub struct Counterexample {
    /// Every atom true at the start (the rest are false), as Jason terms.
    pub initial: Vec<String>,
    /// The requests, in arrival order.
    pub requests: Vec<String>,
    /// The run, step by step (empty for a static finding, whose counterexample is a state).
    pub steps: Vec<TraceStep>,
    /// For a liveness violation (a lasso): the index in `steps` where the loop starts; the
    /// steps from there on repeat forever.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loop_start: Option<usize>,
}

/// The kinds of step of a run.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum StepKindTag {
    /// A user request arrives.
    Request,
    /// An event is taken from the queue.
    Event,
    /// A plan is chosen for an event.
    Plan,
    /// An environment action runs.
    Action,
    /// A belief is added or removed by the agent.
    Belief,
    /// An internal action runs.
    Internal,
    /// An explanation is given.
    Explanation,
}

impl StepKindTag {
    /// The kind as reports write it (`request`, `event`, ...).
    pub fn name(self) -> &'static str {
        match self {
            StepKindTag::Request => "request",
            StepKindTag::Event => "event",
            StepKindTag::Plan => "plan",
            StepKindTag::Action => "action",
            StepKindTag::Belief => "belief",
            StepKindTag::Internal => "internal",
            StepKindTag::Explanation => "explanation",
        }
    }
}

/// One step of a counterexample run.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct TraceStep {
    /// What kind of step.
    pub kind: StepKindTag,
    /// The step as Jason text: the action, the event, the plan's trigger.
    pub text: String,
    /// The intention it belongs to (1-based), if any.
    pub intention: Option<usize>,
    /// `file:line` of the plan it comes from, if any.
    pub plan: Option<String>,
    /// Atoms that became true.
    pub added: Vec<String>,
    /// Atoms that became false.
    pub removed: Vec<String>,
    /// The explanation given at this step, if any.
    pub explanation: Option<String>,
    /// In a project of several agents: the agent whose step it is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub agent: Option<String>,
}

/// The agent's whole state at one point of a run, for people (`bdi-check trace`).
#[derive(Clone, Debug, Serialize, PartialEq, Default)]
pub struct StateView {
    /// Every belief, in the model's atom order.
    pub beliefs: Vec<String>,
    /// Pending events, the next one first, each with the intention it belongs to.
    pub events: Vec<String>,
    /// The intentions: those held by a subgoal's event, the running ones in round-robin
    /// order (the first runs next), the one awaiting its action's feedback, and the ones
    /// suspended by `.wait`.
    pub intentions: Vec<IntentionView>,
    /// Each user's expected successors, as learned so far on this run.
    pub expected: Vec<ExpectedView>,
}

/// One intention of a [`StateView`].
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct IntentionView {
    /// Its number in the run's steps (1-based).
    pub intention: usize,
    /// `held by its event`, `running`, `awaiting feedback` or `waiting`.
    pub status: &'static str,
    /// Its stack, top (running) frame first.
    pub frames: Vec<MeansView>,
}

/// One intended means on an intention's stack.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct MeansView {
    /// The instantiated trigger the plan was chosen for.
    pub trigger: String,
    /// `file:line` of the plan.
    pub plan: String,
    /// The bindings of the plan's variables, `X = value`.
    pub bindings: Vec<String>,
    /// The step it executes next (for a frame below the top: the subgoal it waits for),
    /// as written; `None` when its body is done.
    pub next: Option<String>,
}

/// A user's expected-successor relation `N` at one point of a run.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ExpectedView {
    /// The user.
    pub user: String,
    /// How many pattern pairs the manifest gives the user.
    pub patterns: usize,
    /// The pairs learned on this run so far, `(prev, next)`.
    pub learned: Vec<String>,
}

/// A counterexample replayed step by step with the agent's state after each transition
/// (`bdi-check trace`).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Trace {
    /// The finding traced.
    pub finding: String,
    /// Its check.
    pub check: String,
    /// Its message, as the report gives it.
    pub message: String,
    /// The state the run starts from.
    pub initial: StateView,
    /// One entry per transition, in order.
    pub transitions: Vec<TracedTransition>,
    /// Whether the run still reaches the finding's violation on the project as it is.
    pub reached: bool,
    /// What happened at the end, for people.
    pub outcome: String,
}

/// One transition of a [`Trace`]: the steps it shows and the state it leads to.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct TracedTransition {
    /// The steps, numbered as the counterexample numbers them.
    pub steps: Vec<TraceStep>,
    /// The state after it.
    pub state: StateView,
}

impl TraceStep {
    /// Its belief changes, `+atom` for each added then `-atom` for each removed.
    pub fn changes(&self) -> Vec<String> {
        self.added
            .iter()
            .map(|a| format!("+{a}"))
            .chain(self.removed.iter().map(|a| format!("-{a}")))
            .collect()
    }
}

/// Search statistics of SPEC §3.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
pub struct Stats {
    /// Initial states explored.
    pub initial_states: usize,
    /// Distinct states reached.
    pub states: usize,
    /// Transitions taken.
    pub transitions: usize,
    /// Length of the longest shortest path.
    pub depth: usize,
    /// Wall-clock time.
    pub seconds: f64,
    /// `states / seconds`.
    pub states_per_second: f64,
    /// Whether the search covered every reachable state.
    pub complete: bool,
    /// Among several agents, when the search was reduced (partial-order reduction,
    /// symmetry over instances): the states of the search of every interleaving the checks
    /// of runs that go on for ever were made on (counted in `seconds` and
    /// `states_per_second` too).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liveness_states: Option<usize>,
    /// The run's phases in order (`lint`, `search`, `explanation:USER` per user), each
    /// with its wall-clock time; `seconds` is the whole run's, loading included.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub phases: Vec<Phase>,
}

/// One phase of a run and its wall-clock time.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
pub struct Phase {
    /// `lint`, `search` (the agents' states), `ltl product`, or `explanation:USER`.
    pub name: String,
    /// Its wall-clock time.
    pub seconds: f64,
    /// The states it explored, for a search.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub states: Option<usize>,
    /// The phases it ran beside, on a thread of its own (its time overlaps theirs, so the
    /// phases' times may add up to more than the run's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub beside: Vec<String>,
}

/// The report every project command writes (SPEC §3).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    /// The tool (read back from JSON, the report is this tool's: `merge` writes it).
    #[serde(skip_deserializing)]
    pub tool: Tool,
    /// The project as named on the command line.
    pub project: String,
    /// The overall verdict.
    pub verdict: Verdict,
    /// Every finding, failing and passing.
    pub findings: Vec<Finding>,
    /// Explanations given (filled by `explain`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub explanations: Vec<serde_json::Value>,
    /// Search statistics (filled by `verify`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stats: Option<Stats>,
    /// What the reader must know about how the verdict was reached (e.g. that symmetry
    /// reduction rests on an assumption the agent does not meet).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// The part of the initial states this run covered (`verify --shard K/N`), so that
    /// `merge` can check it has each part of one run exactly once.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
    /// The project's files the run read, each with its SHA-256, so `replay` can tell a
    /// project that changed since from a report that was altered.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sources: Vec<Source>,
}

/// One file a report was made from.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Source {
    /// How reports name it.
    pub file: String,
    /// The SHA-256 of its text, in hex.
    pub sha256: String,
}

/// Every file of a loaded project, as [`Report::sources`] names them.
pub fn sources_of(map: &SourceMap) -> Vec<Source> {
    use sha2::Digest;
    map.files()
        .iter()
        .map(|f| Source {
            file: f.name.clone(),
            sha256: sha2::Sha256::digest(f.text.as_bytes())
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect(),
        })
        .collect()
}

/// One part of a sharded run: the `index`-th (from 1) of `count`.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Shard {
    /// K of `--shard K/N`.
    pub index: u32,
    /// N of `--shard K/N`.
    pub count: u32,
}

impl Report {
    /// A report whose verdict is derived from its findings.
    pub fn new(project: impl Into<String>, mut findings: Vec<Finding>) -> Report {
        unique_ids(&mut findings);
        Report {
            tool: Tool::default(),
            project: project.into(),
            verdict: verdict_of(&findings),
            findings,
            explanations: Vec::new(),
            stats: None,
            warnings: Vec::new(),
            shard: None,
            sources: Vec::new(),
        }
    }
}

impl Finding {
    /// The finding SPEC §2 asks for when input is malformed: check `input`, severity error.
    pub fn from_input_diagnostic(d: &Diagnostic, map: &SourceMap) -> Finding {
        let location = d.location(map);
        let id = match &location {
            Some(l) => format!("input:{}:{}", l.file, l.line),
            None => "input".to_string(),
        };
        Finding {
            id,
            check: "input".into(),
            severity: d.severity,
            status: if d.severity == Severity::Error {
                Status::Fail
            } else {
                Status::Pass
            },
            message: d.message.clone(),
            location,
            counterexample: None,
            span: d.span,
            related: d.secondary.iter().map(|l| l.span).collect(),
            suppressed: None,
        }
    }
}

/// Makes every id unique, for `replay --finding` and SARIF fingerprints: findings that
/// share `check:file:line` get their column, or, where columns are alike too, their
/// position among them (findings come in a fixed order, so ids are stable).
pub fn unique_ids(findings: &mut [Finding]) {
    let mut groups: std::collections::BTreeMap<String, Vec<usize>> = Default::default();
    for (i, f) in findings.iter().enumerate() {
        groups.entry(f.id.clone()).or_default().push(i);
    }
    for (id, members) in groups.into_iter().filter(|(_, m)| m.len() > 1) {
        let columns: Vec<Option<usize>> = members
            .iter()
            .map(|&i| findings[i].location.as_ref().map(|l| l.column))
            .collect();
        let distinct = columns
            .iter()
            .collect::<std::collections::BTreeSet<_>>()
            .len()
            == columns.len()
            && columns.iter().all(Option::is_some);
        for (n, &i) in members.iter().enumerate() {
            findings[i].id = match columns[n] {
                Some(c) if distinct => format!("{id}:{c}"),
                _ => format!("{id}#{}", n + 1),
            };
        }
    }
}

/// The verdict of a set of findings: `error` if an input finding is an error, else `fail` if
/// any finding of severity error failed, else `incomplete` if any is unknown, else `pass`.
pub fn verdict_of(findings: &[Finding]) -> Verdict {
    let failed = |f: &&Finding| {
        f.severity == Severity::Error && f.status == Status::Fail && f.suppressed.is_none()
    };
    if findings.iter().filter(failed).any(|f| f.check == "input") {
        Verdict::Error
    } else if findings.iter().any(|f| failed(&f)) {
        Verdict::Fail
    } else if findings.iter().any(|f| f.status == Status::Unknown) {
        Verdict::Incomplete
    } else {
        Verdict::Pass
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn finding(check: &str, severity: Severity, status: Status) -> Finding {
        Finding {
            id: check.into(),
            check: check.into(),
            severity,
            status,
            message: String::new(),
            location: None,
            counterexample: None,
            span: None,
            related: Vec::new(),
            suppressed: None,
        }
    }

    #[test]
    fn shared_ids_get_their_column_or_their_position() {
        let at = |id: &str, column: usize| Finding {
            id: id.into(),
            location: Some(Location {
                file: "a.asl".into(),
                line: 2,
                column,
            }),
            ..finding("goal-failure", Severity::Error, Status::Fail)
        };
        let mut fs = vec![at("g:a.asl:2", 1), at("g:a.asl:2", 9), at("h:a.asl:2", 1)];
        unique_ids(&mut fs);
        let ids: Vec<&str> = fs.iter().map(|f| f.id.as_str()).collect();
        assert_eq!(ids, ["g:a.asl:2:1", "g:a.asl:2:9", "h:a.asl:2"]);
        let mut fs = vec![at("g:a.asl:2", 1), at("g:a.asl:2", 1)];
        unique_ids(&mut fs);
        let ids: Vec<&str> = fs.iter().map(|f| f.id.as_str()).collect();
        assert_eq!(ids, ["g:a.asl:2#1", "g:a.asl:2#2"]);
    }

    #[test]
    fn verdicts_and_exit_codes() {
        assert_eq!(verdict_of(&[]), Verdict::Pass);
        let warn = finding("coverage-gap", Severity::Warning, Status::Fail);
        assert_eq!(verdict_of(std::slice::from_ref(&warn)), Verdict::Pass);
        let unknown = finding("dead-plan", Severity::Error, Status::Unknown);
        assert_eq!(
            verdict_of(&[warn.clone(), unknown.clone()]),
            Verdict::Incomplete
        );
        let fail = finding("dead-plan", Severity::Error, Status::Fail);
        assert_eq!(verdict_of(&[unknown.clone(), fail.clone()]), Verdict::Fail);
        let input = finding("input", Severity::Error, Status::Fail);
        assert_eq!(verdict_of(&[fail, input]), Verdict::Error);
        assert_eq!(
            [
                Verdict::Pass,
                Verdict::Fail,
                Verdict::Error,
                Verdict::Incomplete
            ]
            .map(Verdict::exit_code),
            [0, 1, 2, 3]
        );
    }
}
