//! The parsed and validated manifest and scenario: plain values, each with the span in the
//! TOML file that later diagnostics point at, and the defaults of the optional sections.

use super::{DEFAULT_MAX_DEPTH, DEFAULT_MAX_REQUESTS, DEFAULT_MAX_STATES};
use crate::syntax::ast::{Expr, Step};
use crate::syntax::source::{FileId, Span};
use std::path::PathBuf;

/// A value from the TOML file with where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Located<T> {
    /// The value.
    pub value: T,
    /// Where it is in the TOML file: the whole value, quotes included, unless a field says
    /// otherwise.
    pub span: Span,
}

/// A logical formula or literal written as a TOML string.
#[derive(Clone, Debug, PartialEq)]
pub struct Formula {
    /// The string's value, as the user wrote it (TOML escapes decoded).
    pub text: String,
    /// The TOML string value, quotes included.
    pub span: Span,
    /// The parsed expression; its spans point inside the TOML string.
    pub expr: Expr,
}

/// A body step (`navigateTo(table)`, `!storeCup(C)`) written as a TOML string.
#[derive(Clone, Debug, PartialEq)]
pub struct StepFormula {
    /// The string's value (TOML escapes decoded).
    pub text: String,
    /// The TOML string value, quotes included.
    pub span: Span,
    /// The parsed step; its spans point inside the TOML string.
    pub step: Step,
}

/// A file the manifest names.
#[derive(Clone, Debug, PartialEq)]
pub struct FileRef {
    /// The path as written in the manifest, with its span.
    pub written: Located<String>,
    /// The path resolved against the manifest's folder (absolute when the manifest's path is,
    /// or when the written path is).
    pub path: PathBuf,
}

/// `[agent]` (or `[[agent]]`): the files of the project.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentSection {
    /// `plans`: the Jason AgentSpeak plan library.
    pub plans: FileRef,
    /// `actions`: the PDDL domain of the environment actions.
    pub actions: FileRef,
    /// `source_path`: folders (relative to the manifest) where `include` also looks, as
    /// Jason's `aslSourcePath`. Default: none.
    pub source_path: Vec<PathBuf>,
    /// The agents of a multi-agent project, in order (a `.mas2j`'s or `[[agent]]`'s); empty
    /// when the project is the one agent of `plans`. Then `plans` is the first agent's.
    pub agents: Vec<AgentEntry>,
    /// `mas`: the Jason project file the agents are read from, when the manifest names one.
    pub mas: Option<FileRef>,
}

/// One agent of a multi-agent project.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentEntry {
    /// Its name (the instances' names are built from it), where it is written.
    pub name: Located<String>,
    /// Its plan library.
    pub plans: FileRef,
    /// How many instances run (`#N` in a `.mas2j`; `instances`, default 1).
    pub instances: u32,
}

/// One entry of `[objects]`: a PDDL type and its objects.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectType {
    /// The type's name (the key).
    pub name: Located<String>,
    /// Its objects, Jason atoms, in the order written.
    pub objects: Vec<Located<String>>,
}

/// `[initial]`: how the initial states are built. The whole section is optional.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct InitialSection {
    /// `facts`: ground atoms true in every initial state. Default: none.
    pub facts: Vec<Formula>,
    /// `vary`: predicate names whose ground atoms may start either way. Default: none. Each
    /// span covers the name inside the string.
    pub vary: Vec<Located<String>>,
    /// `constraints`: formulas every initial state satisfies. Default: none.
    pub constraints: Vec<Formula>,
}

/// When an external request may arrive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Arrival {
    /// `"idle"` (default): only when the agent has no intention.
    #[default]
    Idle,
    /// `"any"`: before any reasoning cycle.
    Any,
}

/// `[requests]`: what the user may ask. The whole section is optional.
#[derive(Clone, Debug, PartialEq)]
pub struct RequestsSection {
    /// `goals`: achievement-goal atoms (without `!`), possibly with variables. Default: none.
    pub goals: Vec<Formula>,
    /// `max`: most requests in one run. Default [`DEFAULT_MAX_REQUESTS`].
    pub max: u32,
    /// `arrival`. Default [`Arrival::Idle`].
    pub arrival: Arrival,
    /// `from`: who asks. A request is then the `achieve` message of that agent, and its
    /// goal carries `source(from)`; without it, `source(self)`, as an initial goal.
    pub from: Option<Located<String>>,
    /// `to`: in a project of several agents, the agent the requests go to (by default,
    /// the first).
    pub to: Option<Located<String>>,
}

