//! A whole project: the manifest, the agent, the PDDL domain, checked against each other
//! and grounded into the finite model that `lint` and `verify` work on.

use super::atoms::{AtomId, AtomSet, AtomTable};
use super::cond::Cond;
use super::formula;
use super::ground::GroundActions;
use super::initial;
use super::plans::PlanLibrary;
use super::universe::Universe;
use super::vocabulary::{self, Vocabulary};
use crate::syntax::ast::{ExprKind, Item, Literal};
use crate::syntax::manifest::{load_manifest, Manifest};
use crate::syntax::pddl::{parse_domain, Domain};
use crate::syntax::{Diagnostic, LoadedAgent, SourceMap, Span};
use std::path::Path;
use std::sync::{Arc, OnceLock};

/// The initial states of a project and what they were built from.
#[derive(Clone, Debug)]
pub struct InitialStates {
    /// Atoms true in every initial state: the manifest's `facts` and the agent's initial
    /// beliefs.
    pub facts: AtomSet,
    /// Atoms that may start either way.
    pub vary: Vec<AtomId>,
    /// The agent's initial beliefs, in source order (part of `facts`).
    pub agent_beliefs: Vec<AtomId>,
    /// What every initial state satisfies: the manifest's constraints and the invariants
    /// over the environment.
    pub conditions: Vec<Cond>,
    /// Most initial states held (`[bounds] max_states`, and 1 GiB of them).
    pub limit: usize,
    /// How many atoms a state has.
    atoms: usize,
    /// The states, enumerated when first asked for (lint never needs them), shared by
    /// the agents of a project; whether they are all.
    enumerated: Arc<OnceLock<(Vec<AtomSet>, bool)>>,
}

impl InitialStates {
    /// The initial states of `atoms` atoms: `facts` true, `vary` either way, every other
    /// atom false, `conditions` holding; at most `limit` of them are held.
    pub fn new(
        atoms: usize,
        facts: AtomSet,
        vary: Vec<AtomId>,
        agent_beliefs: Vec<AtomId>,
        conditions: Vec<Cond>,
        limit: usize,
    ) -> InitialStates {
        InitialStates {
            facts,
            vary,
            agent_beliefs,
            conditions,
            limit,
            atoms,
            enumerated: Arc::default(),
        }
    }

    /// The same states with other initial beliefs of the agent (instances of a project
    /// share the enumeration).
    fn with_beliefs(&self, agent_beliefs: Vec<AtomId>) -> InitialStates {
        InitialStates {
            agent_beliefs,
            ..self.clone()
        }
    }

    fn enumerated(&self) -> &(Vec<AtomSet>, bool) {
        self.enumerated.get_or_init(|| {
            initial::first(
                self.atoms,
                &self.facts,
                &self.vary,
                &self.conditions,
                self.limit,
            )
        })
    }

    /// Every initial state, sorted: the first [`InitialStates::limit`] of them when there
    /// are more ([`InitialStates::complete`] says).
    pub fn states(&self) -> &[AtomSet] {
        &self.enumerated().0
    }

    /// Whether [`InitialStates::states`] holds every initial state.
    pub fn complete(&self) -> bool {
        self.enumerated().1
    }

    /// The initial states in the order a search takes them, made as it takes them: those
    /// of [`InitialStates::states`] when they are few (at most [`SORTED`]), else the
    /// enumeration's, with no bound (the search's own bounds stop it).
    pub fn iter(&self) -> Box<dyn Iterator<Item = AtomSet> + '_> {
        if let Some((states, true)) = self.enumerated.get() {
            return Box::new(states.iter().cloned());
        }
        let mut it =
            initial::Enumeration::new(self.atoms, &self.facts, &self.vary, self.conditions.clone());
        let head: Vec<AtomSet> = it.by_ref().take(SORTED).collect();
        match it.next() {
            None if head.len() <= self.limit => {
                let (states, _) = self.enumerated.get_or_init(|| {
                    let mut head = head;
                    head.sort();
                    (head, true)
                });
                Box::new(states.iter().cloned())
            }
            more => Box::new(head.into_iter().chain(more).chain(it)),
        }
    }

    /// Whether the states have been enumerated yet (the static checks never ask).
    pub fn is_enumerated(&self) -> bool {
        self.enumerated.get().is_some()
    }
}

