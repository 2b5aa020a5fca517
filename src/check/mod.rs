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

/// The dynamic checks, by name.
pub const CHECKS: &[&str] = &[
    "invariant",
    "property",
    "action-failure",
    "goal-failure",
    "deadlock",
    "livelock",
    "request-not-completed",
];

pub mod buchi;
pub mod explanation;
pub mod explore;
pub mod model;
pub mod por;
pub mod run;
pub mod runs;
pub mod sample;
pub mod store;
pub mod symmetry;
pub mod system;
pub mod trace;

mod checker;
mod chunked;
mod explained_runs;
mod failures;
mod liveness;
mod parents;
use crate::semantics::recent;
mod safety;
mod search;
mod settle;
mod slots;

/// Whether a verification frees its searches' structures when it is done with them
/// (the default), or leaves them to the process's exit ([`leave_memory_to_exit`]).
static FREE_WHEN_DONE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

/// Leaves the searches' structures (graphs, stores, memo tables) to the process's exit
/// instead of freeing them when a verification is done with them: for a program that
/// exits right after one verification, as the command line does. Freeing tens of millions
/// of small allocations one by one took 3% of the kitchen's run with both users (5 cups),
/// on the thread whose search ended last.
pub fn leave_memory_to_exit() {
    FREE_WHEN_DONE.store(false, std::sync::atomic::Ordering::Relaxed);
}

/// Frees `x`, or leaves it to the process's exit ([`leave_memory_to_exit`]).
pub(crate) fn done_with<T>(x: T) {
    if FREE_WHEN_DONE.load(std::sync::atomic::Ordering::Relaxed) {
        drop(x);
    } else {
        std::mem::forget(x);
    }
}

use crate::findings::{Finding, Stats, Status};
use crate::model::formula;
use crate::model::project::Project;
use crate::semantics::{Compiled, Note, Packed, Semantics, State};
use crate::syntax::{Diagnostic, Span};
use checker::Checker;
use explore::{Bound, Limits, Options};
use failures::Failures;
use model::{Agent, CompiledAgent};
use safety::Prop;
use search::{search_agent, Conditions, Facts, Plans};
use settle::{settle_non_inductive, settle_undecided, settles};

/// What `verify` found.
pub struct Verification {
    /// One finding per check (failing, passing or undecided).
    pub findings: Vec<Finding>,
    /// Search statistics.
    pub stats: Stats,
    /// The bound that stopped the search, if any.
    pub bound: Option<Bound>,
    /// With [`Bound::Beyond`]: where the first run left the model (`file:line:col`), the
    /// step and why.
    pub beyond: Option<String>,
    /// Bytes held by the visited-state store and by the edges at the end of the search.
    pub memory: (usize, usize),
    /// Peak resident memory of the process, in bytes (0 if unknown).
    pub peak_memory: u64,
    /// The symmetric types (and how many objects each has) when symmetry reduction was on;
    /// with several agents, the groups of interchangeable instances (and their sizes).
    pub symmetric_types: Vec<(String, usize)>,
    /// States the search followed through an ample set only (partial-order reduction):
    /// their counterexamples may be longer than the shortest.
    pub reduced_states: usize,
    /// When symmetry reduction was on and the agent does not treat the objects alike (a
    /// reachable state whose renaming has other successors than its successors renamed):
    /// the renaming, and which plans the stored state was about to use.
    pub symmetry_caveat: Option<String>,
    /// What else the report must say about how the search was reduced (symmetry over
    /// instances of one agent: the groups left out and why, where renaming them changes
    /// what the agents do).
    pub warnings: Vec<String>,
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
    /// Follow random runs only (`simulate`), not every state.
    pub sample: Option<sample::Sample>,
    /// Partial-order reduction among several agents ([`por`]).
    pub partial_order: bool,
    /// The users' explanation searches read the agent's graph, stored by its exact search
    /// on the compiled cycle ([`explanation::AloneStored`]), instead of running the cycle
    /// again. Off, they run it: the two give the same report.
    pub stored_users: bool,
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
            sample: None,
            partial_order: true,
            stored_users: true,
        }
    }
}