impl Default for RequestsSection {
    fn default() -> Self {
        RequestsSection {
            goals: Vec::new(),
            max: DEFAULT_MAX_REQUESTS,
            arrival: Arrival::Idle,
            from: None,
            to: None,
        }
    }
}

/// One entry of `[invariants]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Invariant {
    /// Its name (the key).
    pub name: Located<String>,
    /// The formula that must hold in every reachable state.
    pub formula: Formula,
}

/// Which temporal kind a property is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PropertyKind {
    /// `always = "f"`: `f` holds in every reachable state.
    Always,
    /// `eventually = "f"`: every run reaches a state where `f` holds.
    Eventually,
    /// `reachable = "f"`: some run reaches a state where `f` holds.
    Reachable,
    /// `ltl = "f"`: every run satisfies the LTL formula `f`.
    Ltl,
}

impl PropertyKind {
    /// The key that introduces it.
    pub fn key(self) -> &'static str {
        match self {
            PropertyKind::Always => "always",
            PropertyKind::Eventually => "eventually",
            PropertyKind::Reachable => "reachable",
            PropertyKind::Ltl => "ltl",
        }
    }
}

/// One `[[property]]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Property {
    /// `name` (required, unique among properties).
    pub name: Located<String>,
    /// Which of `always`, `eventually`, `reachable`, `ltl` was given (exactly one is
    /// required).
    pub kind: PropertyKind,
    /// Its formula. For `ltl`, the text and span of the string, and the expression `true`:
    /// the formula itself is [`Property::ltl`].
    pub formula: Formula,
    /// The LTL formula of an `ltl` property.
    pub ltl: Option<super::ltl::LtlExpr>,
    /// The table: its `[[property]]` header (or inline table).
    pub span: Span,
}

/// How the content algorithm decides that an action modifies the context.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Modifies {
    /// `"syntactic"` (default): the paper's `Eff± ∩ Γ` on atoms.
    #[default]
    Syntactic,
    /// `"semantic"`: the truth of a literal of `Γ` changes.
    Semantic,
}

/// One entry of `[explanation.phrases]`: how a literal or an action reads in a sentence.
#[derive(Clone, Debug, PartialEq)]
pub struct Phrase {
    /// The pattern (the key): an atom or action `p(X)`, or a request `!g(X)`.
    pub pattern: StepFormula,
    /// The template; every `{X}` in it names a variable of the pattern, `{{` and `}}` stand for
    /// literal braces.
    pub template: Located<String>,
}

/// One `(before, after)` pattern of a user's expected-successor relation.
#[derive(Clone, Debug, PartialEq)]
pub struct ExpectedPair {
    /// The first element: an action `a(x)` or a request `!g`.
    pub before: StepFormula,
    /// The second element, of the same shape.
    pub after: StepFormula,
    /// The two-element list.
    pub span: Span,
}

/// One `[explanation.users.NAME]`.
#[derive(Clone, Debug, PartialEq)]
pub struct User {
    /// The user's name (the key).
    pub name: Located<String>,
    /// `expected`: the initial expected-successor relation `N`. Default: empty.
    pub expected: Vec<ExpectedPair>,
}

/// `[explanation]`. Optional as a whole: without it no explanation property is checked.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ExplanationSection {
    /// Where the manifest opens the section (its `explanation` key).
    pub span: Span,
    /// `robot`: the agent whose actions the users watch. Required in a project of several
    /// agents; in a project of one, it may be left out, or must name that agent.
    pub robot: Option<Located<String>>,
    /// `modifies`. Default [`Modifies::Syntactic`].
    pub modifies: Modifies,
    /// `emitted_by`: the action with which the agent explains itself. Default: none (no
    /// conformance checks).
    pub emitted_by: Option<Located<String>>,
    /// `[explanation.phrases]`, in source order. Default: none.
    pub phrases: Vec<Phrase>,
    /// `[explanation.users.*]`, in source order. Default: none.
    pub users: Vec<User>,
}

/// Plan selection during exploration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum PlanSelection {
    /// `"first"` (default, Jason's): the first applicable plan in source order.
    #[default]
    First,
    /// `"any"`: every applicable plan is explored.
    Any,
}

