//! Type checking across the agent, the PDDL domain and the manifest.
//!
//! [`check`] reads every predicate, action and goal that the plan library, the manifest's
//! formulas and the users' expected pairs use, checks them against the PDDL domain and the
//! [`Universe`] of objects, and returns the project's [`Vocabulary`]: the signatures the rest of
//! the tool builds on. Every error is collected (not just the first), located, with code
//! `input` (SPEC §2: bad input is exit 2).
//!
//! # Names
//!
//! * A *predicate* is a PDDL predicate (an *environment* predicate, changed only by actions and
//!   perceived by the agent) or a *mental note*: a belief the plans add themselves (`+b`,
//!   `+>b`, `++b`, `-+b`) or an initial belief of the `.asl`, whose name PDDL does not declare.
//!   Predicates are known by name: a mental note has the arity of its first addition. A
//!   strongly negated note `~p` is a predicate of its own, named `~p` (Jason gives `~p` and
//!   `p` different predicate indicators: both can be believed at once).
//! * An *action* in a plan body is a PDDL action, an internal action (`.print`, ...), or
//!   *undefined*. An undefined action is not an error here but a lint finding
//!   (`undefined-action`, SPEC §2): [`Vocabulary::undefined_actions`] lists every such call.
//!   The action named by `[explanation] emitted_by` is the agent's own way of explaining: it
//!   need not be in PDDL, and calls to it are not undefined actions.
//! * A *goal* is `name/arity`: every achievement goal that is a plan trigger, a subgoal
//!   (`!g`, `!!g`), an initial goal of the `.asl`, or a request of `[requests] goals`. A
//!   request for a goal that has no plan is recorded, not refused: that is lint's
//!   `no-plan-for-goal`.
//! * A *rule* head `r(X) :- ...` is usable in contexts and formulas like a predicate.
//!
//! # Types
//!
//! Within one *clause* (a plan with its trigger, context and body; a rule; an initial belief;
//! a manifest formula; an expected pair, whose two sides share variables), a variable's type is
//! the most specific type required by every typed position it occurs in: the parameters of
//! PDDL predicates and actions, of mental notes, of goals and of rule heads. Two unrelated
//! types for one variable are an error naming both positions. An atom in a typed position must
//! be an object (a PDDL constant or a manifest object) of the position's type or a subtype.
//!
//! Parameter types of goals, rules and mental notes are inferred, to a fixed point:
//!
//! * a goal's parameter is the least common ancestor of the types its `+!g` plans give the
//!   trigger's argument (a variable typed by the plan's context and body, or a constant's own
//!   type); plans that leave the argument unconstrained do not widen it, and a parameter no
//!   plan constrains is `object`. A subgoal `!g(X)` in a plan then types `X`;
//! * a rule's parameter likewise, from the clauses of the rule;
//! * a mental note's parameter is the least common ancestor of the types of its arguments at
//!   every addition (an unconstrained variable counts as `object`).
//!
//! While the fixed point is computed, the positions that *define* a type (the trigger of a
//! goal's own `+!` plan, a rule's head, a mental note's addition) do not constrain; in the final
//! pass every position does, which can only refine a variable, never contradict it.
//!
//! # What the model does not support
//!
//! The model's state is a set of ground atoms over objects, so numbers, strings, lists and
//! structured terms cannot be arguments of PDDL predicates, PDDL actions or mental notes;
//! environment atoms change only through actions (and are perceived), so `+b`/`-b`/`-+b` and
//! initial beliefs of an environment predicate are refused, as is strong negation `~p` of one
//! (the environment is closed-world: write `not p`). Only the internal actions of SPEC §4 are
//! modelled. Namespaces are ignored: `ns::p` is `p`.

use crate::model::universe::{TypeId, Universe};
use crate::syntax::loader::LoadedAgent;
use crate::syntax::manifest::Manifest;
use crate::syntax::pddl;
use crate::syntax::{Diagnostic, SourceMap, Span};
use std::collections::{HashMap, HashSet};

mod agent;
mod declare;
mod diagnostics;
mod formulas;
mod literals;
mod manifest;
mod types;

// ===== the vocabulary ===========================================================================