/// A loaded, checked and grounded project.
#[derive(Clone, Debug)]
pub struct Project {
    /// Every file read, for diagnostics.
    pub map: SourceMap,
    /// `bdi-check.toml`.
    pub manifest: Manifest,
    /// The agent's name, as Jason names it: its `.mas2j` or `[[agent]]` name (`name1` ...
    /// for instances), or the stem of its source file (`kitchen.asl` is `kitchen`).
    pub name: String,
    /// Where the agent is named: its entry in the `.mas2j` or its `[[agent]]` name, or
    /// its plans in the manifest of one agent (findings about the agent point there).
    pub declared: Span,
    /// The agent and the files it includes.
    pub agent: LoadedAgent,
    /// The PDDL action model.
    pub domain: Domain,
    /// Types and objects.
    pub universe: Universe,
    /// Predicates, actions and goals, type-checked.
    pub vocabulary: Vocabulary,
    /// The plan library, compiled to model terms.
    pub plans: PlanLibrary,
    /// Every ground atom.
    pub atoms: AtomTable,
    /// Every ground action.
    pub actions: GroundActions,
    /// The manifest's `[initial] constraints`, compiled.
    pub constraints: Vec<Cond>,
    /// The manifest's `[invariants]`, by name, compiled (with several agents, over the
    /// environment and every agent's beliefs: [`formula::compile_in`]).
    pub invariants: Vec<(String, Cond)>,
    /// The initial states.
    pub initial: InitialStates,
}

/// Why a project did not load: every diagnostic, and the files needed to render them.
#[derive(Debug)]
pub struct LoadError {
    /// The files read so far.
    pub map: SourceMap,
    /// What is wrong.
    pub diagnostics: Vec<Diagnostic>,
}

/// Loads the project at `path` (its folder or its manifest): every stage runs as far as the
/// earlier ones allow, and all their errors are returned together. A project of several
/// agents is refused here (see [`load_system`]).
pub fn load_project(path: &Path) -> Result<Project, LoadError> {
    let mut agents = load_agents(path)?;
    if agents.len() > 1 {
        let p = &agents[0];
        let span = p.manifest.agent.agents[1].name.span;
        let d = Diagnostic::error(
            "input",
            format!(
                "this project has {} agents, and this command runs one agent",
                agents.len()
            ),
        )
        .with_label(span, "a second agent")
        .with_help("`lint` and `verify` check multi-agent projects");
        let map = agents.swap_remove(0).map;
        return Err(LoadError {
            map,
            diagnostics: vec![d],
        });
    }
    Ok(agents.remove(0))
}

/// The agents of a project: one [`Project`] per running agent (every instance of an
/// agent of a `.mas2j` or `[[agent]]`, named as Jason names them), in order. They share
/// the manifest, the domain, the objects and one table of atoms (built from what all of
/// them use), so a state of one reads as a state of any other; each has its own plans and
/// initial beliefs, and its `initial.states` are those of the shared environment (plus
/// its own initial beliefs).
pub fn load_system(path: &Path) -> Result<Vec<Project>, LoadError> {
    load_agents(path)
}