/// `[bounds]`. The whole section is optional.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// `max_states` (at least 1). Default [`DEFAULT_MAX_STATES`].
    pub max_states: u64,
    /// `max_depth` (at least 1). Default [`DEFAULT_MAX_DEPTH`].
    pub max_depth: u64,
    /// `symmetry`: types of `[objects]` whose objects are interchangeable. Default: none,
    /// because symmetry reduction is only sound when the user vouches for it.
    pub symmetry: Vec<Located<String>>,
    /// `plan_selection`. Default [`PlanSelection::First`].
    pub plan_selection: PlanSelection,
    /// `numbers = [lo, hi]`: the integers that may be arguments of mental notes (counters
    /// and the like), as objects of the type `number`. Default: none.
    pub numbers: Option<Located<(i64, i64)>>,
    /// `random = [0.0, 0.5, ...]`: the values `.random(X)` may give (Jason's are any double
    /// in `[0, 1)`; the model branches over these). Default: none (`.random(X)` refused).
    pub random: Option<Located<Vec<f64>>>,
    /// `fairness = ["intentions", "agents"]`: which runs that go on for ever count. Weak
    /// fairness of intentions is Jason's round-robin selection, which the cycle runs, so it
    /// cannot be left out; weak fairness of agents (a run where an agent that could move in
    /// every state of a loop never moves there does not count) is on unless left out.
    /// Default: both.
    pub fair_agents: bool,
}

/// Most values `[bounds] random` may list.
pub const MAX_RANDOM: usize = 64;

/// Most integers `[bounds] numbers` may span.
pub const MAX_NUMBERS: i64 = 1024;

impl Default for Bounds {
    fn default() -> Self {
        Bounds {
            max_states: DEFAULT_MAX_STATES,
            max_depth: DEFAULT_MAX_DEPTH,
            symmetry: Vec::new(),
            plan_selection: PlanSelection::First,
            numbers: None,
            random: None,
            fair_agents: true,
        }
    }
}

/// A parsed and validated `bdi-check.toml`.
#[derive(Clone, Debug, PartialEq)]
pub struct Manifest {
    /// The manifest's file in the [`SourceMap`]; every span below is in it.
    ///
    /// [`SourceMap`]: crate::syntax::source::SourceMap
    pub file: FileId,
    /// The manifest's path.
    pub path: PathBuf,
    /// The project folder (the manifest's parent; empty for a bare file name).
    pub dir: PathBuf,
    /// `[agent]` (required).
    pub agent: AgentSection,
    /// `[objects]`, in source order. Default: none.
    pub objects: Vec<ObjectType>,
    /// `[initial]`.
    pub initial: InitialSection,
    /// `[requests]`.
    pub requests: RequestsSection,
    /// `[invariants]`, in source order. Default: none.
    pub invariants: Vec<Invariant>,
    /// Every `[[property]]`, in source order. Default: none.
    pub properties: Vec<Property>,
    /// `[explanation]`, when present.
    pub explanation: Option<ExplanationSection>,
    /// `[bounds]`.
    pub bounds: Bounds,
    /// Every `[[allow]]`, in source order. Default: none.
    pub allows: Vec<Allow>,
}

/// One `[[allow]]`: a failing finding the project accepts on purpose, for a reviewer to
/// see.
#[derive(Clone, Debug, PartialEq)]
pub struct Allow {
    /// `check` (required): the finding's check name.
    pub check: Located<String>,
    /// `at`: the file (relative to the project folder) and, after a colon, the line of the
    /// finding's location; without it, every finding of the check.
    pub at: Option<Located<(String, Option<usize>)>>,
    /// `why` (required): the reason, reported with each finding it suppresses.
    pub why: Located<String>,
    /// The table.
    pub span: Span,
}

/// A parsed scenario file: one run (SPEC §2).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// The scenario's file in the [`SourceMap`].
    ///
    /// [`SourceMap`]: crate::syntax::source::SourceMap
    pub file: FileId,
    /// Where it was read from.
    pub path: PathBuf,
    /// `initial` (required): the ground atoms true at the start; all others are false.
    pub initial: Vec<Formula>,
    /// `requests`: ground goal atoms, in order of arrival. Default: none.
    pub requests: Vec<Formula>,
}
