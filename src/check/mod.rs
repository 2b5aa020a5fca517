//! Exhaustive exploration and the dynamic checks of SPEC §3: `invariant`, `property`
//! (`always`, `eventually`, `reachable`), `action-failure`, `goal-failure`, `deadlock`,
//! `livelock`, `request-not-completed`.
//!
//! Safety violations come with the shortest run that reaches them (breadth-first parent
//! links). State checks run as each state is found (in the exploring threads), since no
//! state is kept; the search keeps, per state, only what the liveness checks need: its
//! successors, the requests pending in it and, per `eventually` property, one bit.
//! Liveness violations come as a lasso: the shortest run to a loop, then the loop, found on
//! the strongly connected components of the explored graph (an iterative Tarjan over the
//! compact adjacency arrays, so deep graphs do not overflow the stack). The scheduling of
//! intentions is round-robin, which is fair, so every loop of the graph is a run the agent
//! can really take.

pub mod explanation;
pub mod explore;
pub mod model;
pub mod run;
pub mod store;
pub mod symmetry;
pub mod trace;

use crate::findings::{Counterexample, Finding, Stats, Status};
use crate::model::cond::Cond;
use crate::model::formula;
use crate::model::project::Project;
use crate::semantics::{Compiled, Note, Semantics};
use crate::syntax::{Diagnostic, Severity, Span};
use explore::{explore_with, Bound, Graph, Limits, Options};
use model::{Agent, AgentState, CompiledAgent, CycleNotes, Model};
use std::collections::{BTreeMap, HashMap, VecDeque};

/// What `verify` found.
pub struct Verification {
    /// One finding per check (failing, passing or undecided).
    pub findings: Vec<Finding>,
    /// Search statistics.
    pub stats: Stats,
    /// The bound that stopped the search, if any.
    pub bound: Option<Bound>,
    /// Bytes held by the visited-state store and by the edges at the end of the search.
    pub memory: (usize, usize),
    /// Peak resident memory of the process, in bytes (0 if unknown).
    pub peak_memory: u64,
    /// The symmetric types (and how many objects each has) when symmetry reduction was on.
    pub symmetric_types: Vec<(String, usize)>,
    /// When symmetry reduction was on and the agent does not treat the objects alike (a
    /// reachable state whose renaming has other successors than its successors renamed):
    /// the renaming, and which plans the stored state was about to use.
    pub symmetry_caveat: Option<String>,
}

/// How `verify` searches.
#[derive(Clone, Copy, Debug)]
pub struct VerifyOptions {
    /// Worker threads.
    pub threads: usize,
    /// Symmetry reduction over the manifest's `[bounds] symmetry` types.
    pub symmetry: bool,
    /// `(k, n)`: verify from the `k`-th of `n` parts of the initial states (1-based).
    pub shard: Option<(u32, u32)>,
    /// Stop, as incomplete, once the process holds this many bytes.
    pub max_memory: Option<u64>,
    /// Search the compiled reasoning cycle ([`Compiled`]) where it applies (a local
    /// library); off, the reference one. The two give the same report.
    pub compiled: bool,
}

impl Default for VerifyOptions {
    /// All cores, symmetry as the manifest says, no shard, no memory bound.
    fn default() -> VerifyOptions {
        VerifyOptions {
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            symmetry: true,
            shard: None,
            max_memory: None,
            compiled: true,
        }
    }
}

/// A compiled state property.
struct Prop {
    name: String,
    kind: crate::syntax::manifest::PropertyKind,
    cond: Cond,
    span: Span,
}

/// What the search records about one state, computed where the state is found.
struct Summary {
    /// Bit `j`: condition `j` of [`Conditions`] holds.
    holds: smallvec::SmallVec<[u64; 2]>,
    pending: u64,
    idle: bool,
}

/// The state conditions evaluated on every state, in one numbering: invariants, then
/// properties, then the plan pairs whose overlap lint asks about.
struct Conditions<'a> {
    invariants: Vec<&'a Cond>,
    props: Vec<&'a Cond>,
    overlaps: Vec<(u32, u32)>,
}