/// The checked vocabulary of a project: every predicate, action, goal and rule, with types.
///
/// Every list is in a deterministic order (declaration or first appearance), so indices are
/// stable from run to run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Vocabulary {
    /// Every PDDL predicate in declaration order, then every mental note in order of first
    /// appearance in the `.asl` (includes followed in Jason's order).
    pub predicates: Vec<PredicateSig>,
    /// Every PDDL action, in declaration order.
    pub actions: Vec<ActionSig>,
    /// Every achievement goal, in order of first appearance: the `.asl` first (plan triggers,
    /// subgoals, initial goals), then `[requests] goals`.
    pub goals: Vec<GoalSig>,
    /// Every rule head `name/arity` of the `.asl`, in order of first appearance.
    pub rules: Vec<RuleSig>,
    /// Every call in a plan body of an action that is neither a PDDL action, an internal action
    /// nor the `emitted_by` action, in source order (one entry per call). Not an error: the
    /// caller reports them as `undefined-action` findings.
    pub undefined_actions: Vec<UndefinedAction>,
    /// Test goals `?p(...)` on a predicate nothing defines (no PDDL predicate, mental
    /// note, rule or `+?p` plan): Jason just fails them, so they are lint findings
    /// (`undefined-predicate`), not bad input.
    pub undefined_tests: Vec<UndefinedAction>,
}

/// A predicate: its name and parameter types.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PredicateSig {
    /// The name, as in PDDL and Jason.
    pub name: String,
    /// One type per parameter.
    pub params: Vec<TypeId>,
    /// Where it comes from.
    pub kind: PredicateKind,
}

impl PredicateSig {
    /// Whether this is a PDDL predicate.
    pub fn is_environment(&self) -> bool {
        matches!(self.kind, PredicateKind::Environment { .. })
    }

    /// The predicate's declaration (PDDL) or first addition (mental note).
    pub fn span(&self) -> Span {
        match self.kind {
            PredicateKind::Environment { span } | PredicateKind::MentalNote { span } => span,
        }
    }
}

/// Where a predicate comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PredicateKind {
    /// Declared in the PDDL domain: changed by actions, perceived by the agent.
    Environment {
        /// The declaration `(p ?x - t)` in the `.pddl` file.
        span: Span,
    },
    /// A belief the agent adds itself (or an initial belief of the `.asl`).
    MentalNote {
        /// The literal of its first addition (or initial belief).
        span: Span,
    },
}

/// A PDDL action.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActionSig {
    /// The name.
    pub name: String,
    /// One type per parameter.
    pub params: Vec<TypeId>,
    /// The action's name in its `(:action NAME ...)`.
    pub span: Span,
    /// The parameter named `?agent`, if any: the agent that does the action (Jason's
    /// environment is told who acts, `Environment.executeAction(agName, action)`), which
    /// a plan does not write: `move(table)` by `fetcher` is `move(fetcher, table)`.
    pub actor: Option<usize>,
}

impl ActionSig {
    /// How many arguments a plan writes.
    pub fn call_arity(&self) -> usize {
        self.params.len() - usize::from(self.actor.is_some())
    }

    /// The parameter a plan's argument `i` stands for.
    pub fn param_of_arg(&self, i: usize) -> usize {
        match self.actor {
            Some(a) if i >= a => i + 1,
            _ => i,
        }
    }

    /// The action `t` (as a plan writes it) done by `agent`: with the agent's name as the
    /// `?agent` argument. `t` itself when the action has none or `t` has the wrong arity.
    pub fn done_by(&self, t: &crate::model::Term, agent: &str) -> crate::model::Term {
        match self.actor {
            Some(a) if t.arity() == self.call_arity() => {
                let mut args = t.args().to_vec();
                args.insert(a, crate::model::Term::atom(agent));
                crate::model::Term::structure(t.functor().unwrap_or(""), args)
            }
            _ => t.clone(),
        }
    }
}

/// An achievement goal `name/arity`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GoalSig {
    /// The name.
    pub name: String,
    /// The number of arguments.
    pub arity: usize,
    /// The inferred parameter types (`object` where no plan constrains one).
    pub params: Vec<TypeId>,
    /// The trigger of its first `+!` plan; when it has none, its first mention (a subgoal, an
    /// initial goal, another plan's trigger, or the request in the manifest).
    pub span: Span,
    /// Whether some plan has the trigger `+!name(...)` with this arity.
    pub has_plan: bool,
}

