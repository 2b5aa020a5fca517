//! `bdi-check parse` on a PDDL domain or a whole project: what the finite model holds.

use crate::model::project::Project;
use crate::syntax::pddl::Domain;
use crate::syntax::{Location, SourceMap};
use serde::Serialize;

/// The outline of a PDDL domain file.
#[derive(Clone, Debug, Serialize)]
pub struct DomainOutline {
    /// The file.
    pub file: String,
    /// `(domain NAME)`.
    pub name: String,
    /// Requirement flags.
    pub requirements: Vec<String>,
    /// `type - parent`.
    pub types: Vec<String>,
    /// `constant - type`.
    pub constants: Vec<String>,
    /// `(p ?x - t)`.
    pub predicates: Vec<String>,
    /// Each action with its parameters and place.
    pub actions: Vec<ActionOutline>,
}

/// One action schema.
#[derive(Clone, Debug, Serialize)]
pub struct ActionOutline {
    /// `navigateTo(?to - location)`.
    pub signature: String,
    /// Where it is declared.
    pub location: Location,
}

/// Outlines a parsed domain.
pub fn domain_outline(file: &str, d: &Domain, map: &SourceMap) -> DomainOutline {
    let params = |ps: &[crate::syntax::pddl::TypedVar]| {
        ps.iter()
            .map(|p| format!("?{} - {}", p.name, p.ty))
            .collect::<Vec<_>>()
            .join(" ")
    };
    DomainOutline {
        file: file.to_string(),
        name: d.name.clone(),
        requirements: d.requirements.iter().map(|r| r.name.clone()).collect(),
        types: d
            .types
            .iter()
            .map(|t| format!("{} - {}", t.name, t.parent))
            .collect(),
        constants: d
            .constants
            .iter()
            .map(|c| format!("{} - {}", c.name, c.ty))
            .collect(),
        predicates: d
            .predicates
            .iter()
            .map(|p| {
                format!(
                    "({}{}{})",
                    p.name,
                    if p.params.is_empty() { "" } else { " " },
                    params(&p.params)
                )
            })
            .collect(),
        actions: d
            .actions
            .iter()
            .map(|a| ActionOutline {
                signature: format!("{}({})", a.name, params(&a.params)),
                location: map.location(a.span),
            })
            .collect(),
    }
}

/// What a project grounds to.
#[derive(Clone, Debug, Serialize)]
pub struct ProjectOutline {
    /// The manifest.
    pub file: String,
    /// Objects by type (each type lists its own objects and its subtypes').
    pub objects: Vec<TypeObjects>,
    /// Every ground atom, in id order.
    pub atoms: Vec<String>,
    /// Every ground action.
    pub actions: Vec<String>,
    /// The initial states.
    pub initial: InitialOutline,
}

/// The objects of one type.
#[derive(Clone, Debug, Serialize)]
pub struct TypeObjects {
    /// The type.
    #[serde(rename = "type")]
    pub ty: String,
    /// Its objects.
    pub objects: Vec<String>,
}

/// The initial states of a project.
#[derive(Clone, Debug, Serialize)]
pub struct InitialOutline {
    /// How many.
    pub count: usize,
    /// Atoms true in all of them.
    pub facts: Vec<String>,
    /// Atoms that may start either way.
    pub vary: Vec<String>,
    /// Each state as the atoms true in it.
    pub states: Vec<Vec<String>>,
}