impl Conditions<'_> {
    fn len(&self) -> usize {
        self.invariants.len() + self.props.len() + self.overlaps.len()
    }

    fn summarize(&self, sem: &Semantics, s: &impl AgentState) -> Summary {
        let mut holds = smallvec::SmallVec::from_elem(0u64, self.len().div_ceil(64).max(1));
        let mut set = |j: usize| holds[j / 64] |= 1 << (j % 64);
        let conds = self.invariants.iter().chain(&self.props);
        for (j, c) in conds.enumerate() {
            if c.eval(s.beliefs()) {
                set(j);
            }
        }
        if !self.overlaps.is_empty() {
            if let Some(ev) = s.first_event() {
                let applicable = s.applicable(sem, &ev.trigger);
                let base = self.invariants.len() + self.props.len();
                for (k, (a, b)) in self.overlaps.iter().enumerate() {
                    if applicable.iter().any(|(p, _)| p == a)
                        && applicable.iter().any(|(p, _)| p == b)
                    {
                        set(base + k);
                    }
                }
            }
        }
        Summary {
            holds,
            pending: s.pending_requests(),
            idle: s.is_idle(),
        }
    }
}

/// Per-state facts kept for the checks after the search.
#[derive(Default)]
struct Facts {
    /// For each condition: the first state where it holds and the first where it does not.
    first_holds: Vec<Option<u32>>,
    first_fails: Vec<Option<u32>>,
    /// Bit per state: idle.
    idle: Vec<u64>,
    /// Per state: an index into `masks` (the requests pending there).
    pending: Vec<u32>,
    masks: Vec<u64>,
    mask_ids: HashMap<u64, u32>,
    /// Per `eventually` property: bit per state, set when the property does not hold.
    bad: Vec<Vec<u64>>,
}

fn bit(v: &[u64], i: u32) -> bool {
    v.get(i as usize / 64)
        .is_some_and(|w| w >> (i % 64) & 1 == 1)
}

fn set_bit(v: &mut Vec<u64>, i: u32, value: bool) {
    let w = i as usize / 64;
    if v.len() <= w {
        v.resize(w + 1, 0);
    }
    if value {
        v[w] |= 1 << (i % 64);
    }
}

/// Explores the project's state space and runs every dynamic check, with the default
/// [`VerifyOptions`].
pub fn verify(
    project: &Project,
    limits: Limits,
    progress: impl FnMut(usize, u32, f64),
    lint: &[Finding],
) -> Result<Verification, Vec<Diagnostic>> {
    verify_with(project, limits, &VerifyOptions::default(), progress, lint)
}