/// Explores the project's state space and runs every dynamic check, with the default
/// [`VerifyOptions`].
pub fn verify(
    project: &Project,
    limits: Limits,
    mut progress: impl FnMut(usize, u32, f64),
    lint: &[Finding],
) -> Result<Verification, Vec<Diagnostic>> {
    let progress = |_: &str, n, d, t| progress(n, d, t);
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
    mut progress: impl FnMut(&str, usize, u32, f64),
    lint: &[Finding],
) -> Result<Verification, Vec<Diagnostic>> {
    let started = std::time::Instant::now();
    // `--timeout` bounds the whole run: each search after the agent's has what is left.
    let remaining = || Limits {
        timeout: limits
            .timeout
            .map(|t| (t - started.elapsed().as_secs_f64()).max(0.0)),
        ..limits
    };
    let sem = Semantics::new(project)?;
    let symmetry = if opts.symmetry {
        symmetry::Symmetry::new(project, &sem)?
    } else {
        None
    };
    // Decided on runs: properties with a modality or temporal operators, and under symmetry
    // the state properties that name objects unlike (a search that fixes them decides
    // those: see symmetry::RunPlan).
    let on_runs = |p: &crate::syntax::manifest::Property| {
        crate::model::property::is_run_property(p)
            || symmetry
                .as_ref()
                .is_some_and(|s| !s.is_symmetric(project, &p.formula.text, &p.formula.expr))
    };
    let mut errors = Vec::new();
    let props: Vec<Prop> = project
        .manifest
        .properties
        .iter()
        .filter(|p| !on_runs(p))
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
    let (run_props, atomics) = crate::model::property::compile_where(project, &[], on_runs)?;
    let run_atoms = (!run_props.is_empty()).then(|| runs::RunAtoms::new(&atomics, &sem));
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
    // Under symmetry the stored graph follows one object under different names from state
    // to state: it decides the run properties that no renaming changes, and the others
    // have searches reduced by the renamings that fix what they name (symmetry::RunPlan).
    let on_agent_graph = run_props.iter().any(|p| p.user.is_none());
    let plan = agent
        .symmetry
        .as_ref()
        .filter(|_| on_agent_graph)
        .map(|sym| {
            let mine: Vec<_> = run_props
                .iter()
                .filter(|p| p.user.is_none())
                .cloned()
                .collect();
            sym.plan_runs(&atomics, &mine)
        });
    let whole_atoms = plan
        .as_ref()
        .map(|plan| runs::RunAtoms::for_props(&atomics, &sem, &plan.whole));
    let conditions = Conditions {
        invariants: project.invariants.iter().map(|(_, c)| c).collect(),
        props: props.iter().map(|p| &p.cond).collect(),
        overlaps,
        // Only for properties decided on the agent's graph (not on a user's search).
        runs: whole_atoms
            .as_ref()
            .or(run_atoms.as_ref())
            .filter(|_| on_agent_graph),
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
        sample: opts.sample,
        room_for: 0,
        numbered: true,
        places: 0,
    };
    let mut failures = Failures::default();
    let compiled = if opts.compiled {
        Compiled::new(&sem)
    } else {
        None
    };
    // The agents of the searches that decide run properties with their objects fixed, each
    // with the renamings that leave those objects in place (none: an exact search);
    // declared before the graphs that borrow them.
    let fixed_agents: Vec<Agent> = (plan.iter().flat_map(|p| &p.fixing))
        .map(|fixing| Agent {
            sem: &sem,
            symmetry: (agent.symmetry.as_ref())
                .and_then(|s| s.fixing(project, &sem, &fixing.objects)),
        })
        .collect();
    let users_may_read_a_graph = compiled.is_some()
        && opts.stored_users
        && search.shard.is_none()
        && search.sample.is_none()
        && (project.manifest.explanation.as_ref()).is_some_and(|e| !e.users.is_empty());
    // The users' searches follow the agent's transitions again, once per view: an exact
    // search keeps its states and notes for them (about 30 bytes a state), so that they
    // read its graph instead of running the cycle again.
    let mut stored =
        (users_may_read_a_graph && agent.symmetry.is_none()).then(explanation::Stored::default);
    // The agent's table, dropped when its search ends, is the memory of a user's array by
    // place (`slots::keep_a_freed_table`), until the users' searches are over.
    let mut keeping = stored.is_some().then(slots::Keeping::start);
    // Reduction is only exact if renaming a state renames its successors: on the compiled
    // cycle every memoized phase is checked for it once the search ends
    // (Symmetry::phase_violation), on the reference cycle every stored state
    // (Symmetry::equivariance_violation); where it does not hold, the report says so.
    let (graph, not_equivariant, unchecked) = agent_search(
        &agent,
        compiled.as_ref(),
        &conditions,
        (limits, &search),
        (&mut facts, &eventually, &mut failures),
        stored.as_mut(),
        &mut |n, d, t| progress("search", n, d, t),
    );
    let stored_runs = match (&compiled, &stored) {
        (Some(c), Some(st)) => explanation::AloneStored::new(c, st, &graph),
        _ => None,
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
    let mut findings: Vec<Finding> = Vec::new();
    let mut run_phases = Vec::new();
    let mut caveat = not_equivariant;
    let mut found = Vec::new();
    // The products of the run properties with the agent's graph take the cores the users'
    // searches leave or free, a property at a time, on the thread that freed the core:
    // beside those searches, a third thread on two cores slowed the longest by a third
    // (4-cup kitchen), and on a thread of their own they took fresh memory where the
    // search before them on that thread had freed as much (6-cup kitchen;
    // docs/benchmarks.md). Findings are merged by property number, so the order they
    // come in does not matter.
    // The liveness checks (a pass or more over every edge of the agent's graph) run
    // beside the searches that follow, instead of before them, and beside settling the
    // lint findings.
    let whole: Vec<(usize, crate::model::property::RunProperty)> = match &plan {
        _ if !on_agent_graph => Vec::new(),
        Some(plan) => plan.whole.clone(),
        None => run_props.iter().cloned().enumerate().collect(),
    };
    let next_product = std::sync::atomic::AtomicUsize::new(0);
    let products_found = std::sync::Mutex::new(ProductsFound::default());
    let products = || {
        if next_product.load(std::sync::atomic::Ordering::Relaxed) >= whole.len() {
            return;
        }
        let t = std::time::Instant::now();
        let (found, reached) = c.runs_taken(&next_product, &whole);
        let mut p = products_found.lock().unwrap_or_else(|e| e.into_inner());
        p.found.extend(found);
        p.reached += reached;
        p.began = Some(p.began.map_or(t, |b| b.min(t)));
        p.ended = Some(std::time::Instant::now());
    };
    let (live, run_and_user_findings) = std::thread::scope(|scope| {
        let live = scope.spawn(|| {
            let mut out = Vec::new();
            c.liveness(&mut out, &props);
            out
        });
        findings = lint
            .iter()
            .map(|f| c.settle(f, &action_failures, &no_plan))
            .collect();
        let adopted = |plan| search::bit(&applied, plan);
        settle_undecided(&mut findings, project, adopted, &no_plan, graph.complete());
        c.safety(&mut findings, &props);
        settle_non_inductive(&mut findings, project, graph.complete());
        note_handled_gaps(&mut findings, project, &goal_failures);
        c.failures(&mut findings, action_failures, goal_failures);
        let mut reached = 0;
        let mut seconds = 0.0;
        // Under symmetry, once one of those searches is exact and complete, the users'
        // searches are exact too, and the first such search keeps its graph for them, as
        // the agent's exact search does: following its transitions costs a user's state
        // about a quarter of what running the cycle and finding the canonical renaming
        // costs, which more than pays for the states symmetry would have merged (4-cup
        // kitchen: 2.2 M exact user states against 1.3 M). Whether the users' searches are
        // exact depends on that search alone, not on whether its graph was kept, so that
        // every way of running them counts the same states.
        let mut exact: Option<(explanation::Stored, explore::Graph)> = None;
        let mut exact_complete = false;
        for (fixing, fixed) in plan.iter().flat_map(|p| &p.fixing).zip(&fixed_agents) {
            let mut keep = (users_may_read_a_graph
                && stored_runs.is_none()
                && exact.is_none()
                && fixed.symmetry.is_none())
            .then(explanation::Stored::default);
            let ran = fixing_runs(
                (project, fixed, compiled.as_ref()),
                (&atomics, fixing),
                (remaining(), &search),
                (&mut found, keep.as_mut()),
                &mut progress,
            );
            run_phases.push(ran.phase);
            reached += ran.reached;
            seconds += ran.product_seconds;
            caveat = caveat.take().or(ran.not_equivariant);
            exact_complete |= fixed.symmetry.is_none()
                && ran.graph.complete()
                && room_for_exact_users(ran.graph.len(), search.max_memory);
            if let Some(st) = keep {
                exact = Some((st, ran.graph));
            }
        }
        let exact_runs = match (&compiled, &exact) {
            (Some(c), Some((st, g))) => explanation::AloneStored::new(c, st, g),
            _ => None,
        };
        if stored_runs.is_none() && exact_runs.is_none() {
            // No user's search reads a stored graph, so none makes an array by place: the
            // table kept for one (hundreds of megabytes) is given back now.
            drop(keeping.take());
        }
        let symmetry = agent.symmetry.as_ref().filter(|_| !exact_complete);
        let users = users_and_explanations(
            (project, &sem, compiled.as_ref(), symmetry),
            stored_runs.or(exact_runs),
            (&run_props, run_atoms.as_ref()),
            (&remaining, &search),
            &mut progress,
            &products,
        );
        // Without users' searches (or when they failed), here.
        products();
        // A panic in the liveness checks is re-raised here, as a search thread's is.
        fn join<T>(h: std::thread::ScopedJoinHandle<'_, T>) -> T {
            h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))
        }
        let p = std::mem::take(&mut *products_found.lock().unwrap_or_else(|e| e.into_inner()));
        let whole = on_agent_graph.then(|| {
            let took = (p.began.zip(p.ended)).map_or(0.0, |(b, e)| (e - b).as_secs_f64());
            let mut found = p.found;
            found.sort_by_key(|(k, _)| *k);
            (found, p.reached + reached, took + seconds)
        });
        done_with(exact);
        (join(live), users.map(|u| (whole, u)))
    });
    drop(keeping);
    findings.extend(live);
    let (whole_runs, users) = run_and_user_findings?;
    let (user_found, user_phases, phases) = users;
    if let Some((whole_found, reached, seconds)) = whole_runs {
        found.extend(whole_found);
        findings.extend(runs::merge(found));
        run_phases.push(crate::findings::Phase {
            name: "ltl product".into(),
            seconds,
            states: Some(reached),
            beside: (run_phases.iter().chain(&user_phases).chain(&phases))
                .map(|p| p.name.clone())
                .collect(),
        });
    }
    findings.extend(user_found);
    let mut v = Verification {
        symmetric_types,
        symmetry_caveat: caveat,
        ..Verification::of(&graph, project, findings)
    };
    v.stats.phases.extend(run_phases);
    v.stats.phases.extend(user_phases);
    v.stats.phases.extend(phases);
    if unchecked {
        v.warnings.push("symmetry reduction was not checked to rename the successors of the states stored after `--timeout` passed (the check is made on every other state): `--no-symmetry` gives the exact verdict".into());
    }
    done_with((graph, stored, facts));
    done_with(compiled);
    Ok(v)
}

