//! Exhaustive exploration and the dynamic checks of SPEC §3: `invariant`, `property`
//! (`always`, `eventually`, `reachable`), `action-failure`, `goal-failure`, `deadlock`,
//! `livelock`, `request-not-completed`.
//!
//! Safety violations come with the shortest run that reaches them (breadth-first parent
//! links). Liveness violations come as a lasso: the shortest run to a loop, then the loop,
//! found on the strongly connected components of the explored graph (petgraph's
//! `kosaraju_scc`, which is iterative, so deep graphs do not overflow the stack). The
//! scheduling of intentions is round-robin, which is fair, so every loop of the graph is a
//! run the agent can really take.

pub mod explore;
pub mod model;
pub mod trace;

use crate::model::cond::Cond;
use crate::model::formula;
use crate::model::project::Project;
use crate::report::{Counterexample, Finding, Stats, Status};
use crate::semantics::{Note, Semantics, State};
use crate::syntax::{Diagnostic, Severity, Span};
use explore::{explore, Bound, Graph, Limits};
use petgraph::graphmap::DiGraphMap;
use std::collections::{BTreeMap, HashSet, VecDeque};

/// What `verify` found.
pub struct Verification {
    /// One finding per check (failing, passing or undecided).
    pub findings: Vec<Finding>,
    /// Search statistics.
    pub stats: Stats,
    /// The bound that stopped the search, if any.
    pub bound: Option<Bound>,
}

/// A compiled state property.
struct Prop {
    name: String,
    kind: crate::syntax::manifest::PropertyKind,
    cond: Cond,
    span: Span,
}

/// Explores the project's state space and runs every dynamic check. The static findings
/// in `lint` are settled against the explored states as SPEC §3 says: a warning that some
/// run reaches becomes an error with that run; one no run reaches becomes a note (when the
/// search was complete); every other finding is kept as it is.
pub fn verify(
    project: &Project,
    limits: Limits,
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
    // First (hence shallowest-source) transition of each failure, keyed by place.
    let mut action_failures: BTreeMap<(u32, u32), (u32, u32, Note)> = BTreeMap::new();
    let mut goal_failures: BTreeMap<String, (u32, u32, Note)> = BTreeMap::new();
    let mut no_plan: BTreeMap<(String, usize), (u32, u32)> = BTreeMap::new();
    let graph = explore(
        &sem,
        limits,
        |src, k, notes: &Vec<Note>| {
            for n in notes {
                match n {
                    Note::ActionFailed { span, .. } => {
                        action_failures.entry((span.file.0, span.start)).or_insert((
                            src,
                            k,
                            n.clone(),
                        ));
                    }
                    Note::GoalFailed { goal, span, .. } => {
                        let key = match span {
                            Some(sp) => format!("{}:{}", sp.file.0, sp.start),
                            None => goal.to_string(),
                        };
                        goal_failures.entry(key).or_insert((src, k, n.clone()));
                    }
                    Note::NoApplicablePlan(t) => {
                        let key = (
                            t.literal.functor().unwrap_or("").to_string(),
                            t.literal.arity(),
                        );
                        no_plan.entry(key).or_insert((src, k));
                    }
                    _ => {}
                }
            }
        },
        progress,
    );
    let c = Checker {
        project,
        sem: &sem,
        graph: &graph,
    };
    let mut findings: Vec<Finding> = lint
        .iter()
        .map(|f| c.settle(f, &action_failures, &no_plan))
        .collect();
    c.safety(&mut findings, &props);
    c.failures(&mut findings, action_failures, goal_failures);
    c.liveness(&mut findings, &props);
    let seconds = graph.seconds;
    let stats = Stats {
        initial_states: graph.initial,
        states: graph.states.len(),
        transitions: graph.transitions,
        depth: graph.max_depth() as usize,
        seconds,
        states_per_second: if seconds > 0.0 {
            graph.states.len() as f64 / seconds
        } else {
            0.0
        },
        complete: graph.complete(),
    };
    Ok(Verification {
        findings,
        stats,
        bound: graph.bound,
    })
}

/// A run reaching a state: the path to it, and the transition taken there, if any.
type Reach = (Vec<u32>, Option<(u32, u32)>);