/// Explores the project's state space and runs every dynamic check. The static findings
/// in `lint` are settled against the explored states as SPEC §3 says: a warning that some
/// run reaches becomes an error with that run; one no run reaches becomes a note (when the
/// search was complete); every other finding is kept as it is.
pub fn verify_with(
    project: &Project,
    limits: Limits,
    opts: &VerifyOptions,
    progress: impl FnMut(usize, u32, f64),
    lint: &[Finding],
) -> Result<Verification, Vec<Diagnostic>> {
    let sem = Semantics::new(project)?;
    let mut errors = Vec::new();
    let props: Vec<Prop> = project
        .manifest
        .properties
        .iter()
        .filter_map(|p| {
            match formula::compile(&p.formula.expr, &project.atoms, &project.universe) {
                Ok(cond) => Some(Prop {
                    name: p.name.value.clone(),
                    kind: p.kind,
                    cond,
                    span: p.formula.span,
                }),
                Err(d) => {
                    errors.push(d);
                    None
                }
            }
        })
        .collect();
    if !errors.is_empty() {
        return Err(errors);
    }
    let symmetry = if opts.symmetry {
        symmetry::Symmetry::new(project, &sem)?
    } else {
        None
    };
    let symmetric_types = symmetry
        .as_ref()
        .map(|s| s.describe(project))
        .unwrap_or_default();
    let agent = Agent {
        sem: &sem,
        symmetry,
    };
    let plan_at = |sp: Span| project.plans.plans.iter().position(|p| p.span == sp);
    let overlaps: Vec<(u32, u32)> = lint
        .iter()
        .filter(|f| settles(f) && f.check == "plan-overlap")
        .filter_map(|f| {
            let later = plan_at(f.span?)?;
            let earlier = plan_at(f.secondary_plan_span()?)?;
            Some((earlier as u32, later as u32))
        })
        .collect();
    let conditions = Conditions {
        invariants: project.invariants.iter().map(|(_, c)| c).collect(),
        props: props.iter().map(|p| &p.cond).collect(),
        overlaps,
    };
    let n_conds = conditions.len();
    let eventually: Vec<usize> = props
        .iter()
        .enumerate()
        .filter(|(_, p)| p.kind == crate::syntax::manifest::PropertyKind::Eventually)
        .map(|(j, _)| project.invariants.len() + j)
        .collect();
    let mut facts = Facts {
        first_holds: vec![None; n_conds],
        first_fails: vec![None; n_conds],
        bad: vec![Vec::new(); eventually.len()],
        ..Facts::default()
    };
    let search = Options {
        threads: opts.threads,
        keep_edges: true,
        max_memory: opts.max_memory,
        shard: opts.shard,
    };
    let mut failures = Failures::default();
    let compiled = if opts.compiled {
        Compiled::new(&sem)
    } else {
        None
    };
    // Every stored state is also checked for equivariance: reduction is only exact if
    // renaming a state renames its successors (see Symmetry::equivariance_violation);
    // where it does not, the report says so.
    let (graph, not_equivariant) = match &compiled {
        Some(c) => {
            let model = CompiledAgent {
                compiled: c,
                symmetry: agent.symmetry.as_ref(),
            };
            let (g, unequal) = search_agent(
                &model,
                &sem,
                &conditions,
                |s| model.equivariance_violation(s),
                (limits, &search),
                (&mut facts, &eventually, &mut failures),
                progress,
            );
            (g.cast(), unequal)
        }
        None => search_agent(
            &agent,
            &sem,
            &conditions,
            |s| {
                agent
                    .symmetry
                    .as_ref()
                    .and_then(|sym| sym.equivariance_violation(&sem, s))
            },
            (limits, &search),
            (&mut facts, &eventually, &mut failures),
            progress,
        ),
    };
    let Failures {
        actions: action_failures,
        goals: goal_failures,
        no_plan,
        applied,
    } = failures;
    let c = Checker {
        project,
        agent: &agent,
        graph: &graph,
        facts: &facts,
        conditions: &conditions,
    };
    let mut findings: Vec<Finding> = lint
        .iter()
        .map(|f| c.settle(f, &action_failures, &no_plan))
        .collect();
    settle_undecided(&mut findings, project, &applied, &no_plan, graph.complete());
    c.safety(&mut findings, &props);
    settle_non_inductive(&mut findings, project, graph.complete());
    c.failures(&mut findings, action_failures, goal_failures);
    c.liveness(&mut findings, &props);
    // The explanation properties: one more search per user, each state paired with the
    // user's expected successors.
    let explore_opts = explore::Options {
        threads: opts.threads,
        keep_edges: false,
        max_memory: opts.max_memory,
        shard: opts.shard,
    };
    findings.extend(
        explanation::verify(
            project,
            &sem,
            agent.symmetry.as_ref(),
            limits,
            &explore_opts,
        )?
        .0,
    );
    let seconds = graph.seconds;
    let stats = Stats {
        initial_states: graph.initial_covered,
        states: graph.len(),
        transitions: graph.transitions,
        depth: graph.max_depth() as usize,
        seconds,
        states_per_second: if seconds > 0.0 {
            graph.len() as f64 / seconds
        } else {
            0.0
        },
        complete: graph.complete(),
    };
    Ok(Verification {
        findings,
        stats,
        bound: graph.bound,
        memory: (graph.store_bytes(), graph.edge_bytes()),
        peak_memory: graph.peak_memory,
        symmetric_types,
        symmetry_caveat: not_equivariant,
    })
}

/// The first (hence shallowest-source) transition of each failure, keyed by place.
#[derive(Default)]
struct Failures {
    actions: BTreeMap<(u32, u32), Failure>,
    goals: BTreeMap<String, Failure>,
    no_plan: BTreeMap<(String, usize), Failure>,
    /// The plans some run adopts.
    applied: std::collections::BTreeSet<u32>,
}

impl Failures {
    /// Records the failures a transition shows.
    fn record<'n>(&mut self, src: u32, k: u32, fp: u64, notes: impl Iterator<Item = &'n Note>) {
        for n in notes {
            let at = || Failure {
                src,
                k,
                fp,
                note: n.clone(),
            };
            match n {
                Note::ActionFailed { span, .. } => {
                    self.actions
                        .entry((span.file.0, span.start))
                        .or_insert_with(at);
                }
                Note::GoalFailed { goal, span, .. } => {
                    let key = match span {
                        Some(sp) => format!("{}:{}", sp.file.0, sp.start),
                        None => goal.to_string(),
                    };
                    self.goals.entry(key).or_insert_with(at);
                }
                Note::NoApplicablePlan(t) => {
                    let key = (
                        t.literal.functor().unwrap_or("").to_string(),
                        t.literal.arity(),
                    );
                    self.no_plan.entry(key).or_insert_with(at);
                }
                Note::Plan { plan, .. } => {
                    self.applied.insert(*plan);
                }
                _ => {}
            }
        }
    }
}