/// Bytes of memory that the users' exact searches (a manifest's usual two) take per state
/// of the exact agent graph they follow: about 80 on the kitchen (6 cups: 1.6 user states
/// per agent state and user, each about 10 bytes in a table of fingerprints alone, and
/// the stored graph's 30; the run's peak went from 3.4 GB for the agent's search alone to
/// 8.5 GB for 65.6 M agent states), with some room for libraries whose users meet more
/// views per agent state. A library whose users meet many more is cut short at the memory
/// bound (`incomplete`, exit 3) where reduced searches might have fitted.
const EXACT_USER_BYTES: u64 = 120;

/// Whether the users' searches may follow an exact graph of `states` states instead of
/// running reduced by symmetry, within the memory bound (`max`): exact, they take about
/// twice the memory the reduced ones take on the kitchen, and a search that reaches the
/// bound is cut short (`incomplete`), so they only do when the room left holds them.
fn room_for_exact_users(states: usize, max: Option<u64>) -> bool {
    let (Some(max), Some(now)) = (max, explore::resident_memory()) else {
        return true;
    };
    (states as u64).saturating_mul(EXACT_USER_BYTES) <= max.saturating_sub(now)
}

/// What the users' searches found: the findings, the phases of the searches that decide
/// run properties about explanations, the phases of the explanation searches.
type UsersFound = (
    Vec<Finding>,
    Vec<crate::findings::Phase>,
    Vec<crate::findings::Phase>,
);

