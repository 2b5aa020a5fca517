//! `verify` of a project of several agents: every interleaving of their reasoning cycles
//! ([`System`]) is explored, and the checks that one state or one transition decides are
//! made: invariants, `always` and `reachable` properties over the shared environment,
//! action failures and goal failures of every agent, and the deadlock of each agent (it
//! is not done and can never take a step again). Each violation comes with the shortest
//! run to it, every step naming its agent.
//!
//! Instances of one agent are interchangeable: with symmetry on, states equal up to a
//! renaming of them are explored once ([`Instances`]), every run shown is still a concrete
//! run of the system, and a failure found stands for its renamings (another instance's, a
//! goal that names another), each reported with its run renamed, as the full search would.
//!
//! The checks that follow runs for ever (`livelock`, `request-not-completed`, `eventually`)
//! are `liveness`'s, on a search of every interleaving. The explanation properties are
//! [`super::explanation`]'s, on every interleaving as the users watching the robot see it.

use super::explore::{explore_with, Graph, Limits, Options, Walk};
use super::model::{beyond_of, Model};
use super::por::PartialOrder;
use super::symmetry::{AgentPerm, Instances};
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

mod deadlock;
mod liveness;
mod schedule;

use deadlock::{busy_agents, first_stuck, record_busy, Steps};
pub use deadlock::{stuck_from, stuck_states};
pub use schedule::run_schedule;

impl Model for System<'_> {
    type State = SystemState;
    type Label = Step;

    fn init_states(&self) -> Box<dyn Iterator<Item = SystemState> + '_> {
        Box::new(self.initial_states().into_iter())
    }

    fn init_complete(&self) -> bool {
        self.agents[0].project.initial.complete()
    }

    fn next_states(&self, s: &SystemState) -> Vec<(Step, SystemState)> {
        self.successors(s)
    }

    fn beyond(&self, label: &Step) -> Option<(Span, String)> {
        beyond_of(label.notes.iter())
    }
}

/// The interleavings the search follows: the system's, with partial-order reduction
/// when it is on ([`PartialOrder`]), and states stored up to renaming of interchangeable
/// instances when symmetry is on ([`Instances`]).
struct Interleavings<'a, 's> {
    system: &'a System<'s>,
    partial_order: Option<PartialOrder>,
    instances: Option<&'a Instances>,
}

/// A transition the search follows: a step of one agent, and under symmetry over
/// instances the renaming that takes its target to the canonical member of its class
/// (what the search stores it under), so that a check following one agent from state to
/// state knows which agent it is in the next stored state.
#[derive(Clone, Debug)]
struct Move {
    step: Step,
    canon: Option<AgentPerm>,
}

impl Move {
    /// The agent that takes the step; `None` for a request of the user.
    fn mover(&self) -> Option<u8> {
        match self.step.notes.as_slice() {
            [Note::Request { .. }] => None,
            _ => Some(self.step.agent),
        }
    }
}

impl std::ops::Deref for Move {
    type Target = Step;
    fn deref(&self) -> &Step {
        &self.step
    }
}

impl Model for Interleavings<'_, '_> {
    type State = SystemState;
    type Label = Move;

    fn init_states(&self) -> Box<dyn Iterator<Item = SystemState> + '_> {
        Box::new(self.system.initial_states().into_iter())
    }

    fn init_complete(&self) -> bool {
        self.system.agents[0].project.initial.complete()
    }

    fn next_states(&self, s: &SystemState) -> Vec<(Move, SystemState)> {
        self.system
            .successors(s)
            .into_iter()
            .map(|(step, t)| (Move { step, canon: None }, t))
            .collect()
    }

    fn beyond(&self, label: &Move) -> Option<(Span, String)> {
        beyond_of(label.notes.iter())
    }

    fn fingerprint(&self, s: &SystemState) -> u64 {
        match self.instances {
            Some(i) => i.fingerprint(s),
            None => super::explore::fingerprint(s),
        }
    }

    fn fingerprint_labelled(&self, label: &mut Move, s: &SystemState) -> u64 {
        match self.instances {
            Some(i) => {
                let (fp, perm) = i.canonical_renaming(s);
                label.canon = Some(perm);
                fp
            }
            None => super::explore::fingerprint(s),
        }
    }

    fn ample(
        &self,
        s: &SystemState,
        successors: &[(Move, SystemState)],
    ) -> Option<std::ops::Range<usize>> {
        self.partial_order
            .as_ref()
            .and_then(|p| p.ample(self.system, s, successors.iter().map(|(m, t)| (&m.step, t))))
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
    /// The requests pending (of the agent they go to), one bit each.
    pending: u64,
    /// The `eventually` properties that hold, one bit each.
    holds: u64,
    /// The run properties' propositions that hold ([`super::runs::RunAtoms`]).
    letter: super::runs::Letter,
    /// Under symmetry: a renaming of instances that changes what the system does here.
    unequal: Option<String>,
}