/// The agent's search (on the reference or the compiled model: they have the same
/// fingerprints), recording each state's facts and each transition's failures. Returns
/// the graph and the first equivariance violation `equivariance` reports.
#[allow(clippy::too_many_arguments)]
fn search_agent<M>(
    model: &M,
    sem: &Semantics,
    conditions: &Conditions,
    equivariance: impl Fn(&M::State) -> Option<String> + Sync,
    (limits, opts): (Limits, &Options),
    (facts, eventually, failures): (&mut Facts, &[usize], &mut Failures),
    progress: impl FnMut(usize, u32, f64),
) -> (Graph, Option<String>)
where
    M: Model + Sync,
    M::State: AgentState + Send + Sync,
    M::Label: CycleNotes + Send,
{
    let mut not_equivariant = None;
    let graph = explore_with(
        model,
        limits,
        opts,
        |s| (conditions.summarize(sem, s), equivariance(s)),
        |i, (sum, unequal)| {
            if not_equivariant.is_none() {
                not_equivariant = unequal;
            }
            facts.record(i, sum, eventually)
        },
        |src, k, label: &M::Label, fp| failures.record(src, k, fp, label.notes()),
        progress,
    );
    (graph.cast(), not_equivariant)
}

/// Decides with the runs the plan checks lint could not decide (z3's budget, arithmetic
/// it does not model): a plan some run adopts is not dead, nor hidden by an earlier one
/// (with Jason's first-applicable selection); a goal for which no run meets a state where
/// no plan applies, in a complete search, has no gap any run reaches.
fn settle_undecided(
    findings: &mut [Finding],
    project: &Project,
    applied: &std::collections::BTreeSet<u32>,
    no_plan: &BTreeMap<(String, usize), Failure>,
    complete: bool,
) {
    let first =
        project.manifest.bounds.plan_selection == crate::syntax::manifest::PlanSelection::First;
    for f in findings.iter_mut() {
        if f.status != Status::Unknown {
            continue;
        }
        let Some(i) = project
            .plans
            .plans
            .iter()
            .position(|p| Some(p.span) == f.span)
        else {
            continue;
        };
        let plan = &project.plans.plans[i];
        match f.check.as_str() {
            "dead-plan" if applied.contains(&(i as u32)) => {
                f.status = Status::Pass;
                f.message = format!("{} is applicable: a run adopts it", plan.name());
            }
            "shadowed-plan" if first && applied.contains(&(i as u32)) => {
                f.status = Status::Pass;
                f.message = format!("no earlier plan hides {}: a run adopts it", plan.name());
            }
            "coverage-gap" if complete => {
                let t = &plan.trigger.literal;
                let key = (t.functor().unwrap_or("").to_string(), t.arity());
                if !no_plan.contains_key(&key) {
                    f.status = Status::Pass;
                    f.message = format!(
                        "no run meets a state where no plan for {} applies",
                        plan.trigger
                    );
                }
            }
            _ => {}
        }
    }
}

/// Settles lint's `action-breaks-invariant` warnings with the invariants the search
/// checked: an action that can break an invariant from some state only matters when a
/// run breaks it. Reached, the warning is an error with the run that breaks the
/// invariant; never reached (a complete search), a note: the invariant is not inductive,
/// but holds in every reachable state.
fn settle_non_inductive(findings: &mut [Finding], project: &Project, complete: bool) {
    let broken: Vec<(String, Option<Counterexample>)> = project
        .invariants
        .iter()
        .filter_map(|(name, _)| {
            let f = findings.iter().find(|f| {
                f.check == "invariant"
                    && f.status == Status::Fail
                    && f.message.starts_with(&format!("invariant `{name}` "))
            })?;
            Some((name.clone(), f.counterexample.clone()))
        })
        .collect();
    for f in findings.iter_mut() {
        if f.check != "action-breaks-invariant"
            || f.status != Status::Fail
            || f.severity != Severity::Warning
        {
            continue;
        }
        let hit = broken
            .iter()
            .find(|(name, _)| f.message.contains(&format!("`{name}` (after")));
        match hit {
            Some((name, cx)) => {
                f.severity = Severity::Error;
                f.message = format!("{} — and a run breaks `{name}`", f.message);
                f.counterexample = cx.clone();
            }
            None if complete => {
                f.severity = Severity::Note;
                f.message = format!(
                    "{} — but no run breaks it: the invariant is not inductive, yet it holds in every reachable state",
                    f.message
                );
            }
            None => {}
        }
    }
}

/// Whether a lint finding is one that exploration settles.
fn settles(f: &Finding) -> bool {
    matches!(
        f.check.as_str(),
        "coverage-gap" | "plan-overlap" | "precondition"
    ) && f.status == Status::Fail
        && f.severity == Severity::Warning
}

/// A transition that shows a failure: where it starts, its number there, the fingerprint
/// of its target, and the note.
struct Failure {
    src: u32,
    k: u32,
    fp: u64,
    note: Note,
}