/// The run properties about explanations, each decided on its user's explanation search
/// (exact), then the explanation properties: one more search per user, each state paired
/// with the user's expected successors.
fn users_and_explanations(
    (project, sem, compiled, symmetry): (
        &Project,
        &Semantics,
        Option<&Compiled>,
        Option<&symmetry::Symmetry>,
    ),
    stored: Option<explanation::AloneStored>,
    (run_props, run_atoms): (
        &[crate::model::property::RunProperty],
        Option<&runs::RunAtoms>,
    ),
    (remaining, search): (&dyn Fn() -> Limits, &Options),
    progress: &mut dyn FnMut(&str, usize, u32, f64),
    spare: &(dyn Fn() + Sync),
) -> Result<UsersFound, Vec<Diagnostic>> {
    let mut findings = Vec::new();
    let mut user_phases = Vec::new();
    if let Some(atoms) = run_atoms {
        for u in crate::model::property::explained_users(run_props) {
            let props: Vec<&crate::model::property::RunProperty> = run_props
                .iter()
                .filter(|p| p.user.as_deref() == Some(u))
                .collect();
            let users = crate::explain::agent::users(project, Some(u))?;
            let ex = crate::explain::agent::Explainer::new(project, sem);
            let (found, phase) = match (stored, compiled) {
                (Some(stored), _) => user_runs(
                    project,
                    (u, explanation::Explained::watching(stored, &ex, &users[0])),
                    (&props, atoms),
                    (remaining(), search),
                    &mut *progress,
                ),
                (None, Some(compiled)) => user_runs(
                    project,
                    (
                        u,
                        explanation::Explained::watching(
                            explanation::AloneCompiled::new(compiled, None),
                            &ex,
                            &users[0],
                        ),
                    ),
                    (&props, atoms),
                    (remaining(), search),
                    &mut *progress,
                ),
                (None, None) => user_runs(
                    project,
                    (u, explanation::Explained::new(sem, &ex, &users[0], None)),
                    (&props, atoms),
                    (remaining(), search),
                    &mut *progress,
                ),
            };
            findings.extend(found);
            user_phases.push(phase);
        }
    }
    let explore_opts = explore::Options {
        keep_edges: false,
        ..*search
    };
    let (explained, _, phases) = explanation::verify(
        project,
        sem,
        (compiled, stored),
        symmetry,
        remaining(),
        &explore_opts,
        progress,
        spare,
    )?;
    findings.extend(explained);
    Ok((findings, user_phases, phases))
}