fn load_agents(path: &Path) -> Result<Vec<Project>, LoadError> {
    let mut map = SourceMap::new();
    let fail = |map: SourceMap, diagnostics: Vec<Diagnostic>| Err(LoadError { map, diagnostics });
    let manifest = match load_manifest(path, &mut map) {
        Ok(m) => m,
        Err(d) => return fail(map, d),
    };
    let mut errors = Vec::new();
    // (name, where named, the file) per running agent.
    let mut named: Vec<(String, Span, crate::syntax::manifest::FileRef)> = Vec::new();
    if manifest.agent.agents.is_empty() {
        let stem = manifest
            .agent
            .plans
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "agent".into());
        named.push((
            stem,
            manifest.agent.plans.written.span,
            manifest.agent.plans.clone(),
        ));
    }
    for a in &manifest.agent.agents {
        let names: Vec<String> = if a.instances == 1 {
            vec![a.name.value.clone()]
        } else {
            (1..=a.instances)
                .map(|i| format!("{}{i}", a.name.value))
                .collect()
        };
        for n in names {
            if let Some((_, first, _)) = named.iter().find(|(m, _, _)| *m == n) {
                errors.push(
                    Diagnostic::error("input", format!("two agents are named `{n}`"))
                        .with_label(a.name.span, "this agent or one of its instances")
                        .with_secondary(*first, "and this one")
                        .with_help("Jason would rename one (RuntimeServices.getNewAgentName), and bdi-check does not guess which"),
                );
            }
            named.push((n, a.name.span, a.plans.clone()));
        }
    }
    if named.len() > MAX_AGENTS {
        errors.push(
            Diagnostic::error(
                "input",
                format!(
                    "{} agents run in this project; at most {MAX_AGENTS} are supported",
                    named.len()
                ),
            )
            .in_file(manifest.path.display().to_string()),
        );
        return fail(map, errors);
    }
    // The agent the user's requests go to comes first (`[requests] to`; by default the
    // first agent): the system posts requests to its first agent.
    if let Some(to) = &manifest.requests.to {
        match named.iter().position(|(n, _, _)| *n == to.value) {
            Some(k) => {
                let addressed = named.remove(k);
                named.insert(0, addressed);
            }
            None => {
                let names: Vec<String> = named.iter().map(|(n, _, _)| format!("`{n}`")).collect();
                errors.push(
                    Diagnostic::error("input", format!("no agent is named `{}`", to.value))
                        .with_label(to.span, "the requests go to this agent")
                        .with_help(format!("the agents are {}", names.join(", "))),
                );
                return fail(map, errors);
            }
        }
    }
    // The robot whose actions the users of `[explanation]` watch: an agent of the
    // project, and named whenever there are several.
    if let Some(ex) = &manifest.explanation {
        let names = || -> String {
            let names: Vec<String> = named.iter().map(|(n, _, _)| format!("`{n}`")).collect();
            names.join(", ")
        };
        match &ex.robot {
            Some(r) if !named.iter().any(|(n, _, _)| *n == r.value) => {
                errors.push(
                    Diagnostic::error("input", format!("no agent is named `{}`", r.value))
                        .with_label(r.span, "the robot the users watch")
                        .with_help(format!("the agents are {}", names())),
                );
                return fail(map, errors);
            }
            None if named.len() > 1 => {
                errors.push(
                    Diagnostic::error(
                        "input",
                        "`[explanation]` of a project of several agents must name the robot whose actions its users watch",
                    )
                    .with_label(ex.span, "no `robot` in this section")
                    .with_help(format!(
                        "add `robot = \"{}\"` (the agents are {})",
                        named[0].0,
                        names()
                    )),
                );
                return fail(map, errors);
            }
            _ => {}
        }
    }
    // Each file is read once; instances share it.
    let mut loaded: Vec<(std::path::PathBuf, LoadedAgent)> = Vec::new();
    for (_, _, f) in &named {
        if loaded.iter().any(|(p, _)| *p == f.path) {
            continue;
        }
        match crate::syntax::loader::load_agent_with(&f.path, &mut map, &manifest.agent.source_path)
        {
            Ok(a) => loaded.push((f.path.clone(), a)),
            Err(d) => errors.extend(d),
        }
    }
    let domain = load_domain(&manifest, &mut map).map_err(|d| errors.extend(d));
    let Ok(domain) = domain else {
        return fail(map, errors);
    };
    if !errors.is_empty() {
        return fail(map, errors);
    }
    let universe = match Universe::build(&domain, &manifest) {
        Ok(u) => u,
        Err(d) => return fail(map, d),
    };
    // What the agents may tell, untell and ask each other's plans (`tellHow`, ...).
    let files: Vec<&LoadedAgent> = loaded.iter().map(|(_, a)| a).collect();
    let agents: Vec<(String, usize)> = named
        .iter()
        .map(|(n, _, f)| {
            let file = loaded.iter().position(|(p, _)| *p == f.path).unwrap_or(0);
            (n.clone(), file)
        })
        .collect();
    let know_how = match super::know_how::collect(&files, &agents) {
        Ok(k) => k,
        Err(d) => return fail(map, d),
    };
    let all_items: Vec<&Item> = loaded.iter().flat_map(|(_, a)| a.items()).collect();
    let vocabulary = match vocabulary::check_items(&all_items, &domain, &manifest, &universe, &map)
    {
        Ok(v) => v,
        Err(d) => return fail(map, d),
    };
    let mut libraries = Vec::new();
    for ((_, a), kh) in loaded.iter().zip(&know_how) {
        match PlanLibrary::compile(a, kh) {
            Ok(p) => libraries.push(p),
            Err(d) => errors.extend(d),
        }
    }
    if !errors.is_empty() {
        return fail(map, errors);
    }
    let predicates: Vec<(Arc<str>, Vec<_>)> = vocabulary
        .predicates
        .iter()
        .map(|p| (Arc::<str>::from(p.name.as_str()), p.params.clone()))
        .collect();
    let atoms = match AtomTable::new(&universe, &predicates) {
        Ok(t) => t,
        Err(name) => {
            let d = Diagnostic::error(
                "input",
                format!(
                    "grounding `{name}` over the objects makes more than {} atoms",
                    super::atoms::MAX_ATOMS
                ),
            )
            .in_file(manifest.path.display().to_string());
            return fail(map, vec![d]);
        }
    };
    let actions = match GroundActions::new(&domain, &universe, &atoms) {
        Ok(a) => a,
        Err(d) => return fail(map, d),
    };
    let compile = |f: &crate::syntax::manifest::Formula, errors: &mut Vec<Diagnostic>| {
        formula::compile(&f.expr, &atoms, &universe)
            .map_err(|d| errors.push(d))
            .ok()
    };
    let constraints: Vec<Cond> = manifest
        .initial
        .constraints
        .iter()
        .filter_map(|f| compile(f, &mut errors))
        .collect();
    // With several agents, an invariant may name an agent's belief (`robot1::holding(cup)`).
    let agent_names: Vec<String> = if named.len() > 1 {
        named.iter().map(|(n, _, _)| n.clone()).collect()
    } else {
        Vec::new()
    };
    let invariants: Vec<(String, Cond)> = manifest
        .invariants
        .iter()
        .filter_map(|i| {
            formula::compile_in(&i.formula.expr, &atoms, &universe, &agent_names)
                .map_err(|d| errors.push(d))
                .ok()
                .map(|c| (i.name.value.clone(), c))
        })
        .collect();
    let mut facts = AtomSet::empty(atoms.len());
    for f in &manifest.initial.facts {
        match &f.expr.kind {
            ExprKind::Literal(l) => match ground_atom(l, &atoms, &universe) {
                Ok(a) => facts.insert(a),
                Err(d) => errors.push(d),
            },
            _ => errors.push(
                Diagnostic::error("input", "a fact must be a ground atom")
                    .with_label(f.span, "not an atom"),
            ),
        }
    }
    let several = named.len() > 1;
    // The agents' initial beliefs hold at the start of every run, as in Jason. With one
    // agent they are facts of its states; with several, each agent's are its own.
    let mut initial_beliefs: Vec<Vec<AtomId>> = Vec::new();
    for (_, a) in &loaded {
        let mut mine = Vec::new();
        for item in a.items() {
            if let Item::Belief(b) = item {
                match ground_atom(&b.literal, &atoms, &universe) {
                    Ok(at) => {
                        if several && vocabulary_is_environment(&vocabulary, &atoms, at) {
                            errors.push(
                                Diagnostic::error(
                                    "input",
                                    format!(
                                        "`{}` is an initial belief of a percept in a project of several agents",
                                        crate::syntax::printer::print_literal(&b.literal)
                                    ),
                                )
                                .with_label(b.literal.span, "a predicate of the PDDL domain")
                                .with_help("the environment is shared: give its atoms in `[initial] facts`"),
                            );
                        }
                        if !mine.contains(&at) {
                            mine.push(at);
                        }
                    }
                    Err(d) => errors.push(d),
                }
            }
        }
        initial_beliefs.push(mine);
    }
    if !several {
        for &a in &initial_beliefs[0] {
            facts.insert(a);
        }
    }
    // An action with an `?agent` parameter is done by the agent that calls it: that agent
    // must be an object of the parameter's type.
    for (name, declared, f) in &named {
        let k = loaded
            .iter()
            .position(|(p, _)| *p == f.path)
            .expect("loaded");
        for (a, span) in actions_called(&libraries[k].plans) {
            let Some((_, sig)) = vocabulary.action(&a) else {
                continue;
            };
            let Some(p) = sig.actor else { continue };
            let ty = sig.params[p];
            let fits = universe
                .object(name)
                .is_some_and(|o| universe.is_subtype(universe.object_type(o), ty));
            if !fits {
                errors.push(
                    Diagnostic::error(
                        "input",
                        format!(
                            "`{a}` is done by the agent that calls it (its `?agent` parameter), but the agent `{name}` is no object of type `{}`",
                            universe.type_name(ty)
                        ),
                    )
                    .with_label(span, "called here")
                    .with_secondary(*declared, "the agent")
                    .with_help(format!(
                        "declare `{name}` as an object of type `{}` (in `[objects]` or as a PDDL constant)",
                        universe.type_name(ty)
                    )),
                );
                break;
            }
        }
    }
    let mut vary = Vec::new();
    for v in &manifest.initial.vary {
        match atoms.pred(&v.value) {
            Some(p) => vary.extend(atoms.atoms_of(p)),
            None => errors.push(
                Diagnostic::error("input", format!("`{}` is not a predicate", v.value))
                    .with_label(v.span, "unknown predicate"),
            ),
        }
    }
    if !errors.is_empty() {
        return fail(map, errors);
    }
    // An invariant naming an agent's beliefs is checked on the runs, from their first state.
    let stride = formula::agent_stride(&atoms) as u32;
    let all: Vec<Cond> = constraints
        .iter()
        .cloned()
        .chain(
            invariants
                .iter()
                .filter(|(_, c)| c.atoms().iter().all(|a| a.0 < stride))
                .map(|(_, c)| c.clone()),
        )
        .collect();
    // The initial states are held at once: bounded by `max_states` and by memory.
    let state_bytes = (atoms.len() / 8 + 32) as u64;
    let by_memory = usize::try_from(INITIAL_STATES_BYTES / state_bytes).unwrap_or(usize::MAX);
    let limit = usize::try_from(manifest.bounds.max_states)
        .unwrap_or(usize::MAX)
        .min(by_memory);
    // The states themselves are enumerated when a search needs them; that there is one is
    // known now (a search of the first one stops at once, or finds none).
    let (one, _) = initial::first(atoms.len(), &facts, &vary, &all, 1);
    let states = InitialStates::new(atoms.len(), facts, vary, Vec::new(), all, limit);
    if one.is_empty() {
        let d = Diagnostic::error(
            "input",
            "no initial state satisfies the facts, the constraints and the invariants",
        )
        .in_file(manifest.path.display().to_string())
        .with_help("every check would pass vacuously; look for contradicting constraints");
        return fail(map, vec![d]);
    }
    let mut out = Vec::new();
    for (name, declared, f) in &named {
        let k = loaded
            .iter()
            .position(|(p, _)| *p == f.path)
            .expect("loaded");
        let mut manifest = manifest.clone();
        manifest.agent.plans = f.clone();
        out.push(Project {
            map: map.clone(),
            manifest,
            name: name.clone(),
            declared: *declared,
            agent: loaded[k].1.clone(),
            domain: domain.clone(),
            universe: universe.clone(),
            vocabulary: vocabulary.clone(),
            plans: libraries[k].clone(),
            atoms: atoms.clone(),
            actions: actions.clone(),
            constraints: constraints.clone(),
            invariants: invariants.clone(),
            initial: states.with_beliefs(initial_beliefs[k].clone()),
        });
    }
    Ok(out)
}