struct Checker<'a> {
    project: &'a Project,
    sem: &'a Semantics<'a>,
    graph: &'a Graph,
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
        extra: Option<(u32, u32)>,
        cycle: &[u32],
    ) -> Counterexample {
        trace::counterexample(self.project, self.sem, self.graph, path, extra, cycle)
    }

    fn safety(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let states = &self.graph.states;
        let n = states.len();
        for (name, cond) in &self.project.invariants {
            let span = self
                .project
                .manifest
                .invariants
                .iter()
                .find(|i| &i.name.value == name)
                .map_or(Span::default(), |i| i.formula.span);
            match (0..n).find(|&i| !cond.eval(&states[i].beliefs)) {
                Some(i) => {
                    let mut f = self.finding(
                        "invariant",
                        name,
                        span,
                        Status::Fail,
                        format!(
                            "invariant `{name}` is violated after {} steps",
                            self.graph.depth[i]
                        ),
                    );
                    f.counterexample =
                        Some(self.counterexample(&self.graph.path_to(i as u32), None, &[]));
                    out.push(f);
                }
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
        for p in props {
            match p.kind {
                PropertyKind::Always => match (0..n).find(|&i| !p.cond.eval(&states[i].beliefs)) {
                    Some(i) => {
                        let mut f = self.finding(
                            "property",
                            &p.name,
                            p.span,
                            Status::Fail,
                            format!(
                                "`{}` does not always hold: it is false after {} steps",
                                p.name, self.graph.depth[i]
                            ),
                        );
                        f.counterexample =
                            Some(self.counterexample(&self.graph.path_to(i as u32), None, &[]));
                        out.push(f);
                    }
                    None => out.push(self.finding(
                        "property",
                        &p.name,
                        p.span,
                        self.held(),
                        format!("`{}` holds in all {n} reached states", p.name),
                    )),
                },
                PropertyKind::Reachable => {
                    match (0..n).find(|&i| p.cond.eval(&states[i].beliefs)) {
                        Some(i) => {
                            let mut f = self.finding(
                                "property",
                                &p.name,
                                p.span,
                                Status::Pass,
                                format!(
                                    "`{}` is reached after {} steps (witness run attached)",
                                    p.name, self.graph.depth[i]
                                ),
                            );
                            f.counterexample =
                                Some(self.counterexample(&self.graph.path_to(i as u32), None, &[]));
                            out.push(f);
                        }
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
                    }
                }
                PropertyKind::Eventually => {}
            }
        }
        // Deadlock: a state with nothing to do that is not a finished run. Such states cannot
        // arise from this semantics' rules; the check guards them.
        let stuck = (0..n).find(|&i| {
            let s = &states[i];
            self.graph.edges[i].as_ref().is_some_and(|e| e.is_empty()) && !self.is_done(s)
        });
        let span = self.project.manifest.agent.plans.written.span;
        match stuck {
            Some(i) => {
                let mut f = self.finding(
                    "deadlock",
                    "agent",
                    span,
                    Status::Fail,
                    "the agent is stuck: no step is possible, but it is not done".into(),
                );
                f.counterexample =
                    Some(self.counterexample(&self.graph.path_to(i as u32), None, &[]));
                out.push(f);
            }
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
        action_failures: &BTreeMap<(u32, u32), (u32, u32, Note)>,
        no_plan: &BTreeMap<(String, usize), (u32, u32)>,
    ) -> Finding {
        let settles = matches!(
            f.check.as_str(),
            "coverage-gap" | "plan-overlap" | "precondition"
        );
        if !settles || f.status != Status::Fail || f.severity != Severity::Warning {
            return f.clone();
        }
        let Some(span) = f.span else { return f.clone() };
        let plan_at = |sp: Span| self.project.plans.plans.iter().position(|p| p.span == sp);
        let reached: Option<Reach> = match f.check.as_str() {
            "precondition" => action_failures
                .get(&(span.file.0, span.start))
                .map(|(src, k, _)| (self.graph.path_to(*src), Some((*src, *k)))),
            "coverage-gap" => plan_at(span).and_then(|i| {
                let t = &self.project.plans.plans[i].trigger.literal;
                no_plan
                    .get(&(t.functor().unwrap_or("").to_string(), t.arity()))
                    .map(|(src, k)| (self.graph.path_to(*src), Some((*src, *k))))
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
        (0..self.graph.states.len() as u32).find(|&i| {
            let s = &self.graph.states[i as usize];
            let Some(ev) = s.events.first() else {
                return false;
            };
            let applicable = self.sem.applicable(s, &ev.trigger, false);
            applicable.iter().any(|(p, _)| *p == a) && applicable.iter().any(|(p, _)| *p == b)
        })
    }

    /// A state with no successor ends a run when the agent is idle there (requests that
    /// could still arrive would be successors).
    fn is_done(&self, s: &State) -> bool {
        s.is_idle()
    }

    fn failures(
        &self,
        out: &mut Vec<Finding>,
        actions: BTreeMap<(u32, u32), (u32, u32, Note)>,
        goals: BTreeMap<String, (u32, u32, Note)>,
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
        for (src, k, note) in actions.values() {
            if let Note::ActionFailed {
                text,
                plan,
                span,
                reason,
            } = note
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
                    Some(self.counterexample(&self.graph.path_to(*src), Some((*src, *k)), &[]));
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
        for (src, k, note) in goals.values() {
            if let Note::GoalFailed {
                goal,
                cause,
                span: at,
                reason,
                ..
            } = note
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
                    Some(self.counterexample(&self.graph.path_to(*src), Some((*src, *k)), &[]));
                out.push(f);
            }
        }
    }

    fn liveness(&self, out: &mut Vec<Finding>, props: &[Prop]) {
        let span = self.project.manifest.agent.plans.written.span;
        let n = self.graph.states.len();
        let all: Vec<bool> = vec![true; n];
        let loops = self.cyclic_components(&all);
        let livelock = loops
            .iter()
            .min_by_key(|c| c.iter().map(|&i| self.graph.depth[i as usize]).min());
        match livelock {
            Some(comp) => {
                let (entry, cycle) = self.lasso(comp);
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
            let pending = comp.iter().fold(u64::MAX, |acc, &i| {
                acc & self.graph.states[i as usize].pending_requests()
            });
            if pending != 0 {
                starved = Some((pending.trailing_zeros() as u8, comp));
                break;
            }
        }
        match starved {
            Some((r, comp)) => {
                let (entry, cycle) = self.lasso(comp);
                let goal = &self.sem.requests[r as usize];
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
        for p in props.iter().filter(|p| p.kind == PropertyKind::Eventually) {
            let bad: Vec<bool> = self
                .graph
                .states
                .iter()
                .map(|s| !p.cond.eval(&s.beliefs))
                .collect();
            // States reachable from an initial state through states where the property
            // never held.
            let mut seen = vec![false; n];
            let mut queue: VecDeque<u32> = (0..self.graph.initial as u32)
                .filter(|&i| bad[i as usize])
                .collect();
            queue.iter().for_each(|&i| seen[i as usize] = true);
            let mut parent: Vec<Option<u32>> = vec![None; n];
            while let Some(i) = queue.pop_front() {
                for &j in self.graph.edges[i as usize].iter().flatten() {
                    if bad[j as usize] && !seen[j as usize] {
                        seen[j as usize] = true;
                        parent[j as usize] = Some(i);
                        queue.push_back(j);
                    }
                }
            }
            let path_in = |target: u32| {
                let mut path = vec![target];
                let mut at = target;
                while let Some(p) = parent[at as usize] {
                    path.push(p);
                    at = p;
                }
                path.reverse();
                path
            };
            let terminal = (0..n as u32).find(|&i| {
                seen[i as usize]
                    && self.graph.edges[i as usize]
                        .as_ref()
                        .is_some_and(|e| e.is_empty())
            });
            let loop_comp = self.cyclic_components(&seen).into_iter().next();
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
                let (entry, cycle) = self.lasso_within(&comp, &seen);
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
    /// contain a cycle; each sorted, components in order of their first state.
    fn cyclic_components(&self, keep: &[bool]) -> Vec<Vec<u32>> {
        let mut g: DiGraphMap<u32, ()> = DiGraphMap::new();
        for (i, edges) in self.graph.edges.iter().enumerate() {
            if !keep[i] {
                continue;
            }
            g.add_node(i as u32);
            for &j in edges.iter().flatten() {
                if keep[j as usize] {
                    g.add_edge(i as u32, j, ());
                }
            }
        }
        let mut comps: Vec<Vec<u32>> = petgraph::algo::kosaraju_scc(&g)
            .into_iter()
            .filter(|c| c.len() > 1 || g.contains_edge(c[0], c[0]))
            .map(|mut c| {
                c.sort();
                c
            })
            .collect();
        comps.sort();
        comps
    }

    /// The shallowest state of a loop, and a cycle through it (state indices, ending back at
    /// the entry), staying inside the component.
    fn lasso(&self, comp: &[u32]) -> (u32, Vec<u32>) {
        let keep: Vec<bool> = {
            let mut k = vec![false; self.graph.states.len()];
            comp.iter().for_each(|&i| k[i as usize] = true);
            k
        };
        self.lasso_within(comp, &keep)
    }

    fn lasso_within(&self, comp: &[u32], keep: &[bool]) -> (u32, Vec<u32>) {
        let members: HashSet<u32> = comp.iter().copied().collect();
        let entry = *comp
            .iter()
            .min_by_key(|&&i| (self.graph.depth[i as usize], i))
            .expect("a component has a state");
        // Breadth-first from the entry back to itself inside the component.
        let mut parent: BTreeMap<u32, u32> = BTreeMap::new();
        let mut queue = VecDeque::from([entry]);
        let mut closing = None;
        'bfs: while let Some(i) = queue.pop_front() {
            for &j in self.graph.edges[i as usize].iter().flatten() {
                if !members.contains(&j) || !keep[j as usize] {
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