/// What the products of the run properties with the agent's graph found, over the
/// threads that took them: the findings by property number, the product states reached,
/// and when the first began and the last ended.
#[derive(Default)]
struct ProductsFound {
    found: Vec<(usize, Finding)>,
    reached: usize,
    began: Option<std::time::Instant>,
    ended: Option<std::time::Instant>,
}

/// What deciding some run properties on a search of their own gave.
struct FixingRuns {
    /// The search's phase.
    phase: crate::findings::Phase,
    /// Product states and seconds.
    reached: usize,
    product_seconds: f64,
    /// As [`Verification::symmetry_caveat`].
    not_equivariant: Option<String>,
    /// The search's graph.
    graph: explore::Graph,
}

/// Decides the run properties of `fixing` on a search reduced by the renamings that leave
/// its objects in place (exact, phase `ltl search`, when no type keeps two objects to
/// rename), adding one numbered finding per property to `found`.
/// With `stored`, every state of the search and its transitions' notes are kept there.
fn fixing_runs<'c>(
    (project, fixed, compiled): (&Project, &'c Agent, Option<&'c Compiled>),
    (atomics, fixing): (&crate::model::property::Atomics, &symmetry::Fixing),
    (limits, search): (Limits, &Options),
    (found, stored): (
        &mut Vec<(usize, Finding)>,
        Option<&mut explanation::Stored<'c>>,
    ),
    progress: &mut dyn FnMut(&str, usize, u32, f64),
) -> FixingRuns {
    let t = std::time::Instant::now();
    let sem = fixed.sem;
    let atoms = runs::RunAtoms::for_props(atomics, sem, &fixing.props);
    let conditions = Conditions {
        invariants: Vec::new(),
        props: Vec::new(),
        overlaps: Vec::new(),
        runs: Some(&atoms),
    };
    let name = if fixed.symmetry.is_some() {
        format!("ltl search ({} fixed)", fixing.names.join(", "))
    } else {
        "ltl search".to_string()
    };
    let mut facts = Facts::default();
    let (graph, not_equivariant, _) = agent_search(
        fixed,
        compiled,
        &conditions,
        (limits, search),
        (&mut facts, &[], &mut Failures::default()),
        stored,
        &mut |n, d, t| progress(&name, n, d, t),
    );
    let searched = t.elapsed().as_secs_f64();
    let c = Checker {
        project,
        agent: fixed,
        graph: &graph,
        facts: &facts,
        conditions: &conditions,
    };
    let t = std::time::Instant::now();
    let reached = c.runs_numbered(found, &fixing.props);
    FixingRuns {
        phase: crate::findings::Phase {
            name,
            seconds: searched,
            states: Some(graph.len()),
            beside: Vec::new(),
        },
        reached,
        product_seconds: t.elapsed().as_secs_f64(),
        not_equivariant,
        graph,
    }
}