/// Most initial states a search takes sorted, as [`InitialStates::states`] lists them;
/// past that many, it takes them in the order they are enumerated.
pub const SORTED: usize = 100_000;

/// Most agents one project runs.
pub const MAX_AGENTS: usize = 64;

/// Whether atom `a` is of a predicate of the PDDL domain.
fn vocabulary_is_environment(v: &Vocabulary, atoms: &AtomTable, a: AtomId) -> bool {
    let (p, _) = atoms.decode(a);
    v.predicate(atoms.pred_name(p))
        .is_some_and(|(_, sig)| sig.is_environment())
}

/// Reads and parses the manifest's PDDL domain.
fn load_domain(manifest: &Manifest, map: &mut SourceMap) -> Result<Domain, Vec<Diagnostic>> {
    let path = &manifest.agent.actions.path;
    let text = crate::syntax::source::read_input(path).map_err(|e| {
        vec![
            Diagnostic::error("input", format!("cannot read `{}`: {e}", path.display()))
                .with_label(manifest.agent.actions.written.span, "named here"),
        ]
    })?;
    let id = map.add(path, path.display().to_string(), text);
    let text = map.file(id).text.clone();
    match parse_domain(id, &text) {
        (Some(d), errs) if errs.is_empty() => Ok(d),
        (_, errs) if !errs.is_empty() => Err(errs),
        _ => Err(vec![Diagnostic::error(
            "input",
            "no PDDL domain in this file",
        )
        .in_file(path.display().to_string())]),
    }
}