/// A rule head `name/arity` of the `.asl`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RuleSig {
    /// The name.
    pub name: String,
    /// The number of arguments.
    pub arity: usize,
    /// The inferred parameter types (`object` where no clause constrains one).
    pub params: Vec<TypeId>,
    /// The head of its first clause.
    pub span: Span,
}

/// A body action that nothing defines (SPEC §2: a lint finding, `undefined-action`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UndefinedAction {
    /// The action's name.
    pub name: String,
    /// The number of arguments of this call.
    pub arity: usize,
    /// The call.
    pub span: Span,
}

impl Vocabulary {
    /// The predicate of that name (PDDL or mental note), with its index in
    /// [`Vocabulary::predicates`].
    pub fn predicate(&self, name: &str) -> Option<(usize, &PredicateSig)> {
        self.predicates
            .iter()
            .enumerate()
            .find(|(_, p)| p.name == name)
    }

    /// The PDDL action of that name, with its index in [`Vocabulary::actions`].
    pub fn action(&self, name: &str) -> Option<(usize, &ActionSig)> {
        self.actions
            .iter()
            .enumerate()
            .find(|(_, a)| a.name == name)
    }

    /// The goal `name/arity`, with its index in [`Vocabulary::goals`].
    pub fn goal(&self, name: &str, arity: usize) -> Option<(usize, &GoalSig)> {
        self.goals
            .iter()
            .enumerate()
            .find(|(_, g)| g.name == name && g.arity == arity)
    }

    /// The rule `name/arity`, with its index in [`Vocabulary::rules`].
    pub fn rule(&self, name: &str, arity: usize) -> Option<(usize, &RuleSig)> {
        self.rules
            .iter()
            .enumerate()
            .find(|(_, r)| r.name == name && r.arity == arity)
    }

    /// The mental notes: the predicates that are not PDDL's, in order.
    pub fn mental_notes(&self) -> impl Iterator<Item = &PredicateSig> {
        self.predicates.iter().filter(|p| !p.is_environment())
    }
}

/// The internal actions bdi-check models (SPEC §4).
pub const INTERNAL_ACTIONS: &[&str] = &[
    ".print",
    ".count",
    ".desire",
    ".intend",
    ".drop_desire",
    ".drop_intention",
    ".succeed_goal",
    ".fail_goal",
    ".findall",
    ".println",
    ".fail",
    ".my_name",
    ".abolish",
    ".wait",
    ".random",
    ".add_plan",
    ".remove_plan",
    ".send",
    ".broadcast",
];

/// Whether the reasoning cycle models the internal action `name` (those above, and the
/// pure ones of [`super::internal::PURE`]).
fn modelled_action(name: &str) -> bool {
    INTERNAL_ACTIONS.contains(&name) || super::internal::PURE.iter().any(|(n, _)| *n == name)
}

/// Whether `name` is an arithmetic function bdi-check evaluates inside expressions
/// (`X = math.abs(Y)`; [`super::internal::FUNCTIONS`]), besides `.count(Query)`.
fn arithmetic_function(name: &str) -> bool {
    super::internal::FUNCTIONS.iter().any(|(f, _)| *f == name)
}

/// Internal actions whose argument is a goal.
const GOAL_ACTIONS: &[&str] = &[
    ".desire",
    ".intend",
    ".drop_desire",
    ".drop_intention",
    ".succeed_goal",
    ".fail_goal",
];

// ===== entry point ==============================================================================

/// Checks every predicate, action and goal used in the plans (`agent`), in the manifest's
/// formulas, facts, requests, phrases and expected pairs, against the PDDL `domain` and the
/// `universe` of objects; `map` resolves spans for messages that name two places.
///
/// Returns the project's [`Vocabulary`], or every error found (code `input`), sorted by
/// position. Undefined body actions are not errors: see [`Vocabulary::undefined_actions`].
pub fn check(
    agent: &LoadedAgent,
    domain: &pddl::Domain,
    manifest: &Manifest,
    universe: &Universe,
    map: &SourceMap,
) -> Result<Vocabulary, Vec<Diagnostic>> {
    check_items(&agent.items(), domain, manifest, universe, map)
}

