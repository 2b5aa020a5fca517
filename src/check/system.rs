//! `verify` of a project of several agents: every interleaving of their reasoning cycles
//! ([`System`]) is explored, and the checks that one state or one transition decides are
//! made: invariants, `always` and `reachable` properties over the shared environment,
//! action failures and goal failures of every agent, and deadlock. Each violation comes
//! with the shortest run to it, every step naming its agent.
//!
//! Not yet for several agents, and refused where written: formulas over an agent's mental
//! notes, `eventually` properties, and the explanation checks.

use super::explore::{explore_with, Graph, Limits, Options, Walk};
use super::model::{beyond_of, Model};
use super::por::PartialOrder;
use super::trace::Builder;
use super::Verification;
use super::VerifyOptions;
use crate::findings::{Counterexample, Finding, Status};
use crate::model::cond::Cond;
use crate::model::formula;
use crate::model::project::Project;
use crate::semantics::{Note, Step, System, SystemState};
use crate::syntax::manifest::PropertyKind;
use crate::syntax::{Diagnostic, Severity, Span};
use std::collections::BTreeMap;

impl Model for System<'_> {
    type State = SystemState;
    type Label = Step;

    fn init_states(&self) -> Vec<SystemState> {
        self.initial_states()
    }

    fn next_states(&self, s: &SystemState) -> Vec<(Step, SystemState)> {
        self.successors(s)
    }

    fn beyond(&self, label: &Step) -> Option<(Span, String)> {
        beyond_of(label.notes.iter())
    }
}

/// The interleavings the search follows: the system's, with partial-order reduction
/// when it is on ([`PartialOrder`]).
struct Interleavings<'a, 's> {
    system: &'a System<'s>,
    partial_order: Option<PartialOrder>,
}

impl Model for Interleavings<'_, '_> {
    type State = SystemState;
    type Label = Step;

    fn init_states(&self) -> Vec<SystemState> {
        self.system.initial_states()
    }

    fn next_states(&self, s: &SystemState) -> Vec<(Step, SystemState)> {
        self.system.successors(s)
    }

    fn beyond(&self, label: &Step) -> Option<(Span, String)> {
        beyond_of(label.notes.iter())
    }

    fn ample(
        &self,
        s: &SystemState,
        successors: &[(Step, SystemState)],
    ) -> Option<std::ops::Range<usize>> {
        self.partial_order
            .as_ref()
            .and_then(|p| p.ample(self.system, s, successors))
    }
}

/// A transition that shows a failure: where it starts, its number there, its target's
/// fingerprint, its agent and the note.
struct Failure {
    src: u32,
    k: u32,
    fp: u64,
    agent: u8,
    note: Note,
}

/// What one stored state decides: which conditions fail or hold, and which agents are not
/// done (one bit each).
struct Summary {
    fails: Vec<bool>,
    busy: u64,
}