/// The run properties `props` about the explanations `user` gets: decided on `model`, that
/// user's explanation search (on the compiled cycle when the agent has one), with one
/// finding each, and the phase.
fn user_runs<W: explanation::OneAgent>(
    project: &Project,
    (user, model): (&str, explanation::Explained<W>),
    (props, atoms): (&[&crate::model::property::RunProperty], &runs::RunAtoms),
    bounds: (Limits, &Options),
    progress: &mut dyn FnMut(&str, usize, u32, f64),
) -> (Vec<Finding>, crate::findings::Phase) {
    use model::AgentState;
    let facts = |s: &W::State| {
        let agent = model.runs().agent_state(s);
        (atoms.state_letter(&agent), u64::from(!agent.is_idle()))
    };
    let reading = explained_runs::Reading {
        facts: &facts,
        fair_agents: None,
        runs: runs::ONE_AGENT_RUNS,
    };
    explained_runs::decide(
        (project, project),
        (user, &model),
        (props, atoms),
        reading,
        bounds,
        progress,
    )
}

/// The agent's search, on the compiled cycle when there is one, with `agent`'s symmetry.
/// With `stored` (on the compiled cycle only), every state and its transitions' notes are
/// kept there.
fn agent_search<'c>(
    agent: &'c Agent,
    compiled: Option<&'c Compiled>,
    conditions: &Conditions,
    bounds: (Limits, &Options),
    record: (&mut Facts, &[usize], &mut Failures),
    stored: Option<&mut explanation::Stored<'c>>,
    progress: &mut dyn FnMut(usize, u32, f64),
) -> (explore::Graph, Option<String>, bool) {
    let sem = agent.sem;
    match compiled {
        Some(c) => {
            let model = CompiledAgent {
                compiled: c,
                symmetry: agent.symmetry.as_ref(),
            };
            let ids = explanation::NoteIds::default();
            let number = |n: &crate::semantics::Notes<'c>| ids.id(n);
            let mut stored = stored;
            let mut sink = stored
                .as_mut()
                .map(|st| move |s, notes: smallvec::SmallVec<[u32; 4]>| st.push(s, notes));
            // Equivariance is checked on the phases the search computed, once it ends
            // (`Symmetry::phase_violation`), not on every state: every state is covered,
            // those stored after `--timeout` too.
            let (g, _, _) = search_agent(
                &model,
                (conditions, |s: &Packed| c.applicable_plans(s).into()),
                |_, _| None,
                bounds,
                record,
                sink.as_mut()
                    .map(|k| (&number as _, k as &mut dyn FnMut(_, _))),
                progress,
            );
            // The graph's fingerprints come from the words kept for the users from now on:
            // 8 bytes a state less while they search.
            let mut g = g;
            if let Some(st) = stored {
                st.finish(ids);
                if st.covers(&g) {
                    let derived = g.derive_fingerprints(st.fingerprints(c));
                    debug_assert!(derived, "the words give the fingerprints the search kept");
                }
            }
            let unequal = model.symmetry.and_then(|sym| sym.phase_violation(c));
            (g.cast(), unequal, false)
        }
        None => search_agent(
            agent,
            (conditions, |s: &State| {
                s.events.first().map_or_else(Plans::new, |ev| {
                    sem.applicable(s, &ev.trigger, false)
                        .into_iter()
                        .map(|(plan, _)| plan)
                        .collect()
                })
            }),
            |s, _| {
                agent
                    .symmetry
                    .as_ref()
                    .and_then(|sym| sym.equivariance_violation(sem, s))
            },
            bounds,
            record,
            None,
            progress,
        ),
    }
}