/// [`check`] of the items of one agent or of several together (a multi-agent project has
/// one vocabulary, so that what one agent tells another means the same to both).
pub fn check_items(
    items: &[&crate::syntax::ast::Item],
    domain: &pddl::Domain,
    manifest: &Manifest,
    universe: &Universe,
    map: &SourceMap,
) -> Result<Vocabulary, Vec<Diagnostic>> {
    let items = items.to_vec();
    let mut c = Checker::new(domain, manifest, universe, map);
    c.declare(&items, manifest);
    c.collect_agent(&items);
    c.collect_manifest(manifest);
    let types = c.infer();
    c.final_pass(&types);
    let Checker {
        mut diags,
        preds,
        actions,
        goals,
        rules,
        undefined,
        undefined_tests,
        ..
    } = c;
    if !diags.is_empty() {
        diags.sort_by_key(|d| d.span.map(|s| (s.file, s.start, s.end)));
        diags.dedup();
        return Err(diags);
    }
    let obj = |t: &Option<TypeId>| t.unwrap_or(TypeId::OBJECT);
    Ok(Vocabulary {
        predicates: preds
            .iter()
            .enumerate()
            .map(|(i, p)| PredicateSig {
                name: p.name.clone(),
                params: types.preds[i].iter().map(obj).collect(),
                kind: if p.env {
                    PredicateKind::Environment { span: p.span }
                } else {
                    PredicateKind::MentalNote { span: p.span }
                },
            })
            .collect(),
        actions: actions
            .into_iter()
            .map(|a| ActionSig {
                name: a.name,
                params: a.params,
                span: a.span,
                actor: a.actor,
            })
            .collect(),
        goals: goals
            .into_iter()
            .enumerate()
            .map(|(i, g)| GoalSig {
                name: g.name,
                arity: g.arity,
                params: types.goals[i].iter().map(obj).collect(),
                span: g.plan_span.unwrap_or(g.span),
                has_plan: g.plan_span.is_some(),
            })
            .collect(),
        rules: rules
            .into_iter()
            .enumerate()
            .map(|(i, r)| RuleSig {
                name: r.name,
                arity: r.arity,
                params: types.rules[i].iter().map(obj).collect(),
                span: r.span,
            })
            .collect(),
        undefined_actions: undefined,
        undefined_tests,
    })
}

// ===== internal tables ==========================================================================

/// Which signature a typed position belongs to (indices into the checker's tables).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sig {
    Pred(usize),
    Action(usize),
    Goal(usize),
    Rule(usize),
}

/// Whether a position uses a signature or defines its types (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Use,
    Define,
}

/// A variable or a constant in a typed position.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Arg {
    Var(String),
    Const(String),
}

/// One argument in a typed position.
#[derive(Clone, Debug)]
struct Occ {
    arg: Arg,
    span: Span,
    sig: Sig,
    index: usize,
    role: Role,
}

/// The typed positions of one clause: variables are shared within it.
#[derive(Clone, Debug, Default)]
struct Clause {
    occs: Vec<Occ>,
    /// A manifest formula: every named variable must be in a typed position.
    free_check: bool,
    /// Every named variable, with its first span (for the free-variable check).
    vars: Vec<(String, Span)>,
    /// Variables that are results of `.count` (numbers, not objects).
    counted: HashSet<String>,
}

#[derive(Clone, Debug)]
struct PredInfo {
    name: String,
    env: bool,
    /// PDDL: the declaration; mental note: the first addition.
    span: Span,
    arity: usize,
}

#[derive(Clone, Debug)]
struct ActInfo {
    name: String,
    params: Vec<TypeId>,
    span: Span,
    decl: Span,
    /// The `?agent` parameter.
    actor: Option<usize>,
}

#[derive(Clone, Debug)]
struct GoalInfo {
    name: String,
    arity: usize,
    span: Span,
    plan_span: Option<Span>,
}

#[derive(Clone, Debug)]
struct RuleInfo {
    name: String,
    arity: usize,
    span: Span,
}

/// Parameter types, `None` while unconstrained.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Types {
    preds: Vec<Vec<Option<TypeId>>>,
    goals: Vec<Vec<Option<TypeId>>>,
    rules: Vec<Vec<Option<TypeId>>>,
}

/// A variable's type in a clause, and the position that made it so.
#[derive(Clone, Copy, Debug)]
struct VarInfo {
    ty: TypeId,
    span: Span,
    sig: Sig,
    index: usize,
}