impl Facts {
    fn record(&mut self, i: u32, s: Summary, eventually: &[usize]) {
        for j in 0..self.first_holds.len() {
            let slot = if bit(&s.holds, j as u32) {
                &mut self.first_holds[j]
            } else {
                &mut self.first_fails[j]
            };
            slot.get_or_insert(i);
        }
        set_bit(&mut self.idle, i, s.idle);
        let next = self.masks.len() as u32;
        let id = *self.mask_ids.entry(s.pending).or_insert(next);
        if id == next {
            self.masks.push(s.pending);
        }
        self.pending.push(id);
        for (b, &j) in self.bad.iter_mut().zip(eventually) {
            set_bit(b, i, !bit(&s.holds, j as u32));
        }
    }

    fn pending(&self, i: u32) -> u64 {
        self.masks[self.pending[i as usize] as usize]
    }
}

/// A run reaching a state: the path to it, and the transition taken there, if any.
type Reach<'f> = (Vec<u32>, Option<&'f Failure>);

struct Checker<'a> {
    project: &'a Project,
    agent: &'a Agent<'a>,
    graph: &'a Graph,
    facts: &'a Facts,
    conditions: &'a Conditions<'a>,
}

/// Whether a transition's notes show the same failure as `want` (the same place; under
/// symmetry the goal may be a renaming of the one seen in exploration).
fn same_failure(want: &Note, notes: &[Note]) -> bool {
    notes.iter().any(|n| match (want, n) {
        (Note::ActionFailed { span: a, .. }, Note::ActionFailed { span: b, .. }) => a == b,
        (Note::GoalFailed { span: a, .. }, Note::GoalFailed { span: b, .. }) => a == b,
        (Note::NoApplicablePlan(a), Note::NoApplicablePlan(b)) => {
            a.literal.functor() == b.literal.functor() && a.literal.arity() == b.literal.arity()
        }
        _ => false,
    })
}

