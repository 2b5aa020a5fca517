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
use crate::syntax::ast::*;
use crate::syntax::loader::LoadedAgent;
use crate::syntax::manifest::{Formula, Manifest, StepFormula};
use crate::syntax::pddl;
use crate::syntax::{Diagnostic, SourceMap, Span};
use std::collections::{HashMap, HashSet};

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
    let items = agent.items();
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
            });
        }
        c
    }

    // ----- pass 1: declarations ---------------------------------------------------------------

    /// Finds mental notes, goals, rules, test goals and called actions, in order of first
    /// appearance, then the manifest's requests.
    fn declare(&mut self, items: &[&Item], manifest: &Manifest) {
        for item in items {
            match item {
                Item::Belief(b) => self.declare_note(&b.literal, b.literal.span),
                Item::Rule(r) => {
                    let key = (r.head.functor.clone(), r.head.args.len());
                    if !self.rule_ids.contains_key(&key) {
                        self.rule_ids.insert(key, self.rules.len());
                        self.rules.push(RuleInfo {
                            name: r.head.functor.clone(),
                            arity: r.head.args.len(),
                            span: r.head.span,
                        });
                    }
                }
                Item::InitialGoal(g) => {
                    self.declare_goal(&g.literal, g.literal.span, false);
                }
                Item::Plan(p) => self.declare_plan(p),
                Item::Directive(_) => {}
            }
        }
        for f in &manifest.requests.goals {
            let ExprKind::Literal(l) = &f.expr.kind else {
                continue;
            };
            let key = (l.functor.clone(), l.args.len());
            if self.goal_ids.contains_key(&key) {
                continue;
            }
            let others: Vec<&GoalInfo> =
                self.goals.iter().filter(|g| g.name == l.functor).collect();
            if let Some(g) = others.first() {
                let arities: Vec<String> = others.iter().map(|g| g.arity.to_string()).collect();
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "the goal `{}` takes {}, but this request gives it {}",
                        l.functor,
                        plural_or(&arities, "argument"),
                        count(l.args.len(), "argument"),
                    ),
                )
                .with_label(f.expr.span, "wrong number of arguments")
                .with_secondary(g.plan_span.unwrap_or(g.span), goal_place(g));
                self.diags.push(d);
                continue;
            }
            self.declare_goal(l, f.expr.span, false);
        }
    }

    fn declare_plan(&mut self, p: &Plan) {
        if let ExprKind::Literal(l) = &p.trigger.literal.kind {
            match p.trigger.kind {
                TriggerKind::Achieve => {
                    let is_plan = p.trigger.op == TriggerOp::Add;
                    self.declare_goal(l, p.trigger.span, is_plan);
                }
                TriggerKind::Test => {
                    self.test_goals.insert(l.functor.clone());
                }
                TriggerKind::Belief => {}
            }
        }
        if let Some(b) = &p.jason_body() {
            self.declare_body(b);
        }
        for sp in &p.sub_plans {
            self.declare_plan(sp);
        }
    }

    fn declare_body(&mut self, b: &Body) {
        for s in &b.steps {
            match &s.kind {
                StepKind::Action(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        if !l.is_internal_action() {
                            self.called.insert(l.functor.clone());
                        }
                    }
                }
                StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        self.declare_goal(l, e.span, false);
                    }
                }
                StepKind::AddBel(e)
                | StepKind::AddBelEnd(e)
                | StepKind::AddBelNewFocus(e)
                | StepKind::DelAddBel(e) => {
                    if let ExprKind::Literal(l) = &e.kind {
                        if !l.is_internal_action() {
                            self.declare_note(l, e.span);
                        }
                    }
                }
                StepKind::If {
                    branches,
                    else_body,
                } => {
                    for (_, b) in branches {
                        self.declare_body(b);
                    }
                    if let Some(b) = else_body {
                        self.declare_body(b);
                    }
                }
                StepKind::While { body, .. } | StepKind::For { body, .. } => {
                    self.declare_body(body)
                }
                StepKind::Fork { branches, .. } => {
                    for b in branches {
                        self.declare_body(b);
                    }
                }
                StepKind::Group(b) => self.declare_body(b),
                StepKind::Test(_)
                | StepKind::DelBel(_)
                | StepKind::DelBelNewFocus(_)
                | StepKind::Constraint(_) => {}
            }
        }
    }

    fn declare_note(&mut self, l: &Literal, span: Span) {
        let name = l.belief_name();
        if self.pred_ids.contains_key(name.as_ref())
            || (l.negated
                && self
                    .pred_ids
                    .get(&l.functor)
                    .is_some_and(|&p| self.preds[p].env))
        {
            return; // a PDDL predicate or its `~` (refused later), or a known note
        }
        self.pred_ids.insert(name.to_string(), self.preds.len());
        self.preds.push(PredInfo {
            name: name.into_owned(),
            env: false,
            span,
            arity: l.args.len(),
        });
    }

    fn declare_goal(&mut self, l: &Literal, span: Span, is_plan: bool) {
        let key = (l.functor.clone(), l.args.len());
        let id = match self.goal_ids.get(&key) {
            Some(&id) => id,
            None => {
                self.goal_ids.insert(key, self.goals.len());
                self.goals.push(GoalInfo {
                    name: l.functor.clone(),
                    arity: l.args.len(),
                    span,
                    plan_span: None,
                });
                self.goals.len() - 1
            }
        };
        if is_plan && self.goals[id].plan_span.is_none() {
            self.goals[id].plan_span = Some(span);
        }
    }

    // ----- pass 2: clauses and structural checks ----------------------------------------------

    fn collect_agent(&mut self, items: &[&Item]) {
        for item in items {
            match item {
                Item::Belief(b) => {
                    let mut cl = Clause::default();
                    let l = &b.literal;
                    if let Some(&p) = self.pred_ids.get(&l.functor) {
                        if self.preds[p].env {
                            let d = Diagnostic::error(
                                "input",
                                format!(
                                    "the initial belief `{}` is about the environment predicate `{}`, whose atoms start as the manifest's `[initial]` section says",
                                    self.map.slice(l.span),
                                    l.functor
                                ),
                            )
                            .with_label(l.span, "environment atom")
                            .with_secondary(self.preds[p].span, "declared in PDDL here")
                            .with_help("move it to `facts` (or `vary`) in `[initial]` of bdi-check.toml");
                            self.diags.push(d);
                            continue;
                        }
                    }
                    self.belief_literal(&mut cl, l, Usage::Add, Scope::Agent);
                    self.clauses.push(cl);
                }
                Item::Rule(r) => {
                    let mut cl = Clause::default();
                    let h = &r.head;
                    if let Some(&p) = self.pred_ids.get(&h.functor) {
                        if self.preds[p].env {
                            let d = Diagnostic::error(
                                "input",
                                format!(
                                    "the rule defines `{}`, an environment predicate: environment atoms change only through actions in this model",
                                    h.functor
                                ),
                            )
                            .with_label(h.span, "rule head")
                            .with_secondary(self.preds[p].span, "declared in PDDL here")
                            .with_help("give the rule a name of its own");
                            self.diags.push(d);
                        }
                    }
                    if let Some(&id) = self.rule_ids.get(&(h.functor.clone(), h.args.len())) {
                        for (i, a) in h.args.iter().enumerate() {
                            self.loose_arg(
                                &mut cl,
                                a,
                                Sig::Rule(id),
                                i,
                                Role::Define,
                                Scope::Agent,
                            );
                        }
                    }
                    self.formula(&mut cl, &r.body, Scope::Agent, Usage::Query);
                    self.clauses.push(cl);
                }
                Item::InitialGoal(g) => {
                    let mut cl = Clause::default();
                    self.goal_literal(&mut cl, &g.literal, Role::Use, Scope::Agent);
                    self.clauses.push(cl);
                }
                Item::Plan(p) => self.plan(p),
                Item::Directive(_) => {}
            }
        }
    }

    fn plan(&mut self, p: &Plan) {
        let mut cl = Clause::default();
        let t = &p.trigger;
        match (&t.literal.kind, t.kind) {
            (ExprKind::Literal(l), TriggerKind::Achieve) => {
                let role = if t.op == TriggerOp::Add {
                    Role::Define
                } else {
                    Role::Use
                };
                self.goal_literal(&mut cl, l, role, Scope::Agent);
            }
            (ExprKind::Literal(l), TriggerKind::Test) => {
                for a in &l.args {
                    self.term(&mut cl, a, Scope::Agent);
                }
            }
            (ExprKind::Literal(l), TriggerKind::Belief) => {
                self.belief_literal(&mut cl, l, Usage::Trigger, Scope::Agent);
            }
            (_, _) => {
                self.diags.push(
                    Diagnostic::error(
                        "input",
                        "a plan whose trigger is a variable is not supported by bdi-check",
                    )
                    .with_label(t.literal.span, "variable trigger")
                    .with_help("write one plan per goal or belief"),
                );
            }
        }
        if let Some(c) = &p.context {
            self.formula(&mut cl, c, Scope::Agent, Usage::Query);
        }
        if let Some(c) = &p.goal_condition {
            self.formula(&mut cl, c, Scope::Agent, Usage::Query);
        }
        if let Some(b) = &p.jason_body() {
            self.body(&mut cl, b);
        }
        self.clauses.push(cl);
        for sp in &p.sub_plans {
            self.plan(sp);
        }
    }

    fn body(&mut self, cl: &mut Clause, b: &Body) {
        for s in &b.steps {
            self.step(cl, s);
        }
    }

    fn step(&mut self, cl: &mut Clause, s: &Step) {
        match &s.kind {
            StepKind::Action(e) => match &e.kind {
                ExprKind::Literal(l) if l.is_internal_action() => {
                    self.internal(cl, l, Scope::Agent)
                }
                ExprKind::Literal(l) => self.body_action(cl, l),
                _ => self.unsupported(e.span, "an action held in a variable", "variable action"),
            },
            StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => match &e.kind {
                ExprKind::Literal(l) => self.goal_literal(cl, l, Role::Use, Scope::Agent),
                _ => self.unsupported(e.span, "a goal held in a variable", "variable goal"),
            },
            StepKind::Test(e) => self.formula(cl, e, Scope::Agent, Usage::Test),
            StepKind::AddBel(e) | StepKind::AddBelEnd(e) | StepKind::AddBelNewFocus(e) => {
                self.update(cl, e, Usage::Add)
            }
            StepKind::DelAddBel(e) => self.update(cl, e, Usage::Replace),
            StepKind::DelBel(e) | StepKind::DelBelNewFocus(e) => self.update(cl, e, Usage::Del),
            StepKind::Constraint(e) => self.formula(cl, e, Scope::Agent, Usage::Query),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    self.formula(cl, c, Scope::Agent, Usage::Query);
                    self.body(cl, b);
                }
                if let Some(b) = else_body {
                    self.body(cl, b);
                }
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                self.formula(cl, cond, Scope::Agent, Usage::Query);
                self.body(cl, body);
            }
            StepKind::Fork { branches, .. } => {
                for b in branches {
                    self.body(cl, b);
                }
            }
            StepKind::Group(b) => self.body(cl, b),
        }
    }

    fn unsupported(&mut self, span: Span, what: &str, label: &str) {
        self.diags.push(
            Diagnostic::error("input", format!("{what} is not supported by bdi-check"))
                .with_label(span, label),
        );
    }

    /// `+b`, `-b`, `-+b`, ... in a body.
    fn update(&mut self, cl: &mut Clause, e: &Expr, usage: Usage) {
        match &e.kind {
            ExprKind::Literal(l) => self.belief_literal(cl, l, usage, Scope::Agent),
            ExprKind::PlanTerm(_) => self.diags.push(
                Diagnostic::error(
                    "input",
                    "adding or removing plans at run time (`+{ ... }`) is not modelled by bdi-check",
                )
                .with_label(e.span, "plan term"),
            ),
            _ => self.unsupported(e.span, "a belief update held in a variable", "variable"),
        }
    }

    /// A non-internal action in a body: PDDL, `emitted_by`, or undefined.
    fn body_action(&mut self, cl: &mut Clause, l: &Literal) {
        if let Some(&a) = self.action_ids.get(&l.functor) {
            self.action_args(cl, l, a);
        } else {
            if self.emitted_by.as_deref() != Some(l.functor.as_str()) {
                self.undefined.push(UndefinedAction {
                    name: l.functor.clone(),
                    arity: l.args.len(),
                    span: l.span,
                });
            }
            for a in &l.args {
                self.term(cl, a, Scope::Agent);
            }
        }
    }

    /// The arguments of a call of PDDL action `a`, after an arity check.
    fn action_args(&mut self, cl: &mut Clause, l: &Literal, a: usize) {
        let want = self.actions[a].params.len();
        if l.args.len() != want {
            let d = Diagnostic::error(
                "input",
                format!(
                    "the action `{}` takes {}, but {} given",
                    l.functor,
                    count(want, "argument"),
                    given(l.args.len())
                ),
            )
            .with_label(l.span, format!("expected {}", count(want, "argument")))
            .with_secondary(self.actions[a].decl, "declared in PDDL here");
            self.diags.push(d);
            return;
        }
        for (i, x) in l.args.iter().enumerate() {
            self.strict_arg(cl, x, Sig::Action(a), i, Role::Use);
        }
    }

    /// A goal `g(args)` (trigger, subgoal, initial goal, request): its arguments are typed by
    /// the goal's parameters.
    fn goal_literal(&mut self, cl: &mut Clause, l: &Literal, role: Role, scope: Scope) {
        if let Some(&g) = self.goal_ids.get(&(l.functor.clone(), l.args.len())) {
            for (i, a) in l.args.iter().enumerate() {
                self.loose_arg(cl, a, Sig::Goal(g), i, role, scope);
            }
        }
    }

    /// A reference to a goal that must be known: `.desire(g)`, a pair's `!g`, a phrase `!g`.
    fn known_goal(&mut self, cl: &mut Clause, l: &Literal, span: Span, scope: Scope) {
        if self
            .goal_ids
            .contains_key(&(l.functor.clone(), l.args.len()))
        {
            self.goal_literal(cl, l, Role::Use, scope);
            return;
        }
        let others: Vec<&GoalInfo> = self.goals.iter().filter(|g| g.name == l.functor).collect();
        let d = if let Some(g) = others.first() {
            let arities: Vec<String> = others.iter().map(|g| g.arity.to_string()).collect();
            Diagnostic::error(
                "input",
                format!(
                    "the goal `{}` takes {}, but {} given",
                    l.functor,
                    plural_or(&arities, "argument"),
                    given(l.args.len())
                ),
            )
            .with_label(span, "wrong number of arguments")
            .with_secondary(g.plan_span.unwrap_or(g.span), goal_place(g))
        } else {
            let names: Vec<&str> = self.goals.iter().map(|g| g.name.as_str()).collect();
            let hint = suggest(&l.functor, names)
                .map(|s| format!("; did you mean `{s}`?"))
                .unwrap_or_default();
            Diagnostic::error("input", format!("unknown goal `{}`{hint}", l.functor))
                .with_label(span, "no plan, subgoal or request has this goal")
        };
        self.diags.push(d);
    }

    /// A literal read as a belief: a PDDL predicate, a mental note or a rule.
    fn belief_literal(&mut self, cl: &mut Clause, l: &Literal, usage: Usage, scope: Scope) {
        let belief_name = l.belief_name();
        let name = belief_name.as_ref();
        let arity = l.args.len();
        // `~p` of a PDDL predicate is checked (and refused) against `p` itself.
        let env_positive = l
            .negated
            .then(|| self.pred_ids.get(&l.functor).copied())
            .flatten()
            .filter(|&p| self.preds[p].env);
        if let Some(p) = env_positive.or_else(|| self.pred_ids.get(name).copied()) {
            let info = self.preds[p].clone();
            if info.env {
                if matches!(usage, Usage::Add | Usage::Replace | Usage::Del) {
                    let op = match usage {
                        Usage::Add => "add",
                        Usage::Replace => "replace",
                        _ => "delete",
                    };
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "a plan cannot {op} `{name}`: it is an environment predicate, whose atoms change only through actions and perception in this model"
                        ),
                    )
                    .with_label(l.span, "belief update on an environment atom")
                    .with_secondary(info.span, "declared in PDDL here")
                    .with_help("call a PDDL action whose effect changes it, or use a mental note with a name of its own");
                    self.diags.push(d);
                    return;
                }
                if l.negated {
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "strong negation `~{}` of an environment predicate: the environment is closed-world, an atom that is not true is false",
                            l.functor
                        ),
                    )
                    .with_label(l.span, "strong negation")
                    .with_help(format!("write `not {}`", self.map.slice(l.span).trim_start_matches('~')));
                    self.diags.push(d);
                    return;
                }
            }
            if arity != info.arity {
                let (kind, at) = if info.env {
                    ("declared in PDDL here", info.span)
                } else {
                    ("first added here", info.span)
                };
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "`{name}` takes {}, but {} given",
                        count(info.arity, "argument"),
                        given(arity)
                    ),
                )
                .with_label(
                    l.span,
                    format!("expected {}", count(info.arity, "argument")),
                )
                .with_secondary(at, kind);
                self.diags.push(d);
                return;
            }
            let role = if matches!(usage, Usage::Add | Usage::Replace) {
                Role::Define
            } else {
                Role::Use
            };
            for (i, a) in l.args.iter().enumerate() {
                self.strict_arg(cl, a, Sig::Pred(p), i, role);
            }
            return;
        }
        if matches!(usage, Usage::Query | Usage::Test | Usage::Trigger) {
            if let Some(&r) = self.rule_ids.get(&(name.to_string(), arity)) {
                for (i, a) in l.args.iter().enumerate() {
                    self.loose_arg(cl, a, Sig::Rule(r), i, Role::Use, scope);
                }
                return;
            }
            let others: Vec<&RuleInfo> = self.rules.iter().filter(|r| r.name == name).collect();
            if let Some(r) = others.first() {
                let arities: Vec<String> = others.iter().map(|r| r.arity.to_string()).collect();
                let d = Diagnostic::error(
                    "input",
                    format!(
                        "the rule `{name}` takes {}, but {} given",
                        plural_or(&arities, "argument"),
                        given(arity)
                    ),
                )
                .with_label(l.span, "wrong number of arguments")
                .with_secondary(r.span, "the rule's head");
                self.diags.push(d);
                return;
            }
        }
        if usage == Usage::Test && self.test_goals.contains(name) {
            for a in &l.args {
                self.term(cl, a, scope);
            }
            return;
        }
        // Unknown. A test goal on it just fails in Jason: a lint finding.
        if usage == Usage::Test && scope == Scope::Agent {
            self.undefined_tests.push(UndefinedAction {
                name: name.to_string(),
                arity,
                span: l.span,
            });
            for a in &l.args {
                self.term(cl, a, scope);
            }
            return;
        }
        let mut names: Vec<&str> = self.preds.iter().map(|p| p.name.as_str()).collect();
        if usage != Usage::Fact {
            names.extend(self.rules.iter().map(|r| r.name.as_str()));
        }
        let hint = suggest(name, names.iter().copied())
            .map(|s| format!("; did you mean `{s}`?"))
            .unwrap_or_default();
        let what = match usage {
            Usage::Fact => "a fact must be an atom of a PDDL predicate or of a mental note",
            Usage::Del => "only PDDL predicates and mental notes (beliefs the plans add) can be deleted",
            _ => "known predicates are the PDDL domain's, the mental notes the plans add (`+b`) or the initial beliefs, and the heads of rules",
        };
        let d = Diagnostic::error("input", format!("unknown predicate `{name}`{hint}"))
            .with_label(l.span, "unknown predicate")
            .with_help(what);
        self.diags.push(d);
    }

    /// Records a variable or object argument as a typed occurrence (`_` is typed by
    /// nothing); returns false for any other argument.
    fn typed_arg(cl: &mut Clause, a: &Expr, sig: Sig, index: usize, role: Role) -> bool {
        let arg = match &a.kind {
            ExprKind::Var(v) if !v.negated && v.annots.is_none() => {
                if v.name == "_" {
                    return true;
                }
                Arg::Var(v.name.clone())
            }
            ExprKind::Literal(l) if is_atom(l) => Arg::Const(l.functor.clone()),
            _ => return false,
        };
        cl.occs.push(Occ {
            arg,
            span: a.span,
            sig,
            index,
            role,
        });
        true
    }

    /// An argument of a PDDL predicate, PDDL action or mental note: a variable or an object
    /// (an integer, with `[bounds] numbers`; arithmetic then too, untyped: it is checked
    /// against the numbers when it runs).
    fn strict_arg(&mut self, cl: &mut Clause, a: &Expr, sig: Sig, index: usize, role: Role) {
        if self.numbers {
            let int = match &a.kind {
                ExprKind::Int(i) => Some(i.to_string()),
                ExprKind::Unary(crate::syntax::ast::UnaryOp::Neg, x) => match &x.kind {
                    ExprKind::Int(i) => Some(format!("-{i}")),
                    _ => None,
                },
                _ => None,
            };
            if let Some(name) = int {
                cl.occs.push(Occ {
                    arg: Arg::Const(name),
                    span: a.span,
                    sig,
                    index,
                    role,
                });
                return;
            }
            if matches!(a.kind, ExprKind::Arith(..) | ExprKind::Unary(..)) {
                self.term(cl, a, Scope::Agent);
                return;
            }
        }
        if !Self::typed_arg(cl, a, sig, index, role) {
            let what = match &a.kind {
                ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Unary(..) => "a number",
                ExprKind::Str(_) => "a string",
                ExprKind::List(_) => "a list",
                ExprKind::Arith(..) => "an arithmetic expression",
                _ => "a structured term",
            };
            let d = Diagnostic::error(
                "input",
                format!(
                    "{what} cannot be an argument of `{}`: the model's state is a set of ground atoms over objects, so arguments must be objects or variables",
                    self.sig_name(sig)
                ),
            )
            .with_label(a.span, format!("{what}, not an object"))
            .with_help(if what == "a number" || what == "an arithmetic expression" {
                "declare the integers mental notes may hold, such as `[bounds] numbers = [0, 10]`"
            } else {
                "strings, lists and structured terms are not supported as arguments of predicates, actions and mental notes"
            });
            self.diags.push(d);
        }
    }

    /// An argument of a goal or a rule: a variable or an object is typed; anything else is
    /// allowed and not typed.
    fn loose_arg(
        &mut self,
        cl: &mut Clause,
        a: &Expr,
        sig: Sig,
        index: usize,
        role: Role,
        scope: Scope,
    ) {
        if !Self::typed_arg(cl, a, sig, index, role) {
            self.term(cl, a, scope);
        }
    }

    /// A logical formula.
    fn formula(&mut self, cl: &mut Clause, e: &Expr, scope: Scope, usage: Usage) {
        match &e.kind {
            ExprKind::Literal(l) if l.is_internal_action() => self.internal(cl, l, scope),
            ExprKind::Literal(l)
                if l.args.is_empty()
                    && !l.negated
                    && matches!(l.functor.as_str(), "true" | "false") => {}
            ExprKind::Literal(l) => self.belief_literal(cl, l, usage, scope),
            ExprKind::Var(_) => {
                self.unsupported(e.span, "a formula held in a variable", "variable")
            }
            ExprKind::Not(x) => self.formula(cl, x, scope, usage),
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                self.formula(cl, a, scope, usage);
                self.formula(cl, b, scope, usage);
            }
            ExprKind::Rel(op, a, b) => {
                self.term(cl, a, scope);
                self.term(cl, b, scope);
                if matches!(scope, Scope::Manifest { .. }) {
                    if *op == RelOp::Univ {
                        self.unsupported(e.span, "`=..` in a manifest formula", "here");
                    }
                    for x in [a, b] {
                        if let ExprKind::Literal(l) = &x.kind {
                            if is_atom(l) {
                                self.object_exists(&l.functor, x.span);
                            }
                        }
                    }
                }
            }
            ExprKind::PlanTerm(_) => {
                self.unsupported(e.span, "a plan term in a formula", "plan term")
            }
            _ => self.term(cl, e, scope),
        }
    }

    /// Reports an atom that is not an object (in a manifest comparison).
    fn object_exists(&mut self, name: &str, span: Span) {
        if self.universe.object(name).is_none() {
            self.diags.push(self.not_an_object(name, span));
        }
    }

    fn not_an_object(&self, name: &str, span: Span) -> Diagnostic {
        if name.parse::<i64>().is_ok() {
            let (msg, help) = match &self.manifest_numbers {
                Some((lo, hi)) => (
                    format!("`{name}` is not among the model's numbers, {lo} to {hi}"),
                    "widen `[bounds] numbers`",
                ),
                None => (
                    format!("`{name}` is a number, and the model has none"),
                    "declare the integers mental notes may hold, such as `[bounds] numbers = [0, 10]`",
                ),
            };
            return Diagnostic::error("input", msg)
                .with_label(span, "number outside the model")
                .with_help(help);
        }
        let hint = suggest(
            name,
            self.universe
                .objects()
                .map(|o| self.universe.object_name(o)),
        )
        .map(|s| format!("; did you mean `{s}`?"))
        .unwrap_or_default();
        Diagnostic::error("input", format!("`{name}` is not an object{hint}"))
            .with_label(span, "unknown object")
            .with_help("objects are the PDDL domain's constants and the manifest's `[objects]`")
    }

    /// A term that is in no typed position: checks the functions and formulas inside it.
    fn term(&mut self, cl: &mut Clause, e: &Expr, scope: Scope) {
        match &e.kind {
            ExprKind::Literal(l) if l.is_internal_action() => self.function(cl, l, scope),
            ExprKind::Literal(l) => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
            ExprKind::List(le) => {
                for a in &le.elems {
                    self.term(cl, a, scope);
                }
                if let Some(t) = &le.tail {
                    self.term(cl, t, scope);
                }
            }
            ExprKind::Unary(_, a) | ExprKind::Not(a) => self.term(cl, a, scope),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                self.term(cl, a, scope);
                self.term(cl, b, scope);
            }
            ExprKind::Var(_)
            | ExprKind::Int(_)
            | ExprKind::Float(_)
            | ExprKind::Str(_)
            | ExprKind::PlanTerm(_) => {}
        }
    }

    /// A dotted functor in a term: an arithmetic function.
    fn function(&mut self, cl: &mut Clause, l: &Literal, scope: Scope) {
        let name = l.functor.as_str();
        match (name, l.args.len()) {
            (".count", 1) => self.count_query(cl, &l.args[0], scope),
            (".length", 1) => self.term(cl, &l.args[0], scope),
            _ if arithmetic_function(name) => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
            _ => {
                let d = Diagnostic::error(
                    "input",
                    format!("`{name}` is not an arithmetic function modelled by bdi-check"),
                )
                .with_label(l.span, "in an expression")
                .with_help(
                    "functions: `.count(Query)`, `.length(List)` and `math.abs`, `math.max`, ... (Jason's `math` library, except `math.random`)",
                );
                self.diags.push(d);
            }
        }
    }

    fn count_query(&mut self, cl: &mut Clause, q: &Expr, scope: Scope) {
        if matches!(scope, Scope::Manifest { .. }) && !matches!(q.kind, ExprKind::Literal(_)) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    "the query of `.count` must be a literal such as `cupAt(C, _)`",
                )
                .with_label(q.span, "not a literal"),
            );
            return;
        }
        self.formula(cl, q, scope, Usage::Query);
    }

    /// An internal action as a body step or a formula.
    fn internal(&mut self, cl: &mut Clause, l: &Literal, scope: Scope) {
        let name = l.functor.as_str();
        let n = l.args.len();
        if name.starts_with("math.") && arithmetic_function(name) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!("`{name}` is an arithmetic function, not an internal action"),
                )
                .with_label(l.span, "function")
                .with_help(format!(
                    "use it inside an expression, such as `X = {name}(Y)`"
                )),
            );
            return;
        }
        if !modelled_action(name) {
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!("internal action `{name}` is not modelled by bdi-check"),
                )
                .with_label(l.span, "unmodelled internal action")
                .with_help(format!(
                    "bdi-check models {}",
                    INTERNAL_ACTIONS
                        .iter()
                        .copied()
                        .chain(super::internal::PURE.iter().map(|(n, _)| *n))
                        .map(|a| format!("`{a}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            );
            return;
        }
        if let Scope::Manifest { properties } = scope {
            let ok = name == ".count" || (properties && matches!(name, ".intend" | ".desire"));
            if !ok {
                let only = if matches!(name, ".intend" | ".desire") {
                    format!("`{name}` can only be used in a `[[property]]`")
                } else {
                    format!(
                        "`{name}` cannot be used in a manifest formula (only `.count`, and `.intend`/`.desire` in properties)"
                    )
                };
                self.diags
                    .push(Diagnostic::error("input", only).with_label(l.span, "here"));
                return;
            }
        }
        let pure = super::internal::PURE.iter().find(|(n, _)| *n == name);
        let arities: &[usize] = match name {
            ".print" | ".println" => &[],
            ".count" => &[2],
            ".findall" => &[3],
            ".drop_intention" => &[0, 1],
            ".fail" => &[0],
            _ if pure.is_some() => pure.map_or(&[], |(_, a)| a),
            _ => &[1],
        };
        if !arities.is_empty() && !arities.contains(&n) {
            let want: Vec<String> = arities.iter().map(|a| a.to_string()).collect();
            self.diags.push(
                Diagnostic::error(
                    "input",
                    format!(
                        "`{name}` takes {}, but {} given",
                        plural_or(&want, "argument"),
                        given(n)
                    ),
                )
                .with_label(l.span, "wrong number of arguments"),
            );
            return;
        }
        match name {
            ".count" => {
                self.count_query(cl, &l.args[0], scope);
                let out = &l.args[1];
                match &out.kind {
                    ExprKind::Var(v) => {
                        cl.counted.insert(v.name.clone());
                    }
                    ExprKind::Int(_) => {}
                    _ if matches!(scope, Scope::Manifest { .. }) => self.diags.push(
                        Diagnostic::error(
                            "input",
                            "the count of `.count(Query, N)` must be an integer or a variable",
                        )
                        .with_label(out.span, "expected an integer or a variable"),
                    ),
                    _ => self.term(cl, out, scope),
                }
            }
            ".findall" => {
                self.term(cl, &l.args[0], scope);
                self.formula(cl, &l.args[1], scope, Usage::Query);
                self.term(cl, &l.args[2], scope);
            }
            ".abolish" => match &l.args[0].kind {
                // `.abolish(b)` deletes every belief that unifies with `b`.
                ExprKind::Literal(b) if !b.is_internal_action() => {
                    self.belief_literal(cl, b, Usage::Del, scope)
                }
                _ => self.diags.push(
                    Diagnostic::error("input", "`.abolish` expects a belief such as `seen(_)`")
                        .with_label(l.args[0].span, "not a belief literal"),
                ),
            },
            _ if GOAL_ACTIONS.contains(&name) => {
                if let Some(g) = l.args.first() {
                    match &g.kind {
                        ExprKind::Literal(gl) if !gl.is_internal_action() => {
                            self.known_goal(cl, gl, g.span, scope)
                        }
                        ExprKind::Var(_) if scope == Scope::Agent => {}
                        _ => self.diags.push(
                            Diagnostic::error(
                                "input",
                                format!("`{name}` expects a goal such as `storeCup(C)`"),
                            )
                            .with_label(g.span, "not a goal"),
                        ),
                    }
                }
            }
            _ => {
                for a in &l.args {
                    self.term(cl, a, scope);
                }
            }
        }
    }

    // ----- the manifest -----------------------------------------------------------------------

    fn collect_manifest(&mut self, m: &Manifest) {
        for f in &m.initial.facts {
            let mut cl = Clause::default();
            if let ExprKind::Literal(l) = &f.expr.kind {
                self.belief_literal(
                    &mut cl,
                    l,
                    Usage::Fact,
                    Scope::Manifest { properties: false },
                );
            }
            self.clauses.push(cl);
        }
        for v in &m.initial.vary {
            if !self.pred_ids.contains_key(&v.value) {
                let hint = suggest(&v.value, self.preds.iter().map(|p| p.name.as_str()))
                    .map(|s| format!("; did you mean `{s}`?"))
                    .unwrap_or_default();
                self.diags.push(
                    Diagnostic::error("input", format!("unknown predicate `{}`{hint}", v.value))
                        .with_label(v.span, "not a predicate")
                        .with_help("`vary` names PDDL predicates or mental notes"),
                );
            }
        }
        let no_props = Scope::Manifest { properties: false };
        for f in &m.initial.constraints {
            self.manifest_formula(f, no_props);
        }
        for inv in &m.invariants {
            self.manifest_formula(&inv.formula, no_props);
        }
        for p in &m.properties {
            self.manifest_formula(&p.formula, Scope::Manifest { properties: true });
        }
        for f in &m.requests.goals {
            let mut cl = Clause::default();
            if let ExprKind::Literal(l) = &f.expr.kind {
                self.goal_literal(&mut cl, l, Role::Use, no_props);
            }
            self.clauses.push(cl);
        }
        if let Some(x) = &m.explanation {
            if let Some(e) = &x.emitted_by {
                if !self.called.contains(&e.value) {
                    let mut names: Vec<&str> = self.called.iter().map(String::as_str).collect();
                    names.sort_unstable();
                    let hint = suggest(&e.value, names)
                        .map(|s| format!("; did you mean `{s}`?"))
                        .unwrap_or_default();
                    self.diags.push(
                        Diagnostic::error(
                            "input",
                            format!("no plan calls the action `{}`{hint}", e.value),
                        )
                        .with_label(e.span, "`emitted_by` names an action the plans call"),
                    );
                }
            }
            for p in &x.phrases {
                let mut cl = Clause::default();
                self.phrase(&mut cl, &p.pattern);
                self.clauses.push(cl);
            }
            for u in &x.users {
                for pair in &u.expected {
                    let mut cl = Clause {
                        free_check: true,
                        ..Clause::default()
                    };
                    self.observed(&mut cl, &pair.before);
                    self.observed(&mut cl, &pair.after);
                    self.clauses.push(cl);
                }
            }
        }
    }

    fn manifest_formula(&mut self, f: &Formula, scope: Scope) {
        let mut cl = Clause {
            free_check: true,
            ..Clause::default()
        };
        named_vars(&f.expr, &mut cl.vars);
        self.formula(&mut cl, &f.expr, scope, Usage::Query);
        self.clauses.push(cl);
    }

    /// One side of an expected pair: `!g(args)` or a PDDL action.
    fn observed(&mut self, cl: &mut Clause, s: &StepFormula) {
        let scope = Scope::Manifest { properties: false };
        match &s.step.kind {
            StepKind::Achieve(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    named_vars(e, &mut cl.vars);
                    self.known_goal(cl, l, e.span, scope);
                }
            }
            StepKind::Action(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    named_vars(e, &mut cl.vars);
                    if let Some(&a) = self.action_ids.get(&l.functor) {
                        self.action_args(cl, l, a);
                    } else {
                        self.unknown_action(
                            l,
                            "an expected pair names PDDL actions and requests `!g`",
                        );
                    }
                }
            }
            _ => {}
        }
    }

    fn unknown_action(&mut self, l: &Literal, help: &str) {
        let hint = suggest(&l.functor, self.actions.iter().map(|a| a.name.as_str()))
            .map(|s| format!("; did you mean `{s}`?"))
            .unwrap_or_default();
        self.diags.push(
            Diagnostic::error(
                "input",
                format!("`{}` is not an action of the PDDL domain{hint}", l.functor),
            )
            .with_label(l.span, "unknown action")
            .with_help(help.to_string()),
        );
    }

    /// A phrase pattern: a predicate, an action or a request.
    fn phrase(&mut self, cl: &mut Clause, s: &StepFormula) {
        let scope = Scope::Manifest { properties: false };
        match &s.step.kind {
            StepKind::Achieve(e) => {
                if let ExprKind::Literal(l) = &e.kind {
                    self.known_goal(cl, l, e.span, scope);
                }
            }
            StepKind::Action(e) => {
                let ExprKind::Literal(l) = &e.kind else {
                    return;
                };
                if self.pred_ids.contains_key(&l.functor) {
                    self.belief_literal(cl, l, Usage::Pattern, scope);
                } else if let Some(&a) = self.action_ids.get(&l.functor) {
                    self.action_args(cl, l, a);
                } else {
                    let names = self
                        .preds
                        .iter()
                        .map(|p| p.name.as_str())
                        .chain(self.actions.iter().map(|a| a.name.as_str()));
                    let hint = suggest(&l.functor, names)
                        .map(|s| format!("; did you mean `{s}`?"))
                        .unwrap_or_default();
                    self.diags.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "`{}` is neither a predicate nor a PDDL action{hint}",
                                l.functor
                            ),
                        )
                        .with_label(l.span, "unknown name")
                        .with_help("a phrase pattern is an atom `p(X)`, an action `a(X)` or a request `!g(X)`"),
                    );
                }
            }
            _ => {}
        }
    }

    // ----- pass 3: inference ------------------------------------------------------------------

    fn initial_types(&self) -> Types {
        Types {
            preds: (0..self.preds.len())
                .map(|p| match self.pddl_params.get(p) {
                    Some(ps) if self.preds[p].env => ps.iter().map(|&t| Some(t)).collect(),
                    _ => vec![None; self.preds[p].arity],
                })
                .collect(),
            goals: self.goals.iter().map(|g| vec![None; g.arity]).collect(),
            rules: self.rules.iter().map(|r| vec![None; r.arity]).collect(),
        }
    }

    /// Parameter types of goals, rules and mental notes, to a fixed point.
    fn infer(&self) -> Types {
        let mut types = self.initial_types();
        let rounds = 8 + 2 * (self.goals.len() + self.rules.len() + self.preds.len());
        for _ in 0..rounds {
            let mut next = self.initial_types();
            for cl in &self.clauses {
                let vars = self.resolve(cl, &types, None);
                for o in cl.occs.iter().filter(|o| o.role == Role::Define) {
                    let t = match &o.arg {
                        Arg::Var(v) => vars.get(v).map(|i| i.ty),
                        Arg::Const(c) => self
                            .universe
                            .object(c)
                            .map(|o| self.universe.object_type(o)),
                    };
                    let slot = match o.sig {
                        Sig::Pred(p) if !self.preds[p].env => Some((
                            &mut next.preds[p][o.index],
                            Some(t.unwrap_or(TypeId::OBJECT)),
                        )),
                        Sig::Goal(g) => Some((&mut next.goals[g][o.index], t)),
                        Sig::Rule(r) => Some((&mut next.rules[r][o.index], t)),
                        _ => None,
                    };
                    if let Some((slot, Some(t))) = slot {
                        *slot = Some(match *slot {
                            None => t,
                            Some(s) => lca(self.universe, s, t),
                        });
                    }
                }
            }
            if next == types {
                break;
            }
            types = next;
        }
        types
    }

    /// The parameter type of a position.
    fn param(&self, types: &Types, sig: Sig, i: usize) -> Option<TypeId> {
        match sig {
            Sig::Pred(p) => types.preds[p].get(i).copied().flatten(),
            Sig::Action(a) => self.actions[a].params.get(i).copied(),
            Sig::Goal(g) => types.goals[g].get(i).copied().flatten(),
            Sig::Rule(r) => types.rules[r].get(i).copied().flatten(),
        }
    }

    /// The variables' types in one clause. With `diags`, the final pass: every position
    /// constrains, and conflicts, bad constants and free variables are reported.
    fn resolve(
        &self,
        cl: &Clause,
        types: &Types,
        mut diags: Option<&mut Vec<Diagnostic>>,
    ) -> HashMap<String, VarInfo> {
        let last = diags.is_some();
        let mut vars: HashMap<String, VarInfo> = HashMap::new();
        // Uses first: a defining position (typed by what the uses infer) only refines, and a
        // conflict is best reported between the positions that caused it.
        let uses = cl.occs.iter().filter(|o| o.role == Role::Use);
        let defines = cl.occs.iter().filter(|o| o.role == Role::Define && last);
        for o in uses.chain(defines) {
            let Some(want) = self.param(types, o.sig, o.index) else {
                continue;
            };
            match &o.arg {
                Arg::Var(v) => match vars.get_mut(v) {
                    None => {
                        vars.insert(
                            v.clone(),
                            VarInfo {
                                ty: want,
                                span: o.span,
                                sig: o.sig,
                                index: o.index,
                            },
                        );
                    }
                    Some(info) => match self.universe.meet(info.ty, want) {
                        Some(m) => {
                            if m != info.ty {
                                *info = VarInfo {
                                    ty: m,
                                    span: o.span,
                                    sig: o.sig,
                                    index: o.index,
                                };
                            }
                        }
                        None => {
                            if let Some(d) = diags.as_deref_mut() {
                                d.push(self.conflict(v, info, o, want));
                            }
                        }
                    },
                },
                Arg::Const(c) => {
                    if let Some(d) = diags.as_deref_mut() {
                        match self.universe.object(c) {
                            None => d.push(self.not_an_object(c, o.span)),
                            Some(obj) => {
                                let has = self.universe.object_type(obj);
                                if !self.universe.is_subtype(has, want) {
                                    let tn = |t| self.universe.type_name(t);
                                    d.push(
                                        Diagnostic::error(
                                            "input",
                                            format!(
                                                "`{c}` is {}, but {}",
                                                a_type(tn(has)),
                                                self.expects(o.sig, o.index, want)
                                            ),
                                        )
                                        .with_label(o.span, format!("{} here", a_type(tn(has))))
                                        .with_secondary(
                                            self.universe.object_origin(obj).span(),
                                            format!("`{c}` is declared here"),
                                        ),
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
        if let Some(d) = diags {
            if cl.free_check {
                let mut seen = HashSet::new();
                for (v, span) in &cl.vars {
                    if vars.contains_key(v) || cl.counted.contains(v) || !seen.insert(v) {
                        continue;
                    }
                    d.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "variable `{v}` is in no typed position, so it would range over nothing in particular"
                            ),
                        )
                        .with_label(*span, "untyped variable")
                        .with_help(
                            "use it as an argument of a predicate, an action or a goal, whose signature gives its type",
                        ),
                    );
                }
            }
        }
        vars
    }

    fn conflict(&self, v: &str, first: &VarInfo, o: &Occ, want: TypeId) -> Diagnostic {
        let tn = |t| self.universe.type_name(t);
        Diagnostic::error(
            "input",
            format!(
                "variable `{v}` is {} at {} and {} at {}",
                a_type(tn(first.ty)),
                self.map.location(first.span),
                a_type(tn(want)),
                self.map.location(o.span),
            ),
        )
        .with_label(o.span, self.expects(o.sig, o.index, want))
        .with_secondary(first.span, self.expects(first.sig, first.index, first.ty))
        .with_help(format!(
            "no object is both {} and {}",
            a_type(tn(first.ty)),
            a_type(tn(want))
        ))
    }

    /// "`pickUp` expects a `cup`", "`cupAt` expects a `location` as argument 2".
    fn expects(&self, sig: Sig, i: usize, t: TypeId) -> String {
        let arity = match sig {
            Sig::Pred(p) => self.preds[p].arity,
            Sig::Action(a) => self.actions[a].params.len(),
            Sig::Goal(g) => self.goals[g].arity,
            Sig::Rule(r) => self.rules[r].arity,
        };
        let what = a_type(self.universe.type_name(t));
        if arity == 1 {
            format!("`{}` expects {what}", self.sig_name(sig))
        } else {
            format!(
                "`{}` expects {what} as argument {}",
                self.sig_name(sig),
                i + 1
            )
        }
    }

    fn sig_name(&self, sig: Sig) -> String {
        match sig {
            Sig::Pred(p) => self.preds[p].name.clone(),
            Sig::Action(a) => self.actions[a].name.clone(),
            Sig::Goal(g) => format!("!{}", self.goals[g].name),
            Sig::Rule(r) => self.rules[r].name.clone(),
        }
    }

    // ----- pass 4: the final check ------------------------------------------------------------

    fn final_pass(&mut self, types: &Types) {
        let mut finals = types.clone();
        for ps in finals
            .goals
            .iter_mut()
            .chain(finals.rules.iter_mut())
            .chain(finals.preds.iter_mut())
        {
            for p in ps.iter_mut() {
                p.get_or_insert(TypeId::OBJECT);
            }
        }
        let mut diags = Vec::new();
        for cl in &self.clauses {
            self.resolve(cl, &finals, Some(&mut diags));
        }
        self.diags.extend(diags);
    }
}

// ===== helpers ==================================================================================

/// Whether a literal is a plain atom that can name an object.
fn is_atom(l: &Literal) -> bool {
    l.args.is_empty()
        && l.annots.is_none()
        && !l.negated
        && !l.is_internal_action()
        && !matches!(l.functor.as_str(), "true" | "false")
}

/// Every named variable (not `_`, not `_X`) of an expression, with its span, in order.
fn named_vars(e: &Expr, out: &mut Vec<(String, Span)>) {
    let list = |l: &ListExpr, out: &mut Vec<(String, Span)>| {
        l.elems.iter().for_each(|a| named_vars(a, out));
        if let Some(t) = &l.tail {
            named_vars(t, out);
        }
    };
    match &e.kind {
        ExprKind::Literal(l) => l.args.iter().for_each(|a| named_vars(a, out)),
        ExprKind::Var(v) => {
            if !v.name.starts_with('_') {
                out.push((v.name.clone(), e.span));
            }
        }
        ExprKind::List(l) => list(l, out),
        ExprKind::Unary(_, a) | ExprKind::Not(a) => named_vars(a, out),
        ExprKind::Arith(_, a, b)
        | ExprKind::Rel(_, a, b)
        | ExprKind::And(a, b)
        | ExprKind::Or(a, b) => {
            named_vars(a, out);
            named_vars(b, out);
        }
        ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) | ExprKind::PlanTerm(_) => {}
    }
}

/// The least common ancestor of two types.
fn lca(u: &Universe, a: TypeId, b: TypeId) -> TypeId {
    if u.is_subtype(a, b) {
        return b;
    }
    if u.is_subtype(b, a) {
        return a;
    }
    // The common ancestors form a chain; the most specific is below all the others.
    let common: Vec<TypeId> = (0..u.type_count() as u16)
        .map(TypeId)
        .filter(|&t| u.is_subtype(a, t) && u.is_subtype(b, t))
        .collect();
    common
        .iter()
        .copied()
        .find(|&t| common.iter().all(|&s| u.is_subtype(t, s)))
        .unwrap_or(TypeId::OBJECT)
}

/// What the secondary label at a goal's span says.
fn goal_place(g: &GoalInfo) -> String {
    let what = if g.plan_span.is_some() {
        "its first plan"
    } else {
        "first used here"
    };
    format!("`{}/{}`: {what}", g.name, g.arity)
}

/// "a `cup`", "an `item`".
fn a_type(name: &str) -> String {
    let article = if name
        .chars()
        .next()
        .is_some_and(|c| "aeiouAEIOU".contains(c))
    {
        "an"
    } else {
        "a"
    };
    format!("{article} `{name}`")
}

/// "1 argument", "2 arguments".
fn count(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}

/// "1 is", "2 are".
fn given(n: usize) -> String {
    if n == 1 {
        "1 is".to_string()
    } else {
        format!("{n} are")
    }
}

/// "1 argument", "1 or 2 arguments".
fn plural_or(ns: &[String], what: &str) -> String {
    match ns {
        [one] if one == "1" => format!("1 {what}"),
        [one] => format!("{one} {what}s"),
        _ => format!(
            "{} or {} {what}s",
            ns[..ns.len() - 1].join(", "),
            ns[ns.len() - 1]
        ),
    }
}

/// The nearest of `candidates` to `name`, if one is near enough to be a likely typo.
fn suggest<'c>(name: &str, candidates: impl IntoIterator<Item = &'c str>) -> Option<&'c str> {
    let limit = (name.chars().count() / 3).max(1);
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c == name {
            continue;
        }
        let d = if c.eq_ignore_ascii_case(name) {
            1
        } else {
            edit_distance(name, c)
        };
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Edit distance with adjacent transpositions (optimal string alignment): `tabel` is one edit
/// from `table`.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, v) in d[0].iter_mut().enumerate() {
        *v = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_are_near_names_only() {
        assert_eq!(suggest("tabel", ["table", "cupboard"]), Some("table"));
        assert_eq!(suggest("usd", ["used", "dirty"]), Some("used"));
        assert_eq!(suggest("xyz", ["used", "dirty"]), None);
        assert_eq!(suggest("cupat", ["cupAt"]), Some("cupAt"));
    }

    #[test]
    fn articles_and_counts() {
        assert_eq!(a_type("item"), "an `item`");
        assert_eq!(a_type("cup"), "a `cup`");
        assert_eq!(count(1, "argument"), "1 argument");
        assert_eq!(
            plural_or(&["1".into(), "2".into()], "argument"),
            "1 or 2 arguments"
        );
    }
}