/// How a belief literal is used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Usage {
    /// In a context, a rule body, a condition or a manifest formula.
    Query,
    /// In a test goal `?b`.
    Test,
    /// In a belief-event trigger `+b`/`-b`.
    Trigger,
    /// `+b`, `+>b`, `++b`, or an initial belief.
    Add,
    /// `-+b`: an addition too.
    Replace,
    /// `-b`, `--b`.
    Del,
    /// An `[initial] facts` entry.
    Fact,
    /// A phrase pattern.
    Pattern,
}

/// Where a formula is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scope {
    /// In the `.asl`.
    Agent,
    /// In the manifest; `properties` allows `.intend` and `.desire`.
    Manifest { properties: bool },
}

struct Checker<'a> {
    universe: &'a Universe,
    map: &'a SourceMap,
    preds: Vec<PredInfo>,
    /// PDDL parameter types (mental notes: empty, inferred).
    pddl_params: Vec<Vec<TypeId>>,
    pred_ids: HashMap<String, usize>,
    actions: Vec<ActInfo>,
    action_ids: HashMap<String, usize>,
    goals: Vec<GoalInfo>,
    goal_ids: HashMap<(String, usize), usize>,
    rules: Vec<RuleInfo>,
    rule_ids: HashMap<(String, usize), usize>,
    /// Names of test goals with a `+?b` plan.
    test_goals: HashSet<String>,
    /// Names of the non-internal actions the plans call.
    called: HashSet<String>,
    /// `[bounds] numbers` is declared: integers are objects.
    numbers: bool,
    /// Its range.
    manifest_numbers: Option<(i64, i64)>,
    /// `[bounds] random` is declared: `.random(X)` has values to branch over.
    random: bool,
    emitted_by: Option<String>,
    clauses: Vec<Clause>,
    undefined: Vec<UndefinedAction>,
    undefined_tests: Vec<UndefinedAction>,
    diags: Vec<Diagnostic>,
}

impl<'a> Checker<'a> {
    fn new(
        domain: &'a pddl::Domain,
        manifest: &Manifest,
        universe: &'a Universe,
        map: &'a SourceMap,
    ) -> Checker<'a> {
        let ty = |n: &str| universe.type_id(n).unwrap_or(TypeId::OBJECT);
        let mut c = Checker {
            universe,
            map,
            preds: Vec::new(),
            pddl_params: Vec::new(),
            pred_ids: HashMap::new(),
            actions: Vec::new(),
            action_ids: HashMap::new(),
            goals: Vec::new(),
            goal_ids: HashMap::new(),
            rules: Vec::new(),
            rule_ids: HashMap::new(),
            test_goals: HashSet::new(),
            called: HashSet::new(),
            numbers: manifest.bounds.numbers.is_some(),
            manifest_numbers: manifest.bounds.numbers.as_ref().map(|n| n.value),
            random: manifest.bounds.random.is_some(),
            emitted_by: manifest
                .explanation
                .as_ref()
                .and_then(|e| e.emitted_by.as_ref())
                .map(|e| e.value.clone()),
            clauses: Vec::new(),
            undefined: Vec::new(),
            undefined_tests: Vec::new(),
            diags: Vec::new(),
        };
        for p in &domain.predicates {
            if c.pred_ids.contains_key(&p.name) {
                continue; // the PDDL front end reports duplicates
            }
            c.pred_ids.insert(p.name.clone(), c.preds.len());
            c.preds.push(PredInfo {
                name: p.name.clone(),
                env: true,
                span: p.span,
                arity: p.params.len(),
            });
            c.pddl_params
                .push(p.params.iter().map(|v| ty(&v.ty)).collect());
        }
        for a in &domain.actions {
            if c.action_ids.contains_key(&a.name) {
                continue;
            }
            c.action_ids.insert(a.name.clone(), c.actions.len());
            c.actions.push(ActInfo {
                name: a.name.clone(),
                params: a.params.iter().map(|v| ty(&v.ty)).collect(),
                span: a.name_span,
                decl: a.span,
                actor: a
                    .params
                    .iter()
                    .position(|v| v.name.eq_ignore_ascii_case("agent")),
            });
        }
        c
    }
}