/// Explores every interleaving of the agents of `projects` and runs the checks. The
/// findings of `lint` on their plan libraries come first, settled where the runs decide
/// them: a plan some run adopts is not dead nor hidden, a gap no run meets is none, and a
/// non-inductive invariant that every run keeps is a note.
pub fn verify_system(
    projects: &[Project],
    limits: Limits,
    options: &VerifyOptions,
    mut progress: impl FnMut(&str, usize, u32, f64),
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
    // `eventually` properties: decided on runs ([`liveness`]).
    let mut eventually: Vec<(String, Cond, Span)> = Vec::new();
    // `ltl` properties and those with modalities: decided on runs (`check::runs`).
    let (run_props, atomics) = match crate::model::property::compile_in(project, system.names()) {
        Ok(x) => x,
        Err(ds) => {
            errors.extend(ds);
            Default::default()
        }
    };
    let run_atoms =
        (!run_props.is_empty()).then(|| super::runs::RunAtoms::new(&atomics, &system.agents[0]));
    // The propositions read on the interleavings themselves: those of properties not about
    // explanations (which their user's search decides).
    let graph_atoms = run_atoms
        .as_ref()
        .filter(|_| run_props.iter().any(|p| p.user.is_none()));
    for p in &project.manifest.properties {
        if crate::model::property::is_run_property(p) {
            continue;
        }
        match formula::compile_in(
            &p.formula.expr,
            &project.atoms,
            &project.universe,
            system.names(),
        ) {
            Ok(c) if p.kind == PropertyKind::Eventually => {
                eventually.push((p.name.value.clone(), c, p.formula.span))
            }
            Ok(c) => conds.push((p.name.value.clone(), "property", p.kind, c, p.formula.span)),
            Err(d) => errors.push(d),
        }
    }
    if eventually.len() > 64 {
        errors.push(
            Diagnostic::error("input", "more than 64 `eventually` properties")
                .in_file(project.manifest.path.display().to_string()),
        );
    }
    let checked = conds
        .iter()
        .map(|(_, _, _, c, span)| (c, span))
        .chain(eventually.iter().map(|(_, c, span)| (c, span)));
    for (c, span) in checked {
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
    if !errors.is_empty() {
        return Err(errors);
    }
    // The first stored state (in search order, so at least depth) where each condition
    // fails, and where it holds.
    let mut first_fails: Vec<Option<u32>> = vec![None; conds.len()];
    let mut first_holds: Vec<Option<u32>> = vec![None; conds.len()];
    let mut steps = Steps::default();
    let mut busy = Vec::new();
    // Read in both the state and the transition callbacks of the search.
    let facts = std::cell::RefCell::new(liveness::Facts::default());
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
        max_memory: options.max_memory,
        // `simulate`: random runs only.
        sample: options.sample,
        shard: None,
        room_for: 0,
        numbered: true,
        places: 0,
    };
    // The run properties read the exact graph: no reduction when there are any.
    let exact = graph_atoms.is_some();
    let instances = (options.symmetry && !exact).then(|| {
        let named: Vec<(&str, &Cond)> = conds
            .iter()
            .map(|c| (c.0.as_str(), &c.3))
            .chain(eventually.iter().map(|(n, c, _)| (n.as_str(), c)))
            .collect();
        Instances::new(&system, &named)
    });
    let active = instances.as_ref().filter(|i| !i.is_empty());
    let mut unequal: Option<String> = None;
    let model = Interleavings {
        system: &system,
        partial_order: (options.partial_order && !exact).then(|| {
            let read = conds.iter().map(|c| &c.3);
            PartialOrder::new(&system, read.chain(eventually.iter().map(|e| &e.1)))
        }),
        instances: active,
    };
    let summary = |s: &SystemState, renamed: bool| {
        let all = (!conds.is_empty() || !eventually.is_empty()).then(|| system.everything(s));
        Summary {
            fails: match &all {
                Some(all) => conds.iter().map(|(_, _, _, c, _)| !c.eval(all)).collect(),
                None => Vec::new(),
            },
            busy: busy_agents(s),
            pending: s.agents[0].pending_requests(),
            holds: match &all {
                Some(all) => eventually
                    .iter()
                    .enumerate()
                    .filter(|(_, (_, c, _))| c.eval(all))
                    .fold(0, |b, (j, _)| b | 1 << j),
                None => 0,
            },
            letter: graph_atoms
                .map(|r| r.system_letter(&system.everything(s), &s.agents))
                .unwrap_or_default(),
            // Every stored state is checked: reduction is exact only where renaming a
            // state renames its successors.
            unequal: active
                .filter(|_| renamed)
                .and_then(|i| i.equivariance_violation(&system, s)),
        }
    };
    let started = std::time::Instant::now();
    // Per state: its letter; per transition doing a `did` action: those propositions (when
    // there are run properties).
    let mut letters = super::runs::Letters::default();
    let mut did = super::runs::StepLetters::default();
    let graph: Graph<SystemState> = explore_with(
        &model,
        limits,
        &opts,
        |s, _| summary(s, true),
        |i, _, sum| {
            for (j, &fails) in sum.fails.iter().enumerate() {
                let first = if fails {
                    &mut first_fails[j]
                } else {
                    &mut first_holds[j]
                };
                first.get_or_insert(i);
            }
            record_busy(&mut busy, i, sum.busy);
            facts
                .borrow_mut()
                .state(i, sum.busy, sum.pending, sum.holds);
            if graph_atoms.is_some() {
                letters.push(sum.letter);
            }
            if unequal.is_none() {
                unequal = sum.unequal;
            }
        },
        |src, k, label, fp| {
            if let Some(l) =
                graph_atoms.and_then(|r| r.step_letter(label.agent, label.notes.iter()))
            {
                did.insert((src, k), l);
            }
            steps.transition(src, label, fp);
            facts.borrow_mut().transition(src, label.mover());
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
        |n, d, t| progress("search", n, d, t),
    );
    let cx = Cx {
        projects,
        system: &system,
        model: &model,
        graph: &graph,
    };
    let held = if graph.complete() {
        Status::Pass
    } else {
        Status::Unknown
    };
    let n = graph.len();
    let mut findings = Vec::new();
    let mut ltl_phase = None;
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
    let stuck = steps.stuck_forever(&graph, busy, &system, active);
    cx.deadlocks(&mut findings, &first_stuck(&stuck, projects.len()), held);
    // The checks that follow runs need every interleaving, states unrenamed: searched
    // again when a reduction left some out.
    let named: Vec<(String, Span)> = eventually
        .iter()
        .map(|(n, _, span)| (n.clone(), *span))
        .collect();
    // The search of every interleaving for them, if it was another: its states and time.
    let mut liveness_search: Option<(usize, f64)> = None;
    // A reduced search that is complete and has no loop at all stands for a system with
    // no run that goes on for ever (partial-order reduction keeps a run of every run, up to
    // steps no check sees; symmetry, a run of every class of runs), and its runs that end
    // stand for all of them (the conditions read are visible to the reduction, and
    // symmetric): the checks are made on it. (Those about explanations are decided on
    // their user's search, below.)
    if graph_atoms.is_some() {
        let t = std::time::Instant::now();
        let f = facts.borrow();
        let fair = project.manifest.bounds.fair_agents;
        let succ = |i: u32| graph.successors(i);
        // A run ends where nothing can happen, or where every agent is done (the user may
        // stop asking).
        let may_end = |i: u32| {
            graph.successors(i).is_some_and(|e| e.is_empty())
                || f.busy.get(i as usize).is_some_and(|&b| b == 0)
        };
        let enabled = |i: u32| {
            f.moves
                .get(i as usize)
                .map_or(0, |m| m.iter().flatten().fold(0u64, |b, &a| b | 1 << a))
        };
        let mover = |i: u32, k: u32| {
            f.moves
                .get(i as usize)
                .and_then(|m| m.get(k as usize).copied().flatten())
        };
        let recorded = super::runs::RunFacts {
            len: graph.len() as u32,
            initial: graph.initial as u32,
            successors: &succ,
            may_end: &may_end,
            letters: &letters.ids,
            letter_table: &letters.table,
            steps: &did,
            fairness: fair.then_some(super::runs::Fairness {
                agents: system.names().len() as u8,
                enabled: &enabled,
                mover: &mover,
            }),
        };
        let runs = super::runs::agents_runs(fair);
        let mut products = super::runs::Products::default();
        // Those about explanations are decided on their user's search (below).
        for p in run_props.iter().filter(|p| p.user.is_none()) {
            let (status, message, v) =
                super::runs::decide(&recorded, p, (graph.complete(), runs), &mut products);
            let mut x = cx.finding("property", &p.name, p.span, status, String::new());
            x.message = message;
            x.counterexample = v.map(|v| cx.counterexample_via(&v));
            findings.push(x);
        }
        ltl_phase = Some(crate::findings::Phase {
            name: "ltl product".into(),
            seconds: t.elapsed().as_secs_f64(),
            states: Some(products.reached),
            beside: Vec::new(),
        });
    }
    let mut user_phases = Vec::new();
    if let Some(atoms) = &run_atoms {
        for u in crate::model::property::explained_users(&run_props) {
            let props: Vec<&crate::model::property::RunProperty> = run_props
                .iter()
                .filter(|p| p.user.as_deref() == Some(u))
                .collect();
            let (found, phase) = user_runs_among(
                projects,
                &system,
                u,
                &props,
                atoms,
                (limits, &opts),
                &mut progress,
            )?;
            findings.extend(found);
            user_phases.push(phase);
        }
    }
    let reduced = graph.reduced > 0 || active.is_some();
    if reduced && !(graph.complete() && liveness::acyclic(&graph)) {
        let full = Interleavings {
            system: &system,
            partial_order: None,
            instances: None,
        };
        let left = Limits {
            timeout: limits
                .timeout
                .map(|t| (t - started.elapsed().as_secs_f64()).max(0.0)),
            ..limits
        };
        let all_facts = std::cell::RefCell::new(liveness::Facts::default());
        let every: Graph<SystemState> = explore_with(
            &full,
            left,
            &opts,
            |s, _| summary(s, false),
            |i, _, sum| {
                all_facts
                    .borrow_mut()
                    .state(i, sum.busy, sum.pending, sum.holds)
            },
            |src, _, label, _| all_facts.borrow_mut().transition(src, label.mover()),
            |n, d, t| progress("liveness", n, d, t),
        );
        let cx = Cx {
            projects,
            system: &system,
            model: &full,
            graph: &every,
        };
        liveness::liveness(&cx, all_facts.into_inner(), &named, place, &mut findings);
        liveness_search = Some((every.len(), every.seconds));
    } else {
        liveness::liveness(&cx, facts.into_inner(), &named, place, &mut findings);
    }

    let who = |agent: u8| &system.names()[agent as usize];
    cx.failures(
        &mut findings,
        ("action-failure", place, held),
        "no agent ever attempts an action whose precondition does not hold",
        actions.values(),
        |agent, note| match note {
            Note::ActionFailed {
                text,
                plan,
                span,
                reason,
            } => Some((
                (agent, span.file.0, span.start, span.end, String::new()),
                *span,
                format!(
                    "`{text}` of agent `{}` in plan {} fails: {reason}",
                    who(agent),
                    system.agents[agent as usize].plan(*plan).name()
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
        |agent, note| match note {
            Note::GoalFailed {
                goal,
                cause,
                span,
                reason,
                ..
            } => {
                let at = span.unwrap_or(projects[agent as usize].manifest.agent.plans.written.span);
                let what = if goal == cause {
                    format!("goal {goal} of agent `{}` fails ({reason})", who(agent))
                } else {
                    format!(
                        "{cause} fails ({reason}), so goal {goal} of agent `{}` fails",
                        who(agent)
                    )
                };
                Some((
                    (agent, 0, 0, 0, format!("{goal} {cause}")),
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
        let adopted: std::collections::BTreeSet<u32> = same
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
        let adopted = |plan| adopted.contains(&plan);
        super::settle::settle_undecided(&mut all, p, adopted, &gaps, graph.complete());
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
                f.counterexample =
                    Some(cx.counterexample_of(&cx.run(&graph.path_to(x.src), Some(x))));
            }
            None if graph.complete() => {
                f.severity = Severity::Note;
                f.message = format!("{} — but no run reaches it", f.message);
            }
            None => {}
        }
    }
    // The explanation properties: one more search per user, of every interleaving (no
    // reduction: the user sees every step of the robot), each state paired with what the
    // user has seen of the robot.
    let left = Limits {
        timeout: limits
            .timeout
            .map(|t| (t - started.elapsed().as_secs_f64()).max(0.0)),
        ..limits
    };
    let explore_opts = Options {
        threads,
        keep_edges: false,
        ..Options::default()
    };
    let (explained, _, phases) =
        super::explanation::verify_among(projects, &system, left, &explore_opts, &mut progress)?;
    all.extend(explained);
    let mut v = Verification::of(&graph, project, all);
    v.stats.phases.extend(ltl_phase);
    v.stats.phases.extend(user_phases);
    if let Some((states, seconds)) = liveness_search {
        let st = &mut v.stats;
        st.liveness_states = Some(states);
        st.seconds += seconds;
        if st.seconds > 0.0 {
            st.states_per_second = (st.states + states) as f64 / st.seconds;
        }
        st.phases.push(crate::findings::Phase {
            name: "liveness".into(),
            seconds,
            states: Some(states),
            beside: Vec::new(),
        });
    }
    v.stats.phases.extend(phases);
    if let Some(i) = &instances {
        v.symmetric_types = i.describe();
        v.warnings.extend(i.refused.iter().cloned());
    }
    if let Some(r) = unequal {
        v.warnings.push(format!("symmetry reduction treats instances of one agent as interchangeable, but renaming {r} changes what the agents do in a reachable state (Jason perceives several changes of the environment in the hash order of their names, and lists a belief's sources sorted by name): a run of a merged state may have been left out; `--no-symmetry` gives the exact verdict"));
    }
    Ok(v)
}

struct Cx<'a> {
    projects: &'a [Project],
    system: &'a System<'a>,
    model: &'a Interleavings<'a, 'a>,
    graph: &'a Graph<SystemState>,
}

/// A concrete run of the system: its states, and the steps between them.
struct Run {
    states: Vec<SystemState>,
    steps: Vec<Step>,
}

/// The run properties `props` about the explanations `user` gets, among several agents:
/// decided on that user's explanation search (the user watches `[explanation] robot`;
/// loops fair to the agents as the manifest says).
fn user_runs_among(
    projects: &[Project],
    system: &System,
    user: &str,
    props: &[&crate::model::property::RunProperty],
    atoms: &super::runs::RunAtoms,
    bounds: (Limits, &Options),
    progress: &mut impl FnMut(&str, usize, u32, f64),
) -> Result<(Vec<Finding>, crate::findings::Phase), Vec<Diagnostic>> {
    use super::explanation::{Among, Explained};
    let robot = super::explanation::robot_of(projects);
    let users = crate::explain::agent::users(&projects[robot], Some(user))?;
    let ex = crate::explain::agent::Explainer::new(&projects[robot], &system.agents[robot]);
    let model = Explained::watching(Among { system, robot }, &ex, &users[0]);
    let fair = projects[0].manifest.bounds.fair_agents;
    let facts = |s: &SystemState| {
        (
            atoms.system_letter(&system.everything(s), &s.agents),
            busy_agents(s),
        )
    };
    let reading = super::explained_runs::Reading {
        facts: &facts,
        fair_agents: fair.then_some(system.names().len() as u8),
        runs: super::runs::agents_runs(fair),
    };
    Ok(super::explained_runs::decide(
        (&projects[0], &projects[robot]),
        (user, &model),
        (props, atoms),
        reading,
        bounds,
        progress,
    ))
}

/// The key a failure is reported under, per agent (its index first): the file, start and
/// end of an action's step, or a goal failure's goal and cause.
type FailureKey = (u8, u32, u32, u32, String);

/// Whether two notes are one failure, up to the names of interchangeable agents: the same
/// step of the same plan, the same goal signatures.
fn alike(a: &Note, b: &Note) -> bool {
    let shape = |t: &crate::semantics::EventTrigger| {
        (
            t.op,
            t.kind,
            t.literal.functor().map(str::to_string),
            t.literal.arity(),
        )
    };
    match (a, b) {
        (
            Note::ActionFailed {
                span: s, plan: p, ..
            },
            Note::ActionFailed {
                span: t, plan: q, ..
            },
        ) => s == t && p == q,
        (
            Note::GoalFailed {
                goal: g,
                cause: c,
                plan: p,
                span: s,
                ..
            },
            Note::GoalFailed {
                goal: h,
                cause: d,
                plan: q,
                span: t,
                ..
            },
        ) => s == t && p == q && shape(g) == shape(h) && shape(c) == shape(d),
        (Note::NoApplicablePlan(t), Note::NoApplicablePlan(u)) => shape(t) == shape(u),
        _ => false,
    }
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
    /// there is none, one that says so (`none`). `describe` gives a failure's key, place
    /// and message from its agent and note. Under symmetry, every renaming of a failure
    /// found is a failure the full search finds, keyed apart (another agent, a goal with
    /// other names): each is reported, with its run renamed, as that search reports it.
    fn failures<'f>(
        &self,
        out: &mut Vec<Finding>,
        (check, place, held): (&str, Span, Status),
        none: &str,
        failures: impl ExactSizeIterator<Item = &'f Failure>,
        describe: impl Fn(u8, &Note) -> Option<(FailureKey, Span, String)>,
    ) {
        if failures.len() == 0 {
            out.push(self.finding(check, "all", place, held, none.into()));
        }
        // Key -> (depth of the failing state, order found, span, message, run).
        let mut found: BTreeMap<FailureKey, (u32, usize, Span, String, Run)> = BTreeMap::new();
        for (order, x) in failures.enumerate() {
            let depth = self.graph.depth(x.src);
            let run = self.run(&self.graph.path_to(x.src), Some(x));
            // The failure as the run shows it (under symmetry, a renaming of the stored
            // one).
            let last = |run: &Run| {
                run.steps
                    .last()
                    .filter(|_| run.steps.len() == self.graph.depth(x.src) as usize + 1)
                    .and_then(|l| {
                        let n = l.notes.iter().find(|n| alike(n, &x.note))?;
                        Some((l.agent, n.clone()))
                    })
            };
            let (agent, note) = last(&run).unwrap_or((x.agent, x.note.clone()));
            let mut renamed = vec![(agent, note.clone(), run)];
            if let Some(inst) = self.model.instances {
                let mut involved = vec![agent];
                if let Note::GoalFailed { goal, cause, .. } = &note {
                    for t in [&goal.literal, &cause.literal] {
                        involved.extend(inst.named_in(t));
                    }
                }
                let mut distinct = Vec::new();
                for k in involved {
                    if !distinct.contains(&k) {
                        distinct.push(k);
                    }
                }
                let base = &renamed[0].2;
                let mut more = Vec::new();
                for perm in inst.images(&distinct).into_iter().skip(1) {
                    let Some((states, steps)) =
                        inst.rename_run(self.system, &base.states, &base.steps, &perm)
                    else {
                        continue;
                    };
                    let r = Run { states, steps };
                    if let Some((a, n)) = last(&r) {
                        more.push((a, n, r));
                    }
                }
                renamed.extend(more);
            }
            for (agent, note, run) in renamed {
                let Some((key, span, message)) = describe(agent, &note) else {
                    continue;
                };
                let better = found
                    .get(&key)
                    .is_none_or(|(d, o, ..)| (depth, order) < (*d, *o));
                if better {
                    found.insert(key, (depth, order, span, message, run));
                }
            }
        }
        for (_, (_, _, span, message, run)) in found {
            let loc = self.projects[0].map.location(span);
            let name = format!("{}:{}", loc.file, loc.line);
            let mut f = self.finding(check, &name, span, Status::Fail, message);
            f.counterexample = Some(self.counterexample_of(&run));
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
        f.counterexample = Some(self.counterexample_of(&self.run(&self.graph.path_to(at), None)));
        f
    }

    /// The concrete run along `path` (each step the first transition to a state stored
    /// under the next fingerprint: under symmetry, a renaming of the stored state), then
    /// the failing transition `extra` (under symmetry, by an instance of its agent). It
    /// ends early where a step cannot be followed.
    fn run(&self, path: &[u32], extra: Option<&Failure>) -> Run {
        let mut run = Run {
            states: Vec::new(),
            steps: Vec::new(),
        };
        let Some(mut walk) = path
            .first()
            .and_then(|&i| Walk::start(self.model, self.graph, i))
        else {
            return run;
        };
        run.states.push(walk.state.clone());
        for &j in &path[1..] {
            let Some(l) = walk.step_to(j) else {
                return run;
            };
            run.steps.push(l.step);
            run.states.push(walk.state.clone());
        }
        if let Some(x) = extra {
            let fits = |l: &Move| match self.model.instances {
                None => l.agent == x.agent,
                Some(i) => i.alike(l.agent, x.agent) && l.notes.iter().any(|n| alike(n, &x.note)),
            };
            if let Some(l) = walk.step_by(x.k, x.fp, fits) {
                run.steps.push(l.step);
                run.states.push(walk.state.clone());
            }
        }
        run
    }

    /// The run of a run property's violation: each step the transition at the position the
    /// product took (the search was exact), then its loop if it has one.
    fn counterexample_via(&self, v: &super::runs::Violation) -> Counterexample {
        let mut run = Run {
            states: Vec::new(),
            steps: Vec::new(),
        };
        let Some(mut walk) = v
            .path
            .first()
            .and_then(|&i| Walk::start(self.model, self.graph, i))
        else {
            return Counterexample::default();
        };
        run.states.push(walk.state.clone());
        let path = v.path[1..].iter().zip(&v.path_via);
        let cycle = v.cycle.get(1..).unwrap_or(&[]).iter().zip(&v.cycle_via);
        let loop_from = path.len();
        for (&j, &k) in path.chain(cycle) {
            let Some(l) = walk.step_by(k, self.graph.fingerprint(j), |_| true) else {
                break;
            };
            run.steps.push(l.step);
            run.states.push(walk.state.clone());
        }
        self.counterexample_looping(&run, (!v.cycle.is_empty()).then_some(loop_from))
    }

    /// A run as a counterexample: every step names its agent.
    fn counterexample_of(&self, run: &Run) -> Counterexample {
        self.counterexample_looping(run, None)
    }

    /// [`Cx::counterexample_of`] of a run whose steps from `loop_from` on repeat for ever.
    fn counterexample_looping(&self, run: &Run, loop_from: Option<usize>) -> Counterexample {
        let p = &self.projects[0];
        let Some(first) = run.states.first() else {
            return Counterexample::default();
        };
        let initial = first
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
        let mut loop_start = None;
        for (at, label) in run.steps.iter().enumerate() {
            if Some(at) == loop_from {
                loop_start = Some(steps.len());
            }
            let b = &mut builders[label.agent as usize];
            let from = b.steps().len();
            b.push(label.notes.clone());
            for mut st in b.steps()[from..].iter().cloned() {
                st.agent = Some(self.system.names()[label.agent as usize].clone());
                steps.push(st);
            }
        }
        Counterexample {
            initial,
            requests: builders[0].requests().to_vec(),
            steps,
            loop_start,
        }
    }
}