/// Outlines a loaded project.
pub fn project_outline(file: &str, p: &Project) -> ProjectOutline {
    let u = &p.universe;
    let show = |a| p.atoms.display(a, u);
    ProjectOutline {
        file: file.to_string(),
        objects: (0..u.type_count() as u16)
            .map(crate::model::TypeId)
            .filter(|t| !u.objects_of(*t).is_empty())
            .map(|t| TypeObjects {
                ty: u.type_name(t).to_string(),
                objects: u
                    .objects_of(t)
                    .iter()
                    .map(|o| u.object_name(*o).to_string())
                    .collect(),
            })
            .collect(),
        atoms: (0..p.atoms.len() as u32)
            .map(|a| show(crate::model::atoms::AtomId(a)))
            .collect(),
        actions: p.actions.all().iter().map(|a| a.display(u)).collect(),
        initial: InitialOutline {
            count: p.initial.states.len(),
            facts: p.initial.facts.iter().map(show).collect(),
            vary: p.initial.vary.iter().map(|a| show(*a)).collect(),
            states: p
                .initial
                .states
                .iter()
                .map(|s| s.iter().map(show).collect())
                .collect(),
        },
    }
}

/// Human text for a domain outline.
pub fn render_domain(o: &DomainOutline) -> String {
    let mut out = format!(
        "{}: PDDL domain `{}`: {} types, {} constants, {} predicates, {} actions\n",
        o.file,
        o.name,
        o.types.len(),
        o.constants.len(),
        o.predicates.len(),
        o.actions.len()
    );
    if !o.requirements.is_empty() {
        out.push_str(&format!("  requirements  {}\n", o.requirements.join(" ")));
    }
    if !o.types.is_empty() {
        out.push_str(&format!("  types         {}\n", o.types.join(", ")));
    }
    if !o.constants.is_empty() {
        out.push_str(&format!("  constants     {}\n", o.constants.join(", ")));
    }
    for p in &o.predicates {
        out.push_str(&format!("  predicate     {p}\n"));
    }
    for a in &o.actions {
        out.push_str(&format!(
            "  action        {}  {}:{}\n",
            a.signature, a.location.file, a.location.line
        ));
    }
    out
}

/// How many initial states the human output lists before summarising the rest.
const SHOWN_STATES: usize = 10;

/// Human text for a project outline.
pub fn render_project(o: &ProjectOutline) -> String {
    let mut out = format!(
        "{}: {} objects, {} ground atoms, {} ground actions, {} initial states\n",
        o.file,
        o.objects
            .iter()
            .find(|t| t.ty == "object")
            .map_or(0, |t| t.objects.len()),
        o.atoms.len(),
        o.actions.len(),
        o.initial.count
    );
    out.push_str("  objects\n");
    for t in o.objects.iter().filter(|t| t.ty != "object") {
        out.push_str(&format!("    {:<12} {}\n", t.ty, t.objects.join(", ")));
    }
    out.push_str(&format!("  ground atoms ({})\n", o.atoms.len()));
    out.push_str(&wrap(&o.atoms, "    "));
    out.push_str(&format!("  ground actions ({})\n", o.actions.len()));
    out.push_str(&wrap(&o.actions, "    "));
    out.push_str(&format!(
        "  initial states ({}): every assignment of {} varying atoms that satisfies the constraints and invariants\n",
        o.initial.count,
        o.initial.vary.len()
    ));
    out.push_str(&format!("    facts: {}\n", o.initial.facts.join(", ")));
    for (i, s) in o.initial.states.iter().take(SHOWN_STATES).enumerate() {
        out.push_str(&format!("    {:>3}: {}\n", i + 1, s.join(", ")));
    }
    if o.initial.count > SHOWN_STATES {
        out.push_str(&format!(
            "    ... and {} more (`--format json` lists them all)\n",
            o.initial.count - SHOWN_STATES
        ));
    }
    out
}

fn wrap(items: &[String], indent: &str) -> String {
    let mut out = String::new();
    let mut line = String::new();
    for it in items {
        if !line.is_empty() && line.len() + it.len() + 2 > 96 {
            out.push_str(indent);
            out.push_str(&line);
            out.push('\n');
            line.clear();
        }
        if !line.is_empty() {
            line.push_str(", ");
        }
        line.push_str(it);
    }
    if !line.is_empty() {
        out.push_str(indent);
        out.push_str(&line);
        out.push('\n');
    }
    out
}
