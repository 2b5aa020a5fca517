//! `bdi-check parse` on a PDDL domain or a whole project: what the finite model holds.

use crate::model::atoms::AtomId;
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
    /// The environment as data: every ground atom and every ground action with its
    /// precondition and effects, for tools that run the same environment (a recorder
    /// that drives real Jason against it, a simulator).
    pub ground: GroundModel,
}

/// The ground environment model of a project.
#[derive(Clone, Debug, Serialize)]
pub struct GroundModel {
    /// Every ground atom, in id order.
    pub atoms: Vec<String>,
    /// Every ground action.
    pub actions: Vec<ActionModel>,
}

/// One ground action as data. A condition is `true`, `false`, `{"atom": a}`,
/// `{"not": c}`, `{"and": [c...]}`, `{"or": [c...]}` or `{"count": [a...], "cmp": op,
/// "n": k}` (how many of the atoms hold, compared with `k`).
#[derive(Clone, Debug, Serialize)]
pub struct ActionModel {
    /// `navigateTo(table)`.
    pub action: String,
    /// When it may run.
    pub pre: serde_json::Value,
    /// Its conditional effects, each `when` read in the state before the action; all
    /// deletions apply before all additions.
    pub effects: Vec<EffectModel>,
}

/// One conditional effect.
#[derive(Clone, Debug, Serialize)]
pub struct EffectModel {
    /// The condition, read before the action.
    pub when: serde_json::Value,
    /// Atoms made true.
    pub add: Vec<String>,
    /// Atoms made false.
    pub del: Vec<String>,
}

fn cond_json(c: &crate::model::cond::Cond, show: &dyn Fn(AtomId) -> String) -> serde_json::Value {
    use crate::model::cond::{Cond, CountCmp};
    use serde_json::json;
    match c {
        Cond::True => json!(true),
        Cond::False => json!(false),
        Cond::Atom(a) => json!({ "atom": show(*a) }),
        Cond::Not(c) => json!({ "not": cond_json(c, show) }),
        Cond::And(cs) => {
            json!({ "and": cs.iter().map(|c| cond_json(c, show)).collect::<Vec<_>>() })
        }
        Cond::Or(cs) => json!({ "or": cs.iter().map(|c| cond_json(c, show)).collect::<Vec<_>>() }),
        Cond::Count { atoms, cmp, n } => {
            let op = match cmp {
                CountCmp::Eq => "==",
                CountCmp::Lt => "<",
                CountCmp::Le => "<=",
                CountCmp::Gt => ">",
                CountCmp::Ge => ">=",
                CountCmp::Ne => "!=",
            };
            json!({ "count": atoms.iter().map(|a| show(*a)).collect::<Vec<_>>(), "cmp": op, "n": n })
        }
    }
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
    /// How many (of those enumerated: see `complete`).
    pub count: usize,
    /// Whether `count` is all of them: enumeration stops at `[bounds] max_states` (and at
    /// 1 GiB of states).
    pub complete: bool,
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
    let show = |a: AtomId| p.atoms.display(a, u);
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
        atoms: (0..p.atoms.len() as u32).map(|a| show(AtomId(a))).collect(),
        actions: p.actions.all().iter().map(|a| a.display(u)).collect(),
        ground: GroundModel {
            atoms: (0..p.atoms.len() as u32).map(|a| show(AtomId(a))).collect(),
            actions: p
                .actions
                .all()
                .iter()
                .map(|a| ActionModel {
                    action: a.display(u),
                    pre: cond_json(&a.pre, &show),
                    effects: a
                        .effects
                        .iter()
                        .map(|e| EffectModel {
                            when: cond_json(&e.when, &show),
                            add: e.add.iter().map(|x| show(*x)).collect(),
                            del: e.del.iter().map(|x| show(*x)).collect(),
                        })
                        .collect(),
                })
                .collect(),
        },
        initial: InitialOutline {
            count: p.initial.states().len(),
            complete: p.initial.complete(),
            facts: p.initial.facts.iter().map(show).collect(),
            vary: p.initial.vary.iter().map(|a| show(*a)).collect(),
            states: p
                .initial
                .states()
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
        "{}: {} objects, {} ground atoms, {} ground actions, {}{} initial states\n",
        o.file,
        o.objects
            .iter()
            .find(|t| t.ty == "object")
            .map_or(0, |t| t.objects.len()),
        o.atoms.len(),
        o.actions.len(),
        if o.initial.complete { "" } else { "more than " },
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
        "  initial states ({}{}): every assignment of {} varying atoms that satisfies the constraints and invariants\n",
        if o.initial.complete { "" } else { "the first " },
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
