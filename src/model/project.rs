//! A whole project: the manifest, the agent, the PDDL domain, checked against each other
//! and grounded into the finite model that `lint` and `verify` work on.

use super::atoms::{AtomId, AtomSet, AtomTable};
use super::cond::Cond;
use super::formula;
use super::ground::GroundActions;
use super::initial::{self, TooMany};
use super::plans::PlanLibrary;
use super::universe::Universe;
use super::vocabulary::{self, Vocabulary};
use crate::syntax::ast::{ExprKind, Item, Literal};
use crate::syntax::manifest::{load_manifest, Manifest};
use crate::syntax::pddl::{parse_domain, Domain};
use crate::syntax::{Diagnostic, LoadedAgent, SourceMap, Span};
use std::path::Path;
use std::sync::Arc;

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
    /// Every initial state, sorted.
    pub states: Vec<AtomSet>,
}

/// A loaded, checked and grounded project.
#[derive(Clone, Debug)]
pub struct Project {
    /// Every file read, for diagnostics.
    pub map: SourceMap,
    /// `bdi-check.toml`.
    pub manifest: Manifest,
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
    /// The manifest's `[invariants]`, by name, compiled.
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
/// earlier ones allow, and all their errors are returned together.
pub fn load_project(path: &Path) -> Result<Project, LoadError> {
    let mut map = SourceMap::new();
    let fail = |map: SourceMap, diagnostics: Vec<Diagnostic>| Err(LoadError { map, diagnostics });
    let manifest = match load_manifest(path, &mut map) {
        Ok(m) => m,
        Err(d) => return fail(map, d),
    };
    let mut errors = Vec::new();
    let agent = crate::syntax::loader::load_agent_with(
        &manifest.agent.plans.path,
        &mut map,
        &manifest.agent.source_path,
    )
    .map_err(|d| errors.extend(d));
    let domain = load_domain(&manifest, &mut map).map_err(|d| errors.extend(d));
    let (Ok(agent), Ok(domain)) = (agent, domain) else {
        return fail(map, errors);
    };
    let universe = match Universe::build(&domain, &manifest) {
        Ok(u) => u,
        Err(d) => return fail(map, d),
    };
    let vocabulary = match vocabulary::check(&agent, &domain, &manifest, &universe, &map) {
        Ok(v) => v,
        Err(d) => return fail(map, d),
    };
    let plans = match PlanLibrary::compile(&agent) {
        Ok(p) => p,
        Err(d) => return fail(map, d),
    };
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
    let invariants: Vec<(String, Cond)> = manifest
        .invariants
        .iter()
        .filter_map(|i| compile(&i.formula, &mut errors).map(|c| (i.name.value.clone(), c)))
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
    // The agent's initial beliefs hold at the start of every run, as in Jason.
    let mut agent_beliefs = Vec::new();
    for item in agent.items() {
        if let Item::Belief(b) = item {
            match ground_atom(&b.literal, &atoms, &universe) {
                Ok(a) => {
                    facts.insert(a);
                    if !agent_beliefs.contains(&a) {
                        agent_beliefs.push(a);
                    }
                }
                Err(d) => errors.push(d),
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
    let all: Vec<Cond> = constraints
        .iter()
        .cloned()
        .chain(invariants.iter().map(|(_, c)| c.clone()))
        .collect();
    // The initial states are held at once: bounded by `max_states` and by memory.
    let state_bytes = (atoms.len() / 8 + 32) as u64;
    let by_memory = usize::try_from(INITIAL_STATES_BYTES / state_bytes).unwrap_or(usize::MAX);
    let limit = usize::try_from(manifest.bounds.max_states)
        .unwrap_or(usize::MAX)
        .min(by_memory);
    let states = match initial::enumerate(atoms.len(), &facts, &vary, &all, limit) {
        Ok(s) => s,
        Err(TooMany { found }) => {
            let why = if found == by_memory {
                format!(" (each takes {state_bytes} bytes: more would not fit in 1 GiB): vary fewer predicates or constrain them")
            } else {
                ": raise `[bounds] max_states` or constrain `[initial]`".to_string()
            };
            let mut d =
                Diagnostic::error("input", format!("more than {found} initial states{why}"))
                    .in_file(manifest.path.display().to_string());
            if let Some(v) = manifest.initial.vary.first() {
                d = d.with_label(v.span, "the atoms of these predicates vary");
            }
            return fail(map, vec![d]);
        }
    };
    if states.is_empty() {
        let d = Diagnostic::error(
            "input",
            "no initial state satisfies the facts, the constraints and the invariants",
        )
        .in_file(manifest.path.display().to_string())
        .with_help("every check would pass vacuously; look for contradicting constraints");
        return fail(map, vec![d]);
    }
    Ok(Project {
        map,
        manifest,
        agent,
        domain,
        universe,
        vocabulary,
        plans,
        atoms,
        actions,
        constraints,
        invariants,
        initial: InitialStates {
            facts,
            vary,
            agent_beliefs,
            states,
        },
    })
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