impl Checker<'_> {
    fn location(&self, span: Span) -> crate::syntax::Location {
        self.project.map.location(span)
    }

    fn finding(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
    ) -> Finding {
        let location = self.location(span);
        // An undecided check states only what the explored part shows.
        let message = if status == Status::Unknown {
            format!("{message}, as far as the search went: it was cut short before every state was reached")
        } else {
            message
        };
        Finding {
            id: format!("{check}:{name}"),
            check: check.into(),
            severity: Severity::Error,
            status,
            message,
            location: Some(location),
            counterexample: None,
            span: Some(span),
            related: Vec::new(),
        }
    }

    /// Undecided when the search was cut short, passed otherwise.
    fn held(&self) -> Status {
        if self.graph.complete() {
            Status::Pass
        } else {
            Status::Unknown
        }
    }

    fn counterexample(
        &self,
        path: &[u32],
        extra: Option<&Failure>,
        cycle: &[u32],
    ) -> Counterexample {
        let want = |notes: &Vec<Note>| extra.is_some_and(|f| same_failure(&f.note, notes));
        let extra = extra.map(|f| trace::Extra {
            src: f.src,
            k: f.k,
            fp: f.fp,
            want: &want,
        });
        trace::counterexample(self.project, self.agent, self.graph, path, extra, cycle)
    }

    /// A finding for a state reached by a shortest run, with that run.
    fn reached(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
        at: u32,
    ) -> Finding {
        let mut f = self.finding(check, name, span, status, message);
        f.counterexample = Some(self.counterexample(&self.graph.path_to(at), None, &[]));
        f
    }

    fn safety(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let n = self.graph.len();
        let facts = self.facts;
        for (j, (name, _)) in self.project.invariants.iter().enumerate() {
            let span = self
                .project
                .manifest
                .invariants
                .iter()
                .find(|i| &i.name.value == name)
                .map_or(Span::default(), |i| i.formula.span);
            match facts.first_fails[j] {
                Some(i) => out.push(self.reached(
                    "invariant",
                    name,
                    span,
                    Status::Fail,
                    format!(
                        "invariant `{name}` is violated after {} steps",
                        self.graph.depth(i)
                    ),
                    i,
                )),
                None => out.push(self.finding(
                    "invariant",
                    name,
                    span,
                    self.held(),
                    format!("invariant `{name}` holds in all {n} reached states"),
                )),
            }
        }
        use crate::syntax::manifest::PropertyKind;
        let base = self.project.invariants.len();
        for (j, p) in props.iter().enumerate() {
            match p.kind {
                PropertyKind::Always => match facts.first_fails[base + j] {
                    Some(i) => out.push(self.reached(
                        "property",
                        &p.name,
                        p.span,
                        Status::Fail,
                        format!(
                            "`{}` does not always hold: it is false after {} steps",
                            p.name,
                            self.graph.depth(i)
                        ),
                        i,
                    )),
                    None => out.push(self.finding(
                        "property",
                        &p.name,
                        p.span,
                        self.held(),
                        format!("`{}` holds in all {n} reached states", p.name),
                    )),
                },
                PropertyKind::Reachable => match facts.first_holds[base + j] {
                    Some(i) => out.push(self.reached(
                        "property",
                        &p.name,
                        p.span,
                        Status::Pass,
                        format!(
                            "`{}` is reached after {} steps (witness run attached)",
                            p.name,
                            self.graph.depth(i)
                        ),
                        i,
                    )),
                    None => {
                        let status = if self.graph.complete() {
                            Status::Fail
                        } else {
                            Status::Unknown
                        };
                        out.push(self.finding(
                            "property",
                            &p.name,
                            p.span,
                            status,
                            format!("`{}` is never reached", p.name),
                        ));
                    }
                },
                PropertyKind::Eventually => {}
            }
        }
        // Deadlock: a state with nothing to do that is not a finished run. Such states cannot
        // arise from this semantics' rules; the check guards them.
        let stuck = (0..n as u32).find(|&i| {
            self.graph.successors(i).is_some_and(|e| e.is_empty()) && !bit(&facts.idle, i)
        });
        let span = self.project.manifest.agent.plans.written.span;
        match stuck {
            Some(i) => out.push(self.reached(
                "deadlock",
                "agent",
                span,
                Status::Fail,
                "the agent is stuck: no step is possible, but it is not done".into(),
                i,
            )),
            None => out.push(self.finding(
                "deadlock",
                "agent",
                span,
                self.held(),
                "no reachable state is stuck".into(),
            )),
        }
    }

    /// Settles one static finding against the explored graph.
    fn settle(
        &self,
        f: &Finding,
        action_failures: &BTreeMap<(u32, u32), Failure>,
        no_plan: &BTreeMap<(String, usize), Failure>,
    ) -> Finding {
        if !settles(f) {
            return f.clone();
        }
        let Some(span) = f.span else { return f.clone() };
        let plan_at = |sp: Span| self.project.plans.plans.iter().position(|p| p.span == sp);
        let reached: Option<Reach> = match f.check.as_str() {
            "precondition" => action_failures
                .get(&(span.file.0, span.start))
                .map(|x| (self.graph.path_to(x.src), Some(x))),
            "coverage-gap" => plan_at(span).and_then(|i| {
                let t = &self.project.plans.plans[i].trigger.literal;
                no_plan
                    .get(&(t.functor().unwrap_or("").to_string(), t.arity()))
                    .map(|x| (self.graph.path_to(x.src), Some(x)))
            }),
            _ => {
                // plan-overlap: the later plan at the finding, the earlier one beside it.
                let later = plan_at(span);
                let earlier = f.secondary_plan_span().and_then(plan_at);
                match (earlier, later) {
                    (Some(a), Some(b)) => self
                        .overlap(a as u32, b as u32)
                        .map(|i| (self.graph.path_to(i), None)),
                    _ => None,
                }
            }
        };
        let mut g = f.clone();
        match reached {
            Some((path, extra)) => {
                g.severity = Severity::Error;
                g.message = format!("{} — and a run reaches it", f.message);
                g.counterexample = Some(self.counterexample(&path, extra, &[]));
            }
            None if self.graph.complete() => {
                g.severity = Severity::Note;
                g.message = format!("{} — but no run reaches it", f.message);
            }
            None => {}
        }
        g
    }

    /// The first explored state whose next event has both plans applicable.
    fn overlap(&self, a: u32, b: u32) -> Option<u32> {
        let c = self.conditions;
        let k = c.overlaps.iter().position(|&p| p == (a, b))?;
        self.facts.first_holds[c.invariants.len() + c.props.len() + k]
    }

    fn failures(
        &self,
        out: &mut Vec<Finding>,
        actions: BTreeMap<(u32, u32), Failure>,
        goals: BTreeMap<String, Failure>,
    ) {
        let span = self.project.manifest.agent.plans.written.span;
        if actions.is_empty() {
            out.push(self.finding(
                "action-failure",
                "all",
                span,
                self.held(),
                "no action is ever attempted when its precondition does not hold".into(),
            ));
        }
        for x in actions.values() {
            if let Note::ActionFailed {
                text,
                plan,
                span,
                reason,
            } = &x.note
            {
                let loc = self.location(*span);
                let plan = &self.project.plans.plans[*plan as usize];
                let mut f = self.finding(
                    "action-failure",
                    &format!("{}:{}", loc.file, loc.line),
                    *span,
                    Status::Fail,
                    format!("`{text}` in plan {} fails: {reason}", plan.name()),
                );
                f.id = format!("action-failure:{}:{}", loc.file, loc.line);
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(x.src), Some(x), &[]));
                out.push(f);
            }
        }
        if goals.is_empty() {
            out.push(self.finding(
                "goal-failure",
                "all",
                span,
                self.held(),
                "no goal ever fails without a failure plan to handle it".into(),
            ));
        }
        for x in goals.values() {
            if let Note::GoalFailed {
                goal,
                cause,
                span: at,
                reason,
                ..
            } = &x.note
            {
                let place = at.unwrap_or(span);
                let loc = self.location(place);
                let what = if goal == cause {
                    format!("goal {goal} fails ({reason})")
                } else {
                    format!("{cause} fails ({reason}), so goal {goal} fails")
                };
                let mut f = self.finding(
                    "goal-failure",
                    "",
                    place,
                    Status::Fail,
                    format!("{what}, and no failure plan handles it: the intention is dropped"),
                );
                f.id = format!("goal-failure:{}:{}", loc.file, loc.line);
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(x.src), Some(x), &[]));
                out.push(f);
            }
        }
    }

    fn liveness(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let span = self.project.manifest.agent.plans.written.span;
        let n = self.graph.len();
        let loops = self.cyclic_components(|_| true);
        let livelock = loops
            .iter()
            .min_by_key(|c| c.iter().map(|&i| self.graph.depth(i)).min());
        match livelock {
            Some(comp) => {
                let (entry, cycle) = self.lasso_within(comp, |_| true);
                let mut f = self.finding(
                    "livelock",
                    "agent",
                    span,
                    Status::Fail,
                    "the agent can run forever without becoming idle".into(),
                );
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(entry), None, &cycle));
                out.push(f);
            }
            _ => out.push(self.finding(
                "livelock",
                "agent",
                span,
                self.held(),
                "every run ends with the agent idle".into(),
            )),
        }
        // A request pending in every state of a loop is never completed on that run.
        let mut starved: Option<(u8, &Vec<u32>)> = None;
        for comp in &loops {
            let pending = comp
                .iter()
                .fold(u64::MAX, |acc, &i| acc & self.facts.pending(i));
            if pending != 0 {
                starved = Some((pending.trailing_zeros() as u8, comp));
                break;
            }
        }
        match starved {
            Some((r, comp)) => {
                let (entry, cycle) = self.lasso_within(comp, |_| true);
                let goal = &self.agent.sem.requests[r as usize];
                let mut f = self.finding(
                    "request-not-completed",
                    &goal.to_string(),
                    span,
                    Status::Fail,
                    format!("the request !{goal} can stay pending forever"),
                );
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(entry), None, &cycle));
                out.push(f);
            }
            None => out.push(self.finding(
                "request-not-completed",
                "all",
                span,
                self.held(),
                "every request ends (completed or reported as a goal failure)".into(),
            )),
        }
        use crate::syntax::manifest::PropertyKind;
        let eventually = props.iter().filter(|p| p.kind == PropertyKind::Eventually);
        for (p, bad) in eventually.zip(&self.facts.bad) {
            let bad = |i: u32| bit(bad, i);
            // States reachable from an initial state through states where the property
            // never held.
            let mut seen = vec![0u64; n.div_ceil(64)];
            let mut queue: VecDeque<u32> =
                (0..self.graph.initial as u32).filter(|&i| bad(i)).collect();
            queue.iter().for_each(|&i| set_bit(&mut seen, i, true));
            let mut parent: HashMap<u32, u32> = HashMap::new();
            while let Some(i) = queue.pop_front() {
                for &j in self.graph.successors(i).into_iter().flatten() {
                    if bad(j) && !bit(&seen, j) {
                        set_bit(&mut seen, j, true);
                        parent.insert(j, i);
                        queue.push_back(j);
                    }
                }
            }
            let path_in = |target: u32| {
                let mut path = vec![target];
                let mut at = target;
                while let Some(&p) = parent.get(&at) {
                    path.push(p);
                    at = p;
                }
                path.reverse();
                path
            };
            let terminal = (0..n as u32)
                .find(|&i| bit(&seen, i) && self.graph.successors(i).is_some_and(|e| e.is_empty()));
            let loop_comp = self.cyclic_components(|i| bit(&seen, i)).into_iter().next();
            let message = format!("`{}` may never hold", p.name);
            if let Some(t) = terminal {
                let mut f = self.finding(
                    "property",
                    &p.name,
                    p.span,
                    Status::Fail,
                    format!("{message}: a run ends without it"),
                );
                f.counterexample = Some(self.counterexample(&path_in(t), None, &[]));
                out.push(f);
            } else if let Some(comp) = loop_comp {
                let (entry, cycle) = self.lasso_within(&comp, |i| bit(&seen, i));
                let mut f = self.finding(
                    "property",
                    &p.name,
                    p.span,
                    Status::Fail,
                    format!("{message}: a run loops forever without it"),
                );
                f.counterexample = Some(self.counterexample(&path_in(entry), None, &cycle));
                out.push(f);
            } else {
                out.push(self.finding(
                    "property",
                    &p.name,
                    p.span,
                    self.held(),
                    format!("`{}` eventually holds on every run", p.name),
                ));
            }
        }
    }

    /// The strongly connected components, among the states where `keep` holds, that
    /// contain a cycle; each sorted, components in order of their first state. Tarjan's
    /// algorithm with an explicit stack.
    fn cyclic_components(&self, keep: impl Fn(u32) -> bool) -> Vec<Vec<u32>> {
        const UNSEEN: u32 = u32::MAX;
        let n = self.graph.len();
        let succ = |i: u32| -> &[u32] { self.graph.successors(i).unwrap_or(&[]) };
        let mut index = vec![UNSEEN; n];
        let mut low = vec![0u32; n];
        let mut on_stack = vec![0u64; n.div_ceil(64)];
        let mut stack: Vec<u32> = Vec::new();
        let mut next = 0u32;
        let mut comps = Vec::new();
        // (state, position of the next successor to look at)
        let mut calls: Vec<(u32, usize)> = Vec::new();
        for root in 0..n as u32 {
            if index[root as usize] != UNSEEN || !keep(root) {
                continue;
            }
            calls.push((root, 0));
            while let Some(&mut (v, ref mut pos)) = calls.last_mut() {
                if *pos == 0 && index[v as usize] == UNSEEN {
                    index[v as usize] = next;
                    low[v as usize] = next;
                    next += 1;
                    stack.push(v);
                    set_bit(&mut on_stack, v, true);
                }
                let edges = succ(v);
                if let Some(&w) = edges.get(*pos) {
                    *pos += 1;
                    if !keep(w) {
                        continue;
                    }
                    if index[w as usize] == UNSEEN {
                        calls.push((w, 0));
                    } else if bit(&on_stack, w) {
                        low[v as usize] = low[v as usize].min(index[w as usize]);
                    }
                    continue;
                }
                calls.pop();
                if let Some(&(u, _)) = calls.last() {
                    low[u as usize] = low[u as usize].min(low[v as usize]);
                }
                if low[v as usize] == index[v as usize] {
                    let mut comp = Vec::new();
                    while let Some(w) = stack.pop() {
                        on_stack[w as usize / 64] &= !(1 << (w % 64));
                        comp.push(w);
                        if w == v {
                            break;
                        }
                    }
                    let cyclic = comp.len() > 1 || succ(v).contains(&v);
                    if cyclic {
                        comp.sort();
                        comps.push(comp);
                    }
                }
            }
        }
        comps.sort();
        comps
    }

    /// The shallowest state of a loop, and a cycle through it (state indices, ending back at
    /// the entry), staying inside the component and among the states where `keep` holds.
    fn lasso_within(&self, comp: &[u32], keep: impl Fn(u32) -> bool) -> (u32, Vec<u32>) {
        let entry = *comp
            .iter()
            .min_by_key(|&&i| (self.graph.depth(i), i))
            .expect("a component has a state");
        let member = |j: u32| comp.binary_search(&j).is_ok() && keep(j);
        // Breadth-first from the entry back to itself inside the component.
        let mut parent: BTreeMap<u32, u32> = BTreeMap::new();
        let mut queue = VecDeque::from([entry]);
        let mut closing = None;
        'bfs: while let Some(i) = queue.pop_front() {
            for &j in self.graph.successors(i).into_iter().flatten() {
                if !member(j) {
                    continue;
                }
                if j == entry {
                    closing = Some(i);
                    break 'bfs;
                }
                if let std::collections::btree_map::Entry::Vacant(e) = parent.entry(j) {
                    e.insert(i);
                    queue.push_back(j);
                }
            }
        }
        let mut cycle = vec![entry];
        let mut at = closing.unwrap_or(entry);
        while at != entry {
            cycle.push(at);
            at = parent[&at];
        }
        cycle.push(entry);
        // Built backwards from the closing state: entry, ..., entry in run order.
        cycle.reverse();
        (entry, cycle)
    }
}