/// Explores every interleaving of the agents of `projects` and runs the checks. The
/// findings of `lint` on their plan libraries come first, settled where the runs decide
/// them: a plan some run adopts is not dead nor hidden, a gap no run meets is none, and a
/// non-inductive invariant that every run keeps is a note.
pub fn verify_system(
    projects: &[Project],
    limits: Limits,
    options: &VerifyOptions,
    progress: impl FnMut(usize, u32, f64),
    lint: Vec<Finding>,
) -> Result<Verification, Vec<Diagnostic>> {
    let threads = options.threads;
    let project = &projects[0];
    let system = System::new(projects)?;
    let env = &system.agents[0];
    let mut errors = Vec::new();
    let mut conds: Vec<(String, &'static str, PropertyKind, Cond, Span)> = Vec::new();
    let stride = formula::agent_stride(&project.atoms) as u32;
    // Below the stride, the shared environment's atoms; above it, the agents' beliefs.
    let mental = |c: &Cond| {
        c.atoms()
            .into_iter()
            .find(|a| a.0 < stride && !env.is_environment_atom(*a))
    };
    for (name, c) in &project.invariants {
        let span = project
            .manifest
            .invariants
            .iter()
            .find(|i| &i.name.value == name)
            .map_or(Span::default(), |i| i.formula.span);
        conds.push((
            name.clone(),
            "invariant",
            PropertyKind::Always,
            c.clone(),
            span,
        ));
    }
    for p in &project.manifest.properties {
        if p.kind == PropertyKind::Eventually {
            errors.push(
                Diagnostic::error(
                    "input",
                    "an `eventually` property in a project of several agents is not supported yet",
                )
                .with_label(p.formula.span, "here"),
            );
            continue;
        }
        match formula::compile_in(
            &p.formula.expr,
            &project.atoms,
            &project.universe,
            system.names(),
        ) {
            Ok(c) => conds.push((p.name.value.clone(), "property", p.kind, c, p.formula.span)),
            Err(d) => errors.push(d),
        }
    }
    for (_, _, _, c, span) in &conds {
        if let Some(a) = mental(c) {
            errors.push(
                Diagnostic::error(
                    "input",
                    format!(
                        "`{}` is a mental note: in a project of several agents, name whose (`agent::{}`)",
                        project.atoms.display(a, &project.universe),
                        project.atoms.display(a, &project.universe)
                    ),
                )
                .with_label(*span, "this formula"),
            );
        }
    }
    if project.manifest.explanation.is_some() {
        errors.push(
            Diagnostic::error(
                "input",
                "the explanation checks of a project of several agents are not supported yet",
            )
            .in_file(project.manifest.path.display().to_string())
            .with_help("leave `[explanation]` out of this manifest"),
        );
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // The first stored state (in search order, so at least depth) where each condition
    // fails, and where it holds.
    let mut first_fails: Vec<Option<u32>> = vec![None; conds.len()];
    let mut first_holds: Vec<Option<u32>> = vec![None; conds.len()];
    // Per state: the agents not done, and the agents that take a step from it.
    let mut busy: Vec<u64> = Vec::new();
    let mut moves: Vec<u64> = Vec::new();
    let mut actions: BTreeMap<(u8, u32, u32, u32), Failure> = BTreeMap::new();
    let mut goals: BTreeMap<(u8, String), Failure> = BTreeMap::new();
    // Per agent: the plans some run adopts, and the goals some event found no plan for.
    let mut applied: Vec<std::collections::BTreeSet<u32>> =
        vec![Default::default(); projects.len()];
    let mut no_plan: Vec<BTreeMap<(String, usize), Failure>> =
        (0..projects.len()).map(|_| BTreeMap::new()).collect();
    let opts = Options {
        threads,
        keep_edges: true,
        ..Options::default()
    };
    let model = Interleavings {
        system: &system,
        partial_order: options
            .partial_order
            .then(|| PartialOrder::new(&system, conds.iter().map(|c| &c.3))),
    };
    let graph: Graph<SystemState> = explore_with(
        &model,
        limits,
        &opts,
        |s| Summary {
            fails: if conds.is_empty() {
                Vec::new()
            } else {
                let all = system.everything(s);
                conds.iter().map(|(_, _, _, c, _)| !c.eval(&all)).collect()
            },
            busy: (0..s.agents.len())
                .filter(|&k| !s.agents[k].is_idle() || !s.mail[k].is_empty())
                .fold(0, |b, k| b | 1 << k),
        },
        |i, sum| {
            for (j, &fails) in sum.fails.iter().enumerate() {
                let first = if fails {
                    &mut first_fails[j]
                } else {
                    &mut first_holds[j]
                };
                first.get_or_insert(i);
            }
            let i = i as usize;
            if busy.len() <= i {
                busy.resize(i + 1, 0);
            }
            busy[i] = sum.busy;
        },
        |src, k, label, fp| {
            let at = src as usize;
            if moves.len() <= at {
                moves.resize(at + 1, 0);
            }
            moves[at] |= 1 << label.agent;
            for n in &label.notes {
                let x = || Failure {
                    src,
                    k,
                    fp,
                    agent: label.agent,
                    note: n.clone(),
                };
                match n {
                    Note::ActionFailed { span, .. } => {
                        actions
                            .entry((label.agent, span.file.0, span.start, span.end))
                            .or_insert_with(x);
                    }
                    Note::GoalFailed { goal, cause, .. } => {
                        goals
                            .entry((label.agent, format!("{goal} {cause}")))
                            .or_insert_with(x);
                    }
                    Note::Plan { plan, .. } => {
                        applied[label.agent as usize].insert(*plan);
                    }
                    Note::NoApplicablePlan(t) => {
                        let key = (
                            t.literal.functor().unwrap_or("").to_string(),
                            t.literal.arity(),
                        );
                        no_plan[label.agent as usize].entry(key).or_insert_with(x);
                    }
                    _ => {}
                }
            }
        },
        progress,
    );
    let cx = Cx {
        projects,
        system: &system,
        graph: &graph,
    };
    let held = if graph.complete() {
        Status::Pass
    } else {
        Status::Unknown
    };
    let n = graph.len();
    let mut findings = Vec::new();
    for (j, (name, check, kind, _, span)) in conds.iter().enumerate() {
        let f = match (kind, first_fails[j]) {
            (PropertyKind::Reachable, _) => match first_holds[j] {
                Some(i) => cx.reached(
                    check,
                    name,
                    *span,
                    Status::Pass,
                    format!("`{name}` is reached after {} steps", graph.depth(i)),
                    i,
                    Severity::Note,
                ),
                None => cx.finding(
                    check,
                    name,
                    *span,
                    if graph.complete() {
                        Status::Fail
                    } else {
                        Status::Unknown
                    },
                    format!("`{name}` is never reached"),
                ),
            },
            (_, Some(i)) => {
                let what = if *check == "invariant" {
                    format!(
                        "invariant `{name}` is violated after {} steps",
                        graph.depth(i)
                    )
                } else {
                    format!(
                        "`{name}` does not always hold: it is false after {} steps",
                        graph.depth(i)
                    )
                };
                cx.reached(check, name, *span, Status::Fail, what, i, Severity::Error)
            }
            (_, None) => cx.finding(
                check,
                name,
                *span,
                held,
                if *check == "invariant" {
                    format!("invariant `{name}` holds in all {n} reached states")
                } else {
                    format!("`{name}` holds in all {n} reached states")
                },
            ),
        };
        findings.push(f);
    }
    let whole = project.manifest.agent.plans.written.span;
    let place = project
        .manifest
        .agent
        .mas
        .as_ref()
        .map_or(whole, |m| m.written.span);
    busy.resize(n, 0);
    moves.resize(n, 0);
    let stuck = stuck_forever(&graph, &busy, &moves, projects.len());
    for (k, first) in stuck.into_iter().enumerate() {
        let name = &system.names()[k];
        let Some(i) = first else {
            findings.push(cx.finding(
                "deadlock",
                name,
                place,
                held,
                format!("`{name}` can always take a step until it is done"),
            ));
            continue;
        };
        let mut message = if moves[i as usize] == 0 {
            let waiting: Vec<String> = (0..projects.len())
                .filter(|&j| busy[i as usize] >> j & 1 == 1)
                .map(|j| format!("`{}`", system.names()[j]))
                .collect();
            format!(
                "no agent can take a step, but {} {} not done",
                waiting.join(", "),
                if waiting.len() == 1 { "is" } else { "are" }
            )
        } else {
            format!("`{name}` is not done, and can never take a step again")
        };
        // An intention that waits for an answer no agent will send is the likely cause:
        // the finding points at its `.send`.
        let ask = graph.state(&model, i).and_then(|st| {
            st.agents[k]
                .waiting
                .iter()
                .find(|w| w.ask.is_some())
                .map(|w| w.step.3)
        });
        let at = match ask {
            Some(span) => {
                message.push_str(&format!(
                    ": `{name}` waits for the answer to `{}`, which no agent will send",
                    projects[k].map.slice(span).trim()
                ));
                span
            }
            None => place,
        };
        // The run goes on to show what becomes of the agent: the others' steps, taking
        // the first successor each time, until a state comes again or none follows.
        let mut path = graph.path_to(i);
        let mut seen: std::collections::HashMap<u32, usize> =
            std::collections::HashMap::from([(i, path.len() - 1)]);
        let mut loop_from = None;
        while let Some(&j) = graph
            .successors(*path.last().expect("a state"))
            .and_then(|s| s.first())
        {
            path.push(j);
            if let Some(&at) = seen.get(&j) {
                loop_from = Some(at);
                break;
            }
            seen.insert(j, path.len() - 1);
        }
        let mut f = cx.finding("deadlock", name, at, Status::Fail, message);
        f.counterexample = Some(cx.lasso(&path, None, loop_from));
        findings.push(f);
    }
    let who = |x: &Failure| &system.names()[x.agent as usize];
    cx.failures(
        &mut findings,
        ("action-failure", place, held),
        "no agent ever attempts an action whose precondition does not hold",
        actions.values(),
        |x| match &x.note {
            Note::ActionFailed {
                text,
                plan,
                span,
                reason,
            } => Some((
                *span,
                format!(
                    "`{text}` of agent `{}` in plan {} fails: {reason}",
                    who(x),
                    system.agents[x.agent as usize].plan(*plan).name()
                ),
            )),
            _ => None,
        },
    );
    cx.failures(
        &mut findings,
        ("goal-failure", place, held),
        "no agent's goal ever fails without a failure plan to handle it",
        goals.values(),
        |x| match &x.note {
            Note::GoalFailed {
                goal,
                cause,
                span,
                reason,
                ..
            } => {
                let at =
                    span.unwrap_or(projects[x.agent as usize].manifest.agent.plans.written.span);
                let what = if goal == cause {
                    format!("goal {goal} of agent `{}` fails ({reason})", who(x))
                } else {
                    format!(
                        "{cause} fails ({reason}), so goal {goal} of agent `{}` fails",
                        who(x)
                    )
                };
                Some((
                    at,
                    format!("{what}, and no failure plan handles it: the intention is dropped"),
                ))
            }
            _ => None,
        },
    );
    let mut all = lint;
    all.extend(findings);
    // Instances share their library: what one adopts, the file's plans have.
    let mut settled: Vec<&std::path::Path> = Vec::new();
    for p in projects {
        let file = p.manifest.agent.plans.path.as_path();
        if settled.contains(&file) {
            continue;
        }
        settled.push(file);
        let same: Vec<usize> = (0..projects.len())
            .filter(|&j| projects[j].manifest.agent.plans.path == file)
            .collect();
        let adopted = same
            .iter()
            .flat_map(|&j| applied[j].iter().copied())
            .collect();
        let mut gaps = BTreeMap::new();
        for &j in &same {
            for (key, x) in &no_plan[j] {
                gaps.entry(key.clone()).or_insert(super::failures::Failure {
                    src: x.src,
                    k: x.k,
                    fp: x.fp,
                    note: x.note.clone(),
                });
            }
        }
        super::settle::settle_undecided(&mut all, p, &adopted, &gaps, graph.complete());
    }
    super::settle::settle_non_inductive(&mut all, project, graph.complete());
    // A warning of lint about one step or plan: reached by a run, an error with that run;
    // reached by none (every state explored), a note.
    for f in all.iter_mut() {
        if f.status != Status::Fail || f.severity != Severity::Warning {
            continue;
        }
        let Some(span) = f.span else { continue };
        let reached = match f.check.as_str() {
            "precondition" => actions
                .values()
                .find(|x| matches!(&x.note, Note::ActionFailed { span: s, .. } if *s == span)),
            "coverage-gap" => (0..projects.len()).find_map(|k| {
                let plan = projects[k].plans.plans.iter().find(|p| p.span == span)?;
                let t = &plan.trigger.literal;
                no_plan[k].get(&(t.functor().unwrap_or("").to_string(), t.arity()))
            }),
            _ => continue,
        };
        match reached {
            Some(x) => {
                f.severity = Severity::Error;
                f.message = format!("{} — and a run reaches it", f.message);
                f.counterexample = Some(cx.counterexample(&graph.path_to(x.src), Some(x)));
            }
            None if graph.complete() => {
                f.severity = Severity::Note;
                f.message = format!("{} — but no run reaches it", f.message);
            }
            None => {}
        }
    }
    Ok(Verification::of(&graph, project, all))
}

/// For each agent, the first state (in search order, so at least depth) where it is not
/// done and can never take a step again: no run from there reaches a state where it takes
/// one. A state the search did not expand completely may lead anywhere.
fn stuck_forever(
    graph: &Graph<SystemState>,
    busy: &[u64],
    moves: &[u64],
    agents: usize,
) -> Vec<Option<u32>> {
    let n = graph.len();
    // Predecessors, as one array sliced by state.
    let mut start = vec![0usize; n + 1];
    for i in 0..n as u32 {
        for &j in graph.successors(i).unwrap_or(&[]) {
            start[j as usize + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut preds = vec![0u32; start[n]];
    for i in 0..n as u32 {
        for &j in graph.successors(i).unwrap_or(&[]) {
            preds[fill[j as usize]] = i;
            fill[j as usize] += 1;
        }
    }
    (0..agents)
        .map(|k| {
            let bit = 1u64 << k;
            if busy.iter().all(|b| b & bit == 0) {
                return None;
            }
            let mut may_move: Vec<bool> = (0..n as u32)
                .map(|i| moves[i as usize] & bit != 0 || graph.successors(i).is_none())
                .collect();
            let mut queue: Vec<u32> = (0..n as u32).filter(|&i| may_move[i as usize]).collect();
            while let Some(j) = queue.pop() {
                for &i in &preds[start[j as usize]..start[j as usize + 1]] {
                    if !may_move[i as usize] {
                        may_move[i as usize] = true;
                        queue.push(i);
                    }
                }
            }
            (0..n as u32).find(|&i| busy[i as usize] & bit != 0 && !may_move[i as usize])
        })
        .collect()
}

struct Cx<'a> {
    projects: &'a [Project],
    system: &'a System<'a>,
    graph: &'a Graph<SystemState>,
}

impl Cx<'_> {
    fn finding(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
    ) -> Finding {
        let at = (span, self.projects[0].map.location(span));
        super::checker::dynamic_finding(check, name, at, status, message)
    }

    /// One failing finding per failure, with its run (its id `check:file:line`), or, when
    /// there is none, one that says so (`none`).
    fn failures<'f>(
        &self,
        out: &mut Vec<Finding>,
        (check, place, held): (&str, Span, Status),
        none: &str,
        failures: impl ExactSizeIterator<Item = &'f Failure>,
        describe: impl Fn(&Failure) -> Option<(Span, String)>,
    ) {
        if failures.len() == 0 {
            out.push(self.finding(check, "all", place, held, none.into()));
        }
        for x in failures {
            let Some((span, message)) = describe(x) else {
                continue;
            };
            let loc = self.projects[0].map.location(span);
            let name = format!("{}:{}", loc.file, loc.line);
            let mut f = self.finding(check, &name, span, Status::Fail, message);
            f.counterexample = Some(self.counterexample(&self.graph.path_to(x.src), Some(x)));
            out.push(f);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn reached(
        &self,
        check: &str,
        name: &str,
        span: Span,
        status: Status,
        message: String,
        at: u32,
        severity: Severity,
    ) -> Finding {
        let mut f = self.finding(check, name, span, status, message);
        f.severity = severity;
        f.counterexample = Some(self.counterexample(&self.graph.path_to(at), None));
        f
    }

    /// The run along `path`, then the failing transition `extra`: every step names its
    /// agent.
    fn counterexample(&self, path: &[u32], extra: Option<&Failure>) -> Counterexample {
        self.lasso(path, extra, None)
    }

    /// [`Cx::counterexample`] of a run that ends in a loop: `path[loop_from..]` is a cycle
    /// (its last state is `path[loop_from]`).
    fn lasso(
        &self,
        path: &[u32],
        extra: Option<&Failure>,
        loop_from: Option<usize>,
    ) -> Counterexample {
        let p = &self.projects[0];
        let Some(mut walk) = path
            .first()
            .and_then(|&i| Walk::start(self.system, self.graph, i))
        else {
            return Counterexample::default();
        };
        let initial = walk
            .state
            .world
            .iter()
            .map(|a| p.atoms.display(a, &p.universe))
            .collect();
        let mut builders: Vec<Builder> = self
            .projects
            .iter()
            .zip(&self.system.agents)
            .map(|(p, sem)| Builder::new(p, sem))
            .collect();
        let mut steps = Vec::new();
        let mut push = |label: Option<Step>, steps: &mut Vec<crate::findings::TraceStep>| {
            let Some(label) = label else { return };
            let b = &mut builders[label.agent as usize];
            let from = b.steps().len();
            b.push(label.notes);
            for mut st in b.steps()[from..].iter().cloned() {
                st.agent = Some(self.system.names()[label.agent as usize].clone());
                steps.push(st);
            }
        };
        let mut loop_start = None;
        for (at, &j) in path.iter().enumerate().skip(1) {
            if Some(at - 1) == loop_from {
                loop_start = Some(steps.len());
            }
            let l = walk.step_to(j);
            push(l, &mut steps);
        }
        if let Some(x) = extra {
            let l = walk.step_by(x.k, x.fp, |l: &Step| l.agent == x.agent);
            push(l, &mut steps);
        }
        Counterexample {
            initial,
            requests: builders[0].requests().to_vec(),
            steps,
            loop_start,
        }
    }
}

/// Most states [`stuck_from`] looks at.
const MAX_STUCK_STATES: usize = 1 << 20;

/// Whether agent `k`, not done in `s`, can never take a step again: no run from `s`
/// reaches a state where it takes one. `None` when more than [`MAX_STUCK_STATES`] states
/// would have to be looked at to tell.
pub fn stuck_from(system: &System, s: &SystemState, k: usize) -> Option<bool> {
    use std::collections::HashSet;
    let busy = !s.agents[k].is_idle() || !s.mail[k].is_empty();
    if !busy {
        return Some(false);
    }
    let mut seen: HashSet<u64> = HashSet::from([super::explore::fingerprint(s)]);
    let mut frontier = vec![s.clone()];
    while let Some(st) = frontier.pop() {
        for (label, t) in system.successors(&st) {
            if label.agent as usize == k {
                return Some(false);
            }
            if seen.insert(super::explore::fingerprint(&t)) {
                if seen.len() > MAX_STUCK_STATES {
                    return None;
                }
                frontier.push(t);
            }
        }
    }
    Some(true)
}

/// One run on a fixed schedule, as the Jason lab's driver runs a recorded scenario: before
/// each cycle, the next request goes to the first agent when it is idle, has perceived the
/// environment and has no mail; then the scheduled agent runs one reasoning cycle (none
/// when it has nothing to do, or only timers while another agent has something to do:
/// the lab's clock moves only when none has). Where a cycle has several outcomes (a timer that may fire,
/// `.random`), the one whose actions continue `want` (`agent: action`, in order) is taken,
/// depth first. Returns the steps of the run that gives `want`, or of the first run when
/// none does.
pub fn run_schedule(
    system: &System,
    start: SystemState,
    requests: &[u8],
    schedule: &[usize],
    want: &[String],
) -> Vec<Step> {
    struct Search<'a, 's> {
        system: &'a System<'s>,
        requests: &'a [u8],
        schedule: &'a [usize],
        want: &'a [String],
        actions: Vec<String>,
        steps: Vec<Step>,
        first: Option<Vec<Step>>,
    }
    impl Search<'_, '_> {
        fn go(&mut self, mut s: SystemState, at: usize, mut next_request: usize) -> bool {
            let system = self.system;
            if next_request < self.requests.len()
                && s.agents[0].is_idle()
                && s.mail[0].is_empty()
                && system.has_perceived(&s, 0)
            {
                let r = self.requests[next_request] as usize;
                system.agents[0].post_request(&mut s.agents[0], r);
                self.steps.push(Step {
                    agent: 0,
                    notes: vec![Note::Request { index: r as u8 }],
                });
                next_request += 1;
            }
            if at == self.schedule.len() {
                if self.first.is_none() {
                    self.first = Some(self.steps.clone());
                }
                return self.actions == self.want;
            }
            let k = self.schedule[at];
            // The lab's clock moves only when no agent has anything else to do: an agent
            // with nothing to do but wait for its timers lets one fire only then, and its
            // cycle changes nothing otherwise (as one with nothing to do at all).
            let quiet = (0..s.agents.len()).all(|j| !system.enabled(&s, j) || system.asleep(&s, j));
            let mut outcomes = if system.enabled(&s, k) && (quiet || !system.asleep(&s, k)) {
                system.cycle_of(&s, k)
            } else {
                Vec::new()
            };
            if outcomes.is_empty() {
                let idle = Step {
                    agent: k as u8,
                    notes: Vec::new(),
                };
                outcomes.push((idle, s.clone()));
            }
            let name = &system.names()[k];
            let (acted, stepped) = (self.actions.len(), self.steps.len());
            for (step, t) in outcomes {
                for n in &step.notes {
                    if let Note::Action { text, .. } = n {
                        self.actions.push(format!("{name}: {text}"));
                    }
                }
                let n = self.actions.len();
                let fits = n <= self.want.len() && self.actions[..] == self.want[..n];
                self.steps.push(step);
                if (fits || self.first.is_none()) && self.go(t, at + 1, next_request) {
                    return true;
                }
                self.actions.truncate(acted);
                self.steps.truncate(stepped);
            }
            false
        }
    }
    let mut search = Search {
        system,
        requests,
        schedule,
        want,
        actions: Vec::new(),
        steps: Vec::new(),
        first: None,
    };
    if search.go(start, 0, 0) {
        search.steps
    } else {
        search.first.unwrap_or_default()
    }
}