/// Most memory the initial states may take together (they are all held at once).
pub const INITIAL_STATES_BYTES: u64 = 1 << 30;

/// The atom a ground literal names.
fn ground_atom(l: &Literal, atoms: &AtomTable, universe: &Universe) -> Result<AtomId, Diagnostic> {
    let bad = |span: Span, msg: String| Diagnostic::error("input", msg).with_label(span, "here");
    let p = atoms
        .pred_lit(&l.functor, l.negated)
        .ok_or_else(|| bad(l.span, format!("`{}` is not a predicate", l.functor)))?;
    let mut args = Vec::new();
    for a in &l.args {
        match &a.kind {
            ExprKind::Literal(o) if o.args.is_empty() => args.push(
                universe
                    .object(&o.functor)
                    .ok_or_else(|| bad(a.span, format!("`{}` is not an object", o.functor)))?,
            ),
            ExprKind::Int(i) => args.push(
                universe
                    .object_of(&crate::model::Term::int(*i))
                    .ok_or_else(|| bad(a.span, format!("`{i}` is not among `[bounds] numbers`")))?,
            ),
            _ => return Err(bad(a.span, "expected an object".into())),
        }
    }
    atoms.id(p, &args).ok_or_else(|| {
        bad(
            l.span,
            format!(
                "`{}` does not fit the types of `{}`",
                crate::syntax::printer::print_literal(l),
                l.functor
            ),
        )
    })
}

/// The environment actions a plan library calls, each with the place of a first call.
fn actions_called(plans: &[crate::model::plans::Plan]) -> Vec<(String, Span)> {
    use crate::model::plans::{BodyStep, Step};
    fn walk(steps: &[Step], out: &mut Vec<(String, Span)>) {
        for st in steps {
            match &st.kind {
                BodyStep::Action(t) => {
                    let name = t.functor().unwrap_or("");
                    if !out.iter().any(|(n, _)| n == name) {
                        out.push((name.to_string(), st.span));
                    }
                }
                BodyStep::If {
                    branches,
                    else_body,
                } => {
                    branches.iter().for_each(|(_, b)| walk(b, out));
                    walk(else_body, out);
                }
                BodyStep::While(_, b) | BodyStep::For(_, b) => walk(b, out),
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    for p in plans {
        walk(&p.body, &mut out);
    }
    out
}