/// The agent's exact, complete search on the compiled cycle (bounded at a million states)
/// with its graph kept for the users' searches, as `verify` runs it, checking nothing
/// else: the graph and the states and notes kept (tests).
#[cfg(test)]
fn stored_search<'c>(
    agent: &'c Agent,
    compiled: &'c Compiled,
    threads: usize,
) -> (explanation::Stored<'c>, explore::Graph) {
    let conditions = Conditions {
        invariants: Vec::new(),
        props: Vec::new(),
        overlaps: Vec::new(),
        runs: None,
    };
    let limits = Limits {
        max_states: 1_000_000,
        max_depth: 10_000,
        timeout: None,
    };
    let options = Options {
        threads,
        ..Options::default()
    };
    let mut stored = explanation::Stored::default();
    let (graph, _, _) = agent_search(
        agent,
        Some(compiled),
        &conditions,
        (limits, &options),
        (&mut Facts::default(), &[], &mut Failures::default()),
        Some(&mut stored),
        &mut |_, _, _| {},
    );
    (stored, graph)
}

impl Verification {
    /// The verification a search gave: its findings, statistics, bound and memory (no
    /// symmetry reduction said).
    pub(crate) fn of<S>(
        graph: &explore::Graph<S>,
        project: &Project,
        findings: Vec<Finding>,
    ) -> Self {
        let seconds = graph.seconds;
        Verification {
            findings,
            stats: Stats {
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
                liveness_states: None,
                phases: vec![crate::findings::Phase {
                    name: "search".into(),
                    seconds,
                    states: Some(graph.len()),
                    beside: Vec::new(),
                }],
            },
            bound: graph.bound,
            beyond: graph.beyond.as_ref().map(|(span, why)| {
                let at = project.map.location(*span);
                format!("{}:{}:{}: {why}", at.file, at.line, at.column)
            }),
            memory: (graph.store_bytes(), graph.edge_bytes()),
            peak_memory: graph.peak_memory,
            symmetric_types: Vec::new(),
            reduced_states: graph.reduced,
            symmetry_caveat: None,
            warnings: Vec::new(),
        }
    }
}

/// A coverage gap some run reaches is an error (SPEC §3) even when a failure plan handles
/// the goal's failure. When no goal failure the search recorded has the gap as its cause,
/// the message says how to accept the gap on purpose.
fn note_handled_gaps(
    findings: &mut [Finding],
    project: &Project,
    goal_failures: &std::collections::BTreeMap<String, failures::Failure>,
) {
    for f in findings.iter_mut() {
        let reached = f.check == "coverage-gap"
            && f.status == Status::Fail
            && f.severity == crate::syntax::Severity::Error;
        let Some(plan) = reached
            .then(|| project.plans.plans.iter().find(|p| Some(p.span) == f.span))
            .flatten()
        else {
            continue;
        };
        let goal = &plan.trigger.literal;
        let unhandled = goal_failures.values().any(|x| {
            matches!(&x.note, Note::GoalFailed { cause, .. }
                if cause.literal.functor() == goal.functor() && cause.literal.arity() == goal.arity())
        });
        if !unhandled {
            f.message.push_str(
                "; no goal failure found has it as its cause: if a failure plan handles it by design, accept it with `[[allow]] check = \"coverage-gap\"`",
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::explanation::{AloneStored, Runs};
    use super::*;
    use crate::check::model::CycleNotes;
    use std::collections::{HashMap, VecDeque};

    /// A library caller's verification frees what it is done with: only the command line
    /// leaves it to the process's exit (`leave_memory_to_exit`, never called in tests).
    #[test]
    fn what_a_verification_is_done_with_is_freed_by_default() {
        struct Counted<'a>(&'a std::cell::Cell<u32>);
        impl Drop for Counted<'_> {
            fn drop(&mut self) {
                self.0.set(self.0.get() + 1);
            }
        }
        let dropped = std::cell::Cell::new(0);
        done_with((Counted(&dropped), Counted(&dropped)));
        assert_eq!(dropped.get(), 2);
    }

    /// The users' searches follow an exact graph only when the memory bound leaves room
    /// for them: always without a bound, never without room, and by the graph's size in
    /// between.
    #[test]
    fn exact_users_need_room_under_the_memory_bound() {
        assert!(room_for_exact_users(1_000_000, None));
        assert!(!room_for_exact_users(1, Some(0)));
        assert!(room_for_exact_users(1_000_000, Some(u64::MAX)));
        let now = explore::resident_memory().expect("Linux tells the resident memory");
        let bound = now + (1 << 30);
        assert!(room_for_exact_users(1_000, Some(bound)));
        assert!(!room_for_exact_users(1_000_000_000, Some(bound)));
    }

    /// The graph an exact search keeps for the users' searches holds every state, and from
    /// each the compiled cycle's transitions, in its order, with the very same notes: a
    /// breadth-first walk of the stored graph beside the compiled cycle meets, at every
    /// node, the state the cycle reaches there. The agent's graph then gives each state's
    /// fingerprint from its word, that state's.
    #[test]
    fn the_stored_graph_is_the_compiled_cycles() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        for dir in [
            "specs/kitchen",
            "specs/paper",
            "tests/verify/explain_untruthful",
        ] {
            let project = crate::model::project::load_project(&root.join(dir)).expect("loads");
            let sem = Semantics::new(&project).expect("the semantics");
            let compiled = Compiled::new(&sem).expect("a local library");
            let agent = Agent {
                sem: &sem,
                symmetry: None,
            };
            let (stored, graph) = stored_search(&agent, &compiled, 2);
            assert!(graph.complete() && graph.fingerprints_derived(), "{dir}");
            let runs = AloneStored::new(&compiled, &stored, &graph).expect("every state held");
            let mut met = HashMap::new();
            let mut queue: VecDeque<_> = runs.initial().zip(compiled.initial_iter()).collect();
            assert_eq!(queue.len(), graph.initial, "{dir}");
            while let Some((node, state)) = queue.pop_front() {
                if let Some(first) = met.insert(node, state) {
                    assert_eq!(first, state, "{dir}: {node:?} stands for two states");
                    continue;
                }
                let fingerprint = explore::fingerprint(&state);
                assert_eq!(
                    graph.fingerprint(node.index()),
                    fingerprint,
                    "{dir}: {node:?}"
                );
                let (kept, cycle) = (runs.successors(&node), compiled.successors(&state));
                assert_eq!(kept.len(), cycle.len(), "{dir}: {node:?}");
                for ((_, notes, next), (cycle_notes, cycle_next)) in kept.into_iter().zip(cycle) {
                    let at = |n: &crate::semantics::Note| n as *const _ as usize;
                    let kept_at: Vec<usize> = notes.notes().map(at).collect();
                    let cycle_at: Vec<usize> = cycle_notes.iter().map(at).collect();
                    assert_eq!(kept_at, cycle_at, "{dir}: {node:?}");
                    queue.push_back((next, cycle_next));
                }
            }
            assert_eq!(met.len(), graph.len(), "{dir}");
        }
    }
}
