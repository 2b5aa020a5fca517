//! The project manifest `bdi-check.toml` (SPEC §1) and scenario files (SPEC §2).
//!
//! Both are read with `toml`'s spanned document tree ([`toml::de::DeTable`]) rather than with
//! serde derive, because strict validation needs what serde hides: every key and value with its
//! byte range, and every error collected instead of stopping at the first. Each diagnostic points
//! into the TOML text, so it renders as `bdi-check.toml:LINE:COLUMN` with a caret.
//!
//! Formulas written as TOML strings are parsed with the AgentSpeak parser, and their AST spans
//! point *into the TOML file* (one [`FileId`] for the manifest and everything in it), so a
//! syntax error in `always = "not cupAt(C,, floor)"` shows the manifest line with a caret under
//! the second comma. See `StrMap` (private) for how string contents are mapped back to the file.
//!
//! # Defaults
//!
//! Only `[agent]` with `plans` and `actions` is required, plus `name` and one kind in each
//! `[[property]]`. Everything else has a default, listed on each field: no objects, no facts,
//! no varying predicates, no constraints, no requests, [`DEFAULT_MAX_REQUESTS`] request per run
//! arriving when the agent is idle, no invariants, no properties, no explanation checks,
//! [`DEFAULT_MAX_STATES`] states, [`DEFAULT_MAX_DEPTH`] depth, no symmetry, first-plan
//! selection.

use super::ast::*;
use super::diagnostic::Diagnostic;
use super::parser::{parse_expr, parse_step};
use super::source::{FileId, SourceMap, Span};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::{DeArray, DeString, DeTable, DeValue};
use toml::Spanned;

/// The manifest's file name inside a project folder.
pub const MANIFEST_NAME: &str = "bdi-check.toml";
/// Default of `[requests] max`: one request per run. The number of ground goal instances is not
/// known before the PDDL objects are resolved, and one request already exercises every plan.
pub const DEFAULT_MAX_REQUESTS: u32 = 1;
/// Default of `[bounds] max_states`.
pub const DEFAULT_MAX_STATES: u64 = 5_000_000;
/// Default of `[bounds] max_depth`.
pub const DEFAULT_MAX_DEPTH: u64 = 2_000;

// ----- the parsed manifest ---------------------------------------------------------------

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

/// `[agent]`: the files of the project. Both keys are required.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentSection {
    /// `plans`: the Jason AgentSpeak plan library.
    pub plans: FileRef,
    /// `actions`: the PDDL domain of the environment actions.
    pub actions: FileRef,
    /// `source_path`: folders (relative to the manifest) where `include` also looks, as
    /// Jason's `aslSourcePath`. Default: none.
    pub source_path: Vec<PathBuf>,
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
}

impl Default for RequestsSection {
    fn default() -> Self {
        RequestsSection {
            goals: Vec::new(),
            max: DEFAULT_MAX_REQUESTS,
            arrival: Arrival::Idle,
            from: None,
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
}

impl PropertyKind {
    /// The key that introduces it.
    pub fn key(self) -> &'static str {
        match self {
            PropertyKind::Always => "always",
            PropertyKind::Eventually => "eventually",
            PropertyKind::Reachable => "reachable",
        }
    }
}

/// One `[[property]]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Property {
    /// `name` (required, unique among properties).
    pub name: Located<String>,
    /// Which of `always`, `eventually`, `reachable` was given (exactly one is required).
    pub kind: PropertyKind,
    /// Its formula.
    pub formula: Formula,
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
}

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
        }
    }
}

/// A parsed and validated `bdi-check.toml`.
#[derive(Clone, Debug, PartialEq)]
pub struct Manifest {
    /// The manifest's file in the [`SourceMap`]; every span below is in it.
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
}

/// A parsed scenario file: one run (SPEC §2).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// The scenario's file in the [`SourceMap`].
    pub file: FileId,
    /// Where it was read from.
    pub path: PathBuf,
    /// `initial` (required): the ground atoms true at the start; all others are false.
    pub initial: Vec<Formula>,
    /// `requests`: ground goal atoms, in order of arrival. Default: none.
    pub requests: Vec<Formula>,
}

// ----- entry points ----------------------------------------------------------------------

/// Reads and validates a manifest. `path` is the project folder or the manifest file itself
/// (SPEC: every command that takes PROJECT accepts either). The text is added to `map`.
/// Returns every error found, sorted by position.
pub fn load_manifest(path: &Path, map: &mut SourceMap) -> Result<Manifest, Vec<Diagnostic>> {
    let file_path = if path.is_dir() {
        let p = path.join(MANIFEST_NAME);
        if !p.is_file() {
            return Err(vec![Diagnostic::error(
                "input",
                format!(
                    "`{}` is not a project: it has no `{MANIFEST_NAME}`",
                    path.display()
                ),
            )
            .in_file(path.display().to_string())]);
        }
        p
    } else {
        path.to_path_buf()
    };
    let file = read_into(&file_path, map)?;
    parse_manifest(file, &map.file(file).text, &file_path)
}

/// Validates a manifest text already in a [`SourceMap`] under `file`; `path` is where it was
/// read from, against whose folder `plans` and `actions` are resolved and checked to exist.
pub fn parse_manifest(file: FileId, text: &str, path: &Path) -> Result<Manifest, Vec<Diagnostic>> {
    let mut cx = Cx::new(file, text);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let manifest = cx
        .parse_root()
        .and_then(|root| cx.manifest(&root, path, &dir));
    cx.finish(manifest)
}

/// Reads and validates a scenario file (SPEC §2: `initial` and `requests`, nothing else).
pub fn load_scenario(path: &Path, map: &mut SourceMap) -> Result<Scenario, Vec<Diagnostic>> {
    let file = read_into(path, map)?;
    parse_scenario(file, &map.file(file).text, path)
}

/// Validates a scenario text already in a [`SourceMap`] under `file`.
pub fn parse_scenario(file: FileId, text: &str, path: &Path) -> Result<Scenario, Vec<Diagnostic>> {
    let mut cx = Cx::new(file, text);
    let scenario = cx.parse_root().and_then(|root| cx.scenario(&root, path));
    cx.finish(scenario)
}

fn read_into(path: &Path, map: &mut SourceMap) -> Result<FileId, Vec<Diagnostic>> {
    match std::fs::read_to_string(path) {
        Ok(text) => Ok(map.add(path, path.display().to_string(), text)),
        Err(e) => Err(vec![Diagnostic::error(
            "input",
            format!("cannot read `{}`: {e}", path.display()),
        )
        .in_file(path.display().to_string())]),
    }
}

// ----- mapping string contents back into the TOML text -----------------------------------

/// Where each byte of a TOML string's value lies in the TOML text.
///
/// Formulas are parsed from the string's *value* and every span of the resulting AST is then
/// mapped through this table ([`Remap`]). We chose that over parsing a copy of the manifest in
/// which everything but the string is blanked out, because blanking only works when the raw
/// text between the quotes equals the value byte for byte: with escapes (`"a \"b\""`,
/// `\u00e9`) or a multi-line string's line-ending backslash the two differ in length, while the
/// table maps every byte exactly, whatever the string form (basic, literal, multi-line, a
/// quoted key). Should the table ever disagree with `toml`'s own decoding, every span falls
/// back to the whole string value: coarse but never wrong.
struct StrMap {
    /// The string value's range in the TOML text, quotes included.
    whole: Range<usize>,
    /// For each byte of the value: the raw range it came from (an escape maps all the bytes
    /// of its character to the whole escape). `None` when falling back.
    bytes: Option<Vec<(u32, u32)>>,
    /// Where the content ends in the raw text (the closing delimiter), for end-of-input spans.
    content_end: u32,
}

impl StrMap {
    fn new(text: &str, whole: Range<usize>, value: &str) -> StrMap {
        let raw = text.get(whole.clone()).unwrap_or("");
        let base = whole.start as u32;
        match decode_raw(raw) {
            Some((decoded, bytes, end)) if decoded == value => StrMap {
                bytes: Some(
                    bytes
                        .into_iter()
                        .map(|(s, e)| (base + s as u32, base + e as u32))
                        .collect(),
                ),
                content_end: base + end as u32,
                whole,
            },
            _ => StrMap {
                content_end: whole.end as u32,
                whole,
                bytes: None,
            },
        }
    }

    /// Maps a span in the value to the TOML text.
    fn map(&self, s: Span) -> Span {
        let Some(bytes) = &self.bytes else {
            return Span {
                file: s.file,
                start: self.whole.start as u32,
                end: self.whole.end as u32,
            };
        };
        let at = |i: u32| bytes.get(i as usize).map_or(self.content_end, |b| b.0);
        let start = at(s.start);
        let end = if s.end > s.start {
            bytes
                .get(s.end as usize - 1)
                .map_or(self.content_end, |b| b.1)
        } else {
            start
        };
        Span {
            file: s.file,
            start,
            end: end.max(start),
        }
    }

    /// Maps a byte range of the value.
    fn map_range(&self, file: FileId, r: Range<usize>) -> Span {
        self.map(Span::new(file, r.start, r.end))
    }
}

/// Decodes a TOML string or key as written (delimiters included): its value, the raw range of
/// each value byte (relative to `raw`), and where the content ends. `None` for anything not
/// understood, which makes [`StrMap`] fall back.
#[allow(clippy::type_complexity)]
fn decode_raw(raw: &str) -> Option<(String, Vec<(usize, usize)>, usize)> {
    let (delim, multi, basic) = if raw.starts_with("\"\"\"") {
        (3, true, true)
    } else if raw.starts_with("'''") {
        (3, true, false)
    } else if raw.starts_with('"') {
        (1, false, true)
    } else if raw.starts_with('\'') {
        (1, false, false)
    } else {
        (0, false, false) // a bare key
    };
    if raw.len() < 2 * delim {
        return None;
    }
    let end = raw.len() - delim;
    let mut i = delim;
    if multi {
        // TOML trims a newline right after the opening delimiter.
        if raw[i..end].starts_with("\r\n") {
            i += 2;
        } else if raw[i..end].starts_with('\n') {
            i += 1;
        }
    }
    let mut out = String::new();
    let mut map = Vec::new();
    while i < end {
        let c = raw.get(i..end)?.chars().next()?;
        if basic && c == '\\' {
            let e = raw.get(i + 1..end)?.chars().next()?;
            let hex = |n: usize| -> Option<char> {
                let h = raw.get(i + 2..i + 2 + n)?;
                if !h.bytes().all(|b| b.is_ascii_hexdigit()) {
                    return None;
                }
                char::from_u32(u32::from_str_radix(h, 16).ok()?)
            };
            let (ch, len) = match e {
                'b' => ('\u{8}', 2),
                't' => ('\t', 2),
                'n' => ('\n', 2),
                'f' => ('\u{c}', 2),
                'r' => ('\r', 2),
                'e' => ('\u{1b}', 2),
                '"' => ('"', 2),
                '\\' => ('\\', 2),
                'x' => (hex(2)?, 4),
                'u' => (hex(4)?, 6),
                'U' => (hex(8)?, 10),
                ' ' | '\t' | '\r' | '\n' if multi => {
                    // A line-ending backslash eats the whitespace and newlines that follow.
                    let rest = &raw[i + 1..end];
                    let skip = rest.len() - rest.trim_start_matches([' ', '\t', '\r', '\n']).len();
                    if !rest[..skip].contains('\n') {
                        return None;
                    }
                    i += 1 + skip;
                    continue;
                }
                _ => return None,
            };
            out.push(ch);
            map.extend(std::iter::repeat_n((i, i + len), ch.len_utf8()));
            i += len;
        } else {
            out.push(c);
            map.extend((i..i + c.len_utf8()).map(|k| (k, k + 1)));
            i += c.len_utf8();
        }
    }
    Some((out, map, end))
}

/// Rewrites every span of an AST node through a function. Exhaustive over the AST on purpose:
/// a new node kind is then a compile error here rather than a span left pointing at the
/// string's value instead of the TOML file.
trait Remap {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span);
}

impl<T: Remap> Remap for Vec<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.iter_mut().for_each(|x| x.remap(f));
    }
}

impl<T: Remap> Remap for Option<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        if let Some(x) = self {
            x.remap(f);
        }
    }
}

impl<T: Remap> Remap for Box<T> {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        (**self).remap(f);
    }
}

impl Remap for Span {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        *self = f(*self);
    }
}

impl Remap for Expr {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            ExprKind::Literal(l) => l.remap(f),
            ExprKind::Var(v) => v.remap(f),
            ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) => {}
            ExprKind::List(l) => l.remap(f),
            ExprKind::Unary(_, e) | ExprKind::Not(e) => e.remap(f),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                a.remap(f);
                b.remap(f);
            }
            ExprKind::PlanTerm(p) => p.remap(f),
        }
    }
}

impl Remap for Literal {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.namespace.remap(f);
        self.args.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Var {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.namespace.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Namespace {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
    }
}

impl Remap for ListExpr {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.elems.remap(f);
        self.tail.remap(f);
    }
}

impl Remap for PlanTerm {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            PlanTermKind::Plan(p) => p.remap(f),
            PlanTermKind::Trigger(t) => t.remap(f),
            PlanTermKind::Body(b) => b.remap(f),
            PlanTermKind::Rule(r) => r.remap(f),
        }
    }
}

impl Remap for Plan {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.label.remap(f);
        self.trigger.remap(f);
        self.context.remap(f);
        self.goal_condition.remap(f);
        self.body.remap(f);
        self.sub_plans.remap(f);
    }
}

impl Remap for Label {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.annots.remap(f);
    }
}

impl Remap for Trigger {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.literal.remap(f);
    }
}

impl Remap for Rule {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.head.remap(f);
        self.body.remap(f);
    }
}

impl Remap for Body {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        self.steps.remap(f);
    }
}

impl Remap for Step {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        match &mut self.kind {
            StepKind::Action(e)
            | StepKind::Achieve(e)
            | StepKind::AchieveNewFocus(e)
            | StepKind::Test(e)
            | StepKind::AddBel(e)
            | StepKind::AddBelEnd(e)
            | StepKind::AddBelNewFocus(e)
            | StepKind::DelBel(e)
            | StepKind::DelAddBel(e)
            | StepKind::DelBelNewFocus(e)
            | StepKind::Constraint(e) => e.remap(f),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    c.remap(f);
                    b.remap(f);
                }
                else_body.remap(f);
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                cond.remap(f);
                body.remap(f);
            }
            StepKind::Fork { branches, .. } => branches.remap(f),
            StepKind::Group(b) => b.remap(f),
        }
    }
}

impl Remap for Diagnostic {
    fn remap(&mut self, f: &dyn Fn(Span) -> Span) {
        self.span.remap(f);
        for l in &mut self.secondary {
            l.span.remap(f);
        }
    }
}

// ----- validation ------------------------------------------------------------------------

type Entry<'t, 'i> = (&'t Spanned<DeString<'i>>, &'t Spanned<DeValue<'i>>);

/// A table's entries in source order (`DeTable` keeps them sorted by key).
fn entries<'t, 'i>(t: &'t DeTable<'i>) -> Vec<Entry<'t, 'i>> {
    let mut v: Vec<_> = t.iter().collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

fn a_type(v: &DeValue) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

fn one_of(keys: &[&str]) -> String {
    keys.iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A Jason atom: what an object, a predicate or an action is called.
fn is_atom(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next().is_some_and(|c| c.is_ascii_lowercase())
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A PDDL type name.
fn is_type_name(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next().is_some_and(|c| c.is_ascii_alphabetic())
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// A name for an invariant, a property or a user: it appears in finding ids and `--user`.
fn is_name(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Every variable of an expression, with its span, in order.
fn vars<'e>(e: &'e Expr, out: &mut Vec<(&'e str, Span)>) {
    match &e.kind {
        ExprKind::Literal(l) => {
            l.args.iter().for_each(|a| vars(a, out));
            if let Some(a) = &l.annots {
                list_vars(a, out);
            }
        }
        ExprKind::Var(v) => out.push((&v.name, v.span)),
        ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) | ExprKind::PlanTerm(_) => {}
        ExprKind::List(l) => list_vars(l, out),
        ExprKind::Unary(_, a) | ExprKind::Not(a) => vars(a, out),
        ExprKind::Arith(_, a, b)
        | ExprKind::Rel(_, a, b)
        | ExprKind::And(a, b)
        | ExprKind::Or(a, b) => {
            vars(a, out);
            vars(b, out);
        }
    }
}

fn list_vars<'e>(l: &'e ListExpr, out: &mut Vec<(&'e str, Span)>) {
    l.elems.iter().for_each(|a| vars(a, out));
    if let Some(t) = &l.tail {
        vars(t, out);
    }
}

/// What an atom-valued entry is, for messages and for which checks apply.
#[derive(Clone, Copy)]
struct AtomRule {
    /// "a fact", "a goal", ...
    what: &'static str,
    /// An example of the expected shape.
    example: &'static str,
    /// Whether variables are refused.
    ground: bool,
}

const FACT: AtomRule = AtomRule {
    what: "a fact",
    example: "robotAt(table)",
    ground: true,
};
const GOAL: AtomRule = AtomRule {
    what: "a goal",
    example: "storeCup(C)",
    ground: false,
};
const SCENARIO_ATOM: AtomRule = AtomRule {
    what: "an initial atom",
    example: "cupAt(cup1,table)",
    ground: true,
};
const SCENARIO_REQUEST: AtomRule = AtomRule {
    what: "a request",
    example: "storeCup(cup1)",
    ground: true,
};

/// The validation context: the manifest's text and every error found so far.
struct Cx<'a> {
    file: FileId,
    text: &'a str,
    errors: Vec<Diagnostic>,
}

impl<'a> Cx<'a> {
    fn new(file: FileId, text: &'a str) -> Self {
        Cx {
            file,
            text,
            errors: Vec::new(),
        }
    }

    fn span(&self, r: Range<usize>) -> Span {
        Span::new(self.file, r.start, r.end)
    }

    fn err(&mut self, r: Range<usize>, message: impl Into<String>, label: impl Into<String>) {
        let d = Diagnostic::error("input", message).with_label(self.span(r), label);
        self.errors.push(d);
    }

    /// Returns the value when no error was recorded; errors sorted by position.
    fn finish<T>(mut self, value: Option<T>) -> Result<T, Vec<Diagnostic>> {
        match value {
            Some(v) if self.errors.is_empty() => Ok(v),
            _ => {
                if self.errors.is_empty() {
                    // Every failing path records an error; this is a guard, never a pass.
                    self.errors
                        .push(Diagnostic::error("input", "invalid file").at(self.span(0..0)));
                }
                self.errors
                    .sort_by_key(|d| d.span.map_or((0, 0), |s| (s.start, s.end)));
                Err(self.errors)
            }
        }
    }

    /// Parses the TOML document. Syntax errors are all reported, and the schema is not checked
    /// then: the recovered tree holds stand-in values that would only add noise. The parser's
    /// recovery cascades, so only the first error of a line is kept, and a table header
    /// reported as a duplicate hides the duplicate keys of its body (they clash only because
    /// the body was merged into the first table).
    fn parse_root(&mut self) -> Option<DeTable<'a>> {
        let (root, mut errs) = DeTable::parse_recoverable(self.text);
        if errs.is_empty() {
            return Some(root.into_inner());
        }
        let text = self.text;
        let clamp = |r: Range<usize>| r.start.min(text.len())..r.end.min(text.len());
        errs.sort_by_key(|e| e.span().map_or(0, |r| clamp(r).start));
        let line_of = |at: usize| text[..at].rfind('\n').map_or(0, |i| i + 1);
        // The start of the last `[header]` line at or before `at`.
        let header_of = |at: usize| {
            let mut l = line_of(at);
            loop {
                if text[l..].trim_start().starts_with('[') {
                    return Some(l);
                }
                if l == 0 {
                    return None;
                }
                l = line_of(l - 1);
            }
        };
        let mut last_line = None;
        let mut duplicate_header = None;
        for e in errs {
            let r = clamp(e.span().unwrap_or(0..0));
            let line = line_of(r.start);
            if last_line == Some(line) {
                continue;
            }
            let mut msg = e.message().to_string();
            if msg == "duplicate key" {
                let header = header_of(r.start);
                if header == Some(line) {
                    duplicate_header = header;
                } else if header.is_some() && header == duplicate_header {
                    continue;
                }
                msg = format!("duplicate key `{}`", &text.get(r.clone()).unwrap_or(""));
            }
            last_line = Some(line);
            let d = Diagnostic::syntax(self.span(r), format!("TOML: {msg}"), "");
            self.errors.push(d);
        }
        None
    }

    // ----- generic value checks ----------------------------------------------------------

    fn wrong_type(&mut self, v: &Spanned<DeValue>, what: &str, expected: &str) {
        self.err(
            v.span(),
            format!(
                "wrong type for {what}: expected {expected}, found {}",
                a_type(v.get_ref())
            ),
            format!("expected {expected}"),
        );
    }

    /// Reports every key of `t` not in `allowed`; `place` reads "in [agent]", "at the top
    /// level".
    fn check_keys(&mut self, t: &DeTable, allowed: &[&str], place: &str) {
        for (k, _) in entries(t) {
            if !allowed.contains(&k.get_ref().as_ref()) {
                let allowed = match allowed {
                    [only] => format!("the only key allowed is `{only}`"),
                    _ => format!("allowed: {}", one_of(allowed)),
                };
                self.err(
                    k.span(),
                    format!("unknown key `{}` {place}; {allowed}", k.get_ref()),
                    "unknown key",
                );
            }
        }
    }

    fn table<'t, 'i>(
        &mut self,
        v: &'t Spanned<DeValue<'i>>,
        what: &str,
    ) -> Option<&'t DeTable<'i>> {
        match v.get_ref() {
            DeValue::Table(t) => Some(t),
            _ => {
                self.wrong_type(v, what, "a table");
                None
            }
        }
    }

    /// A section `[key]` of `root`, checked for unknown keys.
    fn section<'t, 'i>(
        &mut self,
        root: &'t DeTable<'i>,
        key: &str,
        allowed: &[&str],
    ) -> Option<&'t DeTable<'i>> {
        let t = self.table(root.get(key)?, &format!("[{key}]"))?;
        self.check_keys(t, allowed, &format!("in [{key}]"));
        Some(t)
    }

    fn array<'t, 'i>(
        &mut self,
        v: &'t Spanned<DeValue<'i>>,
        what: &str,
        expected: &str,
    ) -> Option<&'t DeArray<'i>> {
        match v.get_ref() {
            DeValue::Array(a) => Some(a),
            _ => {
                self.wrong_type(v, what, expected);
                None
            }
        }
    }

    fn string(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Located<String>> {
        match v.get_ref() {
            DeValue::String(s) => Some(Located {
                value: s.to_string(),
                span: self.span(v.span()),
            }),
            _ => {
                self.wrong_type(v, what, "a string");
                None
            }
        }
    }

    /// An array of strings; the bad elements are reported and left out.
    fn strings(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
    ) -> Vec<(Located<String>, Range<usize>)> {
        let Some(a) = self.array(v, what, "an array of strings") else {
            return Vec::new();
        };
        a.iter()
            .filter_map(|x| Some((self.string(x, &format!("an element of {what}"))?, x.span())))
            .collect()
    }

    fn integer(&mut self, v: &Spanned<DeValue>, what: &str, min: u64, max: u64) -> Option<u64> {
        let DeValue::Integer(i) = v.get_ref() else {
            self.wrong_type(v, what, "an integer");
            return None;
        };
        match u64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) if (min..=max).contains(&n) => Some(n),
            _ => {
                self.err(
                    v.span(),
                    format!("{what} must be an integer from {min} to {max}"),
                    "out of range",
                );
                None
            }
        }
    }

    /// One of a fixed set of strings; returns its index.
    fn choice(&mut self, v: &Spanned<DeValue>, what: &str, options: &[&str]) -> Option<usize> {
        let s = self.string(v, what)?;
        let found = options.iter().position(|o| *o == s.value);
        if found.is_none() {
            let opts: Vec<String> = options.iter().map(|o| format!("\"{o}\"")).collect();
            self.err(
                v.span(),
                format!(
                    "bad value \"{}\" for {what}: expected {}",
                    s.value.escape_debug(),
                    opts.join(" or ")
                ),
                "not allowed here",
            );
        }
        found
    }

    fn missing(&mut self, r: Range<usize>, key: &str, place: &str) {
        self.err(
            r,
            format!("missing key `{key}` in {place}"),
            format!("{place} needs `{key}`"),
        );
    }

    fn duplicate(&mut self, name: &str, what: &str, at: Span, first: Span) {
        let d = Diagnostic::error("input", format!("duplicate {what} `{name}`"))
            .with_label(at, "defined again here")
            .with_secondary(first, "first defined here");
        self.errors.push(d);
    }

    /// Reports the second and later occurrences of each name (in source order).
    fn no_duplicates(&mut self, names: &[Located<String>], what: &str) {
        let mut sorted: Vec<&Located<String>> = names.iter().collect();
        sorted.sort_by_key(|n| n.span.start);
        for (i, n) in sorted.iter().enumerate() {
            if let Some(first) = sorted[..i].iter().find(|m| m.value == n.value) {
                self.duplicate(&n.value, what, n.span, first.span);
            }
        }
    }

    // ----- formulas ----------------------------------------------------------------------

    /// Parses a TOML string's value with `parse`, every span mapped into the TOML text.
    fn parse_in<T: Remap>(
        &mut self,
        s: &Located<String>,
        raw: Range<usize>,
        parse: impl FnOnce(FileId, &str) -> Result<T, Vec<Diagnostic>>,
    ) -> Option<T> {
        let map = StrMap::new(self.text, raw, &s.value);
        let f = |sp: Span| map.map(sp);
        match parse(self.file, &s.value) {
            Ok(mut t) => {
                t.remap(&f);
                Some(t)
            }
            Err(ds) => {
                for mut d in ds {
                    d.remap(&f);
                    self.errors.push(d);
                }
                None
            }
        }
    }

    fn formula(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Formula> {
        let s = self.string(v, what)?;
        let expr = self.parse_in(&s, v.span(), parse_expr)?;
        Some(Formula {
            text: s.value,
            span: s.span,
            expr,
        })
    }

    fn formulas(&mut self, v: &Spanned<DeValue>, what: &str) -> Vec<Formula> {
        let Some(a) = self.array(v, what, "an array of strings") else {
            return Vec::new();
        };
        a.iter()
            .filter_map(|x| self.formula(x, &format!("an element of {what}")))
            .collect()
    }

    /// An array of atoms obeying `rule`.
    fn atoms(&mut self, v: &Spanned<DeValue>, what: &str, rule: AtomRule) -> Vec<Formula> {
        let fs = self.formulas(v, what);
        fs.into_iter()
            .filter(|f| self.atom(&f.expr, rule))
            .collect()
    }

    /// Whether `e` is a plain atom `p(t, ...)` as `rule` asks; reports what is not.
    fn atom(&mut self, e: &Expr, rule: AtomRule) -> bool {
        let AtomRule {
            what,
            example,
            ground,
        } = rule;
        let err = |cx: &mut Self, at: Span, msg: String, label: &str| {
            cx.errors
                .push(Diagnostic::error("input", msg).with_label(at, label));
        };
        let ExprKind::Literal(l) = &e.kind else {
            err(
                self,
                e.span,
                format!("{what} must be an atom such as `{example}`"),
                "not an atom",
            );
            return false;
        };
        if l.is_internal_action() {
            err(
                self,
                e.span,
                format!(
                    "{what} must be an atom, not the internal action `{}`",
                    l.functor
                ),
                "internal action",
            );
            return false;
        }
        if l.negated || l.namespace.is_some() || l.annots.is_some() {
            err(
                self,
                e.span,
                format!("{what} must be a plain atom such as `{example}`: no `~`, namespace or annotations"),
                "not a plain atom",
            );
            return false;
        }
        if ground {
            let mut vs = Vec::new();
            vars(e, &mut vs);
            if let Some((name, at)) = vs.first() {
                err(
                    self,
                    *at,
                    format!("{what} must be ground, but `{name}` is a variable"),
                    "variable",
                );
                return false;
            }
        }
        true
    }

    /// A bare name `p` inside a string (a predicate or an action name); its span is the name's.
    fn name_in_string(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Located<String>> {
        let f = self.formula(v, what)?;
        match &f.expr.kind {
            ExprKind::Literal(l)
                if l.args.is_empty()
                    && l.annots.is_none()
                    && !l.negated
                    && l.namespace.is_none()
                    && is_atom(&l.functor) =>
            {
                Some(Located {
                    value: l.functor.clone(),
                    span: f.expr.span,
                })
            }
            _ => {
                let at = f.expr.span;
                self.errors.push(
                    Diagnostic::error(
                        "input",
                        format!("{what} must be a name such as `cupAt`, without arguments"),
                    )
                    .with_label(at, "not a name"),
                );
                None
            }
        }
    }

    /// A string holding a body step that is an environment action or a request `!g`.
    fn observed_step(
        &mut self,
        s: Located<String>,
        raw: Range<usize>,
        what: &str,
    ) -> Option<StepFormula> {
        let step = self.parse_in(&s, raw, parse_step)?;
        let ok = match &step.kind {
            StepKind::Action(e) | StepKind::Achieve(e) => {
                matches!(&e.kind, ExprKind::Literal(l) if !l.is_internal_action() && !l.negated)
            }
            _ => false,
        };
        if !ok {
            self.errors.push(
                Diagnostic::error(
                    "input",
                    format!("{what} must be an action `a(x)` or a request `!g(x)`"),
                )
                .with_help("for example `navigateTo(table)` or `!storeCup(C)`")
                .with_label(step.span, "neither an action nor a request"),
            );
            return None;
        }
        Some(StepFormula {
            text: s.value,
            span: s.span,
            step,
        })
    }

    // ----- the manifest ------------------------------------------------------------------

    fn manifest(&mut self, root: &DeTable, path: &Path, dir: &Path) -> Option<Manifest> {
        const TOP: &[&str] = &[
            "agent",
            "objects",
            "initial",
            "requests",
            "invariants",
            "property",
            "explanation",
            "bounds",
        ];
        self.check_keys(root, TOP, "at the top level");
        let agent = self.agent(root, dir);
        let objects = self.objects(root);
        let initial = self.initial(root);
        let requests = self.requests(root);
        let invariants = self.invariants(root);
        let properties = self.properties(root);
        let explanation = self.explanation(root);
        let bounds = self.bounds(root, &objects);
        Some(Manifest {
            file: self.file,
            path: path.to_path_buf(),
            dir: dir.to_path_buf(),
            agent: agent?,
            objects,
            initial,
            requests,
            invariants,
            properties,
            explanation,
            bounds,
        })
    }

    fn agent(&mut self, root: &DeTable, dir: &Path) -> Option<AgentSection> {
        if root.get("agent").is_none() {
            self.err(
                0..0,
                "missing section [agent]: the manifest must name the plan library and the action model",
                "expected `[agent]` with `plans` and `actions`",
            );
            return None;
        }
        let t = self.section(root, "agent", &["plans", "actions", "source_path"])?;
        let header = root.get("agent").map_or(0..0, |v| v.span());
        let file = |cx: &mut Self, key: &str, kind: &str| -> Option<FileRef> {
            let Some(v) = t.get(key) else {
                cx.missing(header.clone(), key, "[agent]");
                return None;
            };
            let written = cx.string(v, &format!("`agent.{key}`"))?;
            let path = dir.join(&written.value);
            if written.value.is_empty() || !path.is_file() {
                let why = if path.is_dir() {
                    "is a folder"
                } else if path.exists() {
                    "is not a regular file"
                } else {
                    "does not exist"
                };
                let d =
                    Diagnostic::error("input", format!("{kind} file `{}` {why}", written.value))
                        .with_label(cx.span(v.span()), "no such file")
                        .with_help(format!(
                            "paths are relative to the manifest's folder; looked for `{}`",
                            path.display()
                        ));
                cx.errors.push(d);
                return None;
            }
            Some(FileRef { written, path })
        };
        let plans = file(self, "plans", "plan library");
        let actions = file(self, "actions", "action model");
        let mut source_path = Vec::new();
        if let Some(v) = t.get("source_path") {
            for (folder, span) in self.strings(v, "`agent.source_path`") {
                let path = dir.join(&folder.value);
                if path.is_dir() {
                    source_path.push(path);
                } else {
                    self.err(
                        span,
                        format!("source path folder `{}` does not exist", folder.value),
                        "no such folder",
                    );
                }
            }
        }
        Some(AgentSection {
            source_path,
            plans: plans?,
            actions: actions?,
        })
    }

    fn objects(&mut self, root: &DeTable) -> Vec<ObjectType> {
        let Some(v) = root.get("objects") else {
            return Vec::new();
        };
        let Some(t) = self.table(v, "[objects]") else {
            return Vec::new();
        };
        let mut types = Vec::new();
        let mut all = Vec::new();
        for (k, v) in entries(t) {
            let name = Located {
                value: k.get_ref().to_string(),
                span: self.span(k.span()),
            };
            if !is_type_name(&name.value) {
                self.err(
                    k.span(),
                    format!("`{}` is not a PDDL type name", name.value),
                    "expected a name such as `cup`",
                );
            }
            let mut objects = Vec::new();
            for (o, _) in self.strings(v, &format!("`objects.{}`", name.value)) {
                if is_atom(&o.value) {
                    all.push(o.clone());
                    objects.push(o);
                } else {
                    let r = o.span.start as usize..o.span.end as usize;
                    self.err(
                        r,
                        format!(
                            "object name \"{}\" is not a Jason atom (a lowercase letter, then letters, digits, `_`)",
                            o.value.escape_debug()
                        ),
                        "expected a name such as `cup1`",
                    );
                }
            }
            types.push(ObjectType { name, objects });
        }
        self.no_duplicates(&all, "object");
        types
    }

    fn initial(&mut self, root: &DeTable) -> InitialSection {
        let mut out = InitialSection::default();
        let Some(t) = self.section(root, "initial", &["facts", "vary", "constraints"]) else {
            return out;
        };
        if let Some(v) = t.get("facts") {
            out.facts = self.atoms(v, "`initial.facts`", FACT);
        }
        if let Some(v) = t.get("vary") {
            if let Some(a) = self.array(v, "`initial.vary`", "an array of strings") {
                out.vary = a
                    .iter()
                    .filter_map(|x| self.name_in_string(x, "an element of `initial.vary`"))
                    .collect();
                let vary = out.vary.clone();
                self.no_duplicates(&vary, "predicate in `initial.vary`");
            }
        }
        if let Some(v) = t.get("constraints") {
            out.constraints = self.formulas(v, "`initial.constraints`");
        }
        out
    }

    fn requests(&mut self, root: &DeTable) -> RequestsSection {
        let mut out = RequestsSection::default();
        let Some(t) = self.section(root, "requests", &["goals", "max", "arrival", "from"]) else {
            return out;
        };
        if let Some(v) = t.get("goals") {
            out.goals = self.atoms(v, "`requests.goals`", GOAL);
        }
        if let Some(v) = t.get("max") {
            if let Some(n) = self.integer(v, "`requests.max`", 0, u32::MAX as u64) {
                out.max = n as u32;
            }
        }
        if let Some(v) = t.get("arrival") {
            match self.choice(v, "`requests.arrival`", &["idle", "any"]) {
                Some(0) => out.arrival = Arrival::Idle,
                Some(_) => out.arrival = Arrival::Any,
                None => {}
            }
        }
        if let Some(v) = t.get("from") {
            if let Some(name) = self.string(v, "`requests.from`") {
                let ok = name
                    .value
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_lowercase())
                    && name
                        .value
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || c == '_');
                if ok {
                    out.from = Some(name);
                } else {
                    self.err(
                        v.span(),
                        format!("`{}` is not an agent name", name.value),
                        "expected a Jason atom such as `owner`",
                    );
                }
            }
        }
        out
    }

    fn invariants(&mut self, root: &DeTable) -> Vec<Invariant> {
        let Some(v) = root.get("invariants") else {
            return Vec::new();
        };
        let Some(t) = self.table(v, "[invariants]") else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (k, v) in entries(t) {
            let name = Located {
                value: k.get_ref().to_string(),
                span: self.span(k.span()),
            };
            if !is_name(&name.value) {
                self.err(
                    k.span(),
                    format!("`{}` is not a valid invariant name", name.value),
                    "expected letters, digits, `_` or `-`",
                );
            }
            if let Some(formula) = self.formula(v, &format!("invariant `{}`", name.value)) {
                out.push(Invariant { name, formula });
            }
        }
        out
    }

    fn properties(&mut self, root: &DeTable) -> Vec<Property> {
        const KEYS: &[&str] = &["name", "always", "eventually", "reachable"];
        let Some(v) = root.get("property") else {
            return Vec::new();
        };
        let Some(a) = self.array(v, "`property`", "an array of tables `[[property]]`") else {
            return Vec::new();
        };
        let mut out = Vec::new();
        let mut names = Vec::new();
        for (i, pv) in a.iter().enumerate() {
            let place = format!("[[property]] #{}", i + 1);
            let Some(t) = self.table(pv, &place) else {
                continue;
            };
            self.check_keys(t, KEYS, "in [[property]]");
            let name = match t.get("name") {
                Some(n) => self.string(n, "`property.name`"),
                None => {
                    self.missing(pv.span(), "name", "[[property]]");
                    None
                }
            };
            if let Some(n) = &name {
                if !is_name(&n.value) {
                    let r = n.span.start as usize..n.span.end as usize;
                    self.err(
                        r,
                        format!(
                            "\"{}\" is not a valid property name",
                            n.value.escape_debug()
                        ),
                        "expected letters, digits, `_` or `-`",
                    );
                }
                names.push(n.clone());
            }
            let label = name.as_ref().map_or("this property".to_string(), |n| {
                format!("property `{}`", n.value)
            });
            let mut kinds: Vec<(PropertyKind, Entry)> = entries(t)
                .into_iter()
                .filter_map(|e| {
                    let k = match e.0.get_ref().as_ref() {
                        "always" => PropertyKind::Always,
                        "eventually" => PropertyKind::Eventually,
                        "reachable" => PropertyKind::Reachable,
                        _ => return None,
                    };
                    Some((k, e))
                })
                .collect();
            kinds.sort_by_key(|(_, (k, _))| k.span().start);
            if kinds.is_empty() {
                self.err(
                    pv.span(),
                    format!("{label} needs one of `always`, `eventually` or `reachable`"),
                    "no formula",
                );
                continue;
            }
            for (k, (key, _)) in &kinds[1..] {
                self.err(
                    key.span(),
                    format!(
                        "{label} has both `{}` and `{}`: give exactly one of `always`, `eventually`, `reachable`",
                        kinds[0].0.key(),
                        k.key()
                    ),
                    "second formula",
                );
            }
            let (kind, (_, fv)) = kinds[0];
            let formula = self.formula(fv, &format!("`{}` of {label}", kind.key()));
            if let (Some(name), Some(formula), 1) = (name, formula, kinds.len()) {
                out.push(Property {
                    name,
                    kind,
                    formula,
                    span: self.span(pv.span()),
                });
            }
        }
        self.no_duplicates(&names, "property name");
        out
    }

    fn explanation(&mut self, root: &DeTable) -> Option<ExplanationSection> {
        const KEYS: &[&str] = &["modifies", "emitted_by", "phrases", "users"];
        let t = self.section(root, "explanation", KEYS)?;
        let mut out = ExplanationSection::default();
        if let Some(v) = t.get("modifies") {
            match self.choice(v, "`explanation.modifies`", &["syntactic", "semantic"]) {
                Some(0) => out.modifies = Modifies::Syntactic,
                Some(_) => out.modifies = Modifies::Semantic,
                None => {}
            }
        }
        if let Some(v) = t.get("emitted_by") {
            out.emitted_by = self.name_in_string(v, "`explanation.emitted_by`");
        }
        if let Some(v) = t.get("phrases") {
            if let Some(pt) = self.table(v, "[explanation.phrases]") {
                for (k, v) in entries(pt) {
                    let key = Located {
                        value: k.get_ref().to_string(),
                        span: self.span(k.span()),
                    };
                    let pattern = self.observed_step(key, k.span(), "a phrase pattern");
                    let template = self.string(v, "a phrase template");
                    if let (Some(pattern), Some(template)) = (pattern, template) {
                        if self.template(&pattern, &template, v.span()) {
                            out.phrases.push(Phrase { pattern, template });
                        }
                    }
                }
            }
        }
        if let Some(v) = t.get("users") {
            if let Some(ut) = self.table(v, "[explanation.users]") {
                for (k, v) in entries(ut) {
                    if let Some(u) = self.user(k, v) {
                        out.users.push(u);
                    }
                }
            }
        }
        Some(out)
    }

    /// Checks that every `{X}` of a template names a variable of the pattern.
    fn template(
        &mut self,
        pattern: &StepFormula,
        template: &Located<String>,
        raw: Range<usize>,
    ) -> bool {
        let mut vs = Vec::new();
        if let StepKind::Action(e) | StepKind::Achieve(e) = &pattern.step.kind {
            vars(e, &mut vs);
        }
        let map = StrMap::new(self.text, raw, &template.value);
        let t = template.value.as_str();
        let mut ok = true;
        let mut i = 0;
        while i < t.len() {
            let rest = &t[i..];
            if rest.starts_with("{{") || rest.starts_with("}}") {
                i += 2;
            } else if rest.starts_with('{') {
                let Some(close) = rest.find('}') else {
                    let at = map.map_range(self.file, i..i + 1);
                    self.errors.push(
                        Diagnostic::error(
                            "input",
                            "unclosed `{` in a phrase template (write `{{` for a brace)",
                        )
                        .with_label(at, "unclosed"),
                    );
                    return false;
                };
                let name = &rest[1..close];
                if !vs.iter().any(|(v, _)| *v == name) {
                    let at = map.map_range(self.file, i..i + close + 1);
                    self.errors.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "`{{{name}}}` names no variable of the pattern `{}`",
                                pattern.text
                            ),
                        )
                        .with_label(at, "unknown variable")
                        .with_secondary(pattern.step.span, "the pattern"),
                    );
                    ok = false;
                }
                i += close + 1;
            } else if rest.starts_with('}') {
                let at = map.map_range(self.file, i..i + 1);
                self.errors.push(
                    Diagnostic::error(
                        "input",
                        "unmatched `}` in a phrase template (write `}}` for a brace)",
                    )
                    .with_label(at, "unmatched"),
                );
                return false;
            } else {
                i += rest.chars().next().map_or(1, char::len_utf8);
            }
        }
        ok
    }

    fn user(&mut self, k: &Spanned<DeString>, v: &Spanned<DeValue>) -> Option<User> {
        let name = Located {
            value: k.get_ref().to_string(),
            span: self.span(k.span()),
        };
        let place = format!("[explanation.users.{}]", name.value);
        if !is_name(&name.value) {
            self.err(
                k.span(),
                format!("`{}` is not a valid user name", name.value),
                "expected letters, digits, `_` or `-`",
            );
        }
        let t = self.table(v, &place)?;
        self.check_keys(t, &["expected"], &format!("in {place}"));
        let mut expected = Vec::new();
        let what = format!("`explanation.users.{}.expected`", name.value);
        if let Some(ev) = t.get("expected") {
            let a = self.array(ev, &what, "an array of pairs")?;
            for pv in a.iter() {
                let bad = |cx: &mut Self, found: String| {
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "an expected pair must be a list of exactly 2 strings; found {found}"
                        ),
                    )
                    .with_label(cx.span(pv.span()), "expected [\"before\", \"after\"]")
                    .with_help("write a pair as [\"!storeCup(C)\", \"navigateTo(table)\"]");
                    cx.errors.push(d);
                };
                let DeValue::Array(pair) = pv.get_ref() else {
                    bad(self, a_type(pv.get_ref()).to_string());
                    continue;
                };
                if pair.len() != 2 {
                    bad(
                        self,
                        format!(
                            "{} element{}",
                            pair.len(),
                            if pair.len() == 1 { "" } else { "s" }
                        ),
                    );
                    continue;
                }
                let (DeValue::String(b), DeValue::String(e)) =
                    (pair[0].get_ref(), pair[1].get_ref())
                else {
                    let odd = pair
                        .iter()
                        .find(|x| !x.get_ref().is_str())
                        .unwrap_or(&pair[0]);
                    bad(self, format!("{} in it", a_type(odd.get_ref())));
                    continue;
                };
                let loc = |s: &str, r: Range<usize>, cx: &Self| Located {
                    value: s.to_string(),
                    span: cx.span(r),
                };
                let before = loc(b, pair[0].span(), self);
                let after = loc(e, pair[1].span(), self);
                let before =
                    self.observed_step(before, pair[0].span(), "an element of an expected pair");
                let after =
                    self.observed_step(after, pair[1].span(), "an element of an expected pair");
                if let (Some(before), Some(after)) = (before, after) {
                    expected.push(ExpectedPair {
                        before,
                        after,
                        span: self.span(pv.span()),
                    });
                }
            }
        }
        Some(User { name, expected })
    }

    fn bounds(&mut self, root: &DeTable, objects: &[ObjectType]) -> Bounds {
        const KEYS: &[&str] = &[
            "max_states",
            "max_depth",
            "symmetry",
            "plan_selection",
            "numbers",
        ];
        let mut out = Bounds::default();
        let Some(t) = self.section(root, "bounds", KEYS) else {
            return out;
        };
        if let Some(v) = t.get("max_states") {
            if let Some(n) = self.integer(v, "`bounds.max_states`", 1, i64::MAX as u64) {
                out.max_states = n;
            }
        }
        if let Some(v) = t.get("max_depth") {
            if let Some(n) = self.integer(v, "`bounds.max_depth`", 1, i64::MAX as u64) {
                out.max_depth = n;
            }
        }
        if let Some(v) = t.get("symmetry") {
            for (s, r) in self.strings(v, "`bounds.symmetry`") {
                if objects.iter().any(|o| o.name.value == s.value) {
                    out.symmetry.push(s);
                } else {
                    self.err(
                        r,
                        format!(
                            "symmetry type \"{}\" is not a type of [objects]",
                            s.value.escape_debug()
                        ),
                        "not in [objects]",
                    );
                }
            }
            let sym = out.symmetry.clone();
            self.no_duplicates(&sym, "symmetry type");
        }
        if let Some(v) = t.get("plan_selection") {
            match self.choice(v, "`bounds.plan_selection`", &["first", "any"]) {
                Some(0) => out.plan_selection = PlanSelection::First,
                Some(_) => out.plan_selection = PlanSelection::Any,
                None => {}
            }
        }
        if let Some(v) = t.get("numbers") {
            let ints: Option<Vec<i64>> = match v.get_ref() {
                DeValue::Array(a) => a
                    .iter()
                    .map(|x| match x.get_ref() {
                        DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok(),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            };
            match ints.as_deref() {
                Some(&[lo, hi]) if lo <= hi && hi - lo < MAX_NUMBERS => {
                    out.numbers = Some(Located {
                        value: (lo, hi),
                        span: self.span(v.span()),
                    })
                }
                _ => self.err(
                    v.span(),
                    format!(
                        "`bounds.numbers` must be `[lo, hi]`, two integers with lo <= hi and fewer than {MAX_NUMBERS} numbers"
                    ),
                    "expected `[lo, hi]`",
                ),
            }
        }
        out
    }

    // ----- scenarios ---------------------------------------------------------------------

    fn scenario(&mut self, root: &DeTable, path: &Path) -> Option<Scenario> {
        self.check_keys(root, &["initial", "requests"], "in a scenario");
        let initial = match root.get("initial") {
            Some(v) => Some(self.atoms(v, "`initial`", SCENARIO_ATOM)),
            None => {
                self.missing(0..0, "initial", "a scenario");
                None
            }
        };
        let requests = match root.get("requests") {
            Some(v) => self.atoms(v, "`requests`", SCENARIO_REQUEST),
            None => Vec::new(),
        };
        Some(Scenario {
            file: self.file,
            path: path.to_path_buf(),
            initial: initial?,
            requests,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_maps_escapes_to_their_raw_bytes() {
        let (s, map, end) = decode_raw(r#""a\"b\u00e9c""#).unwrap();
        assert_eq!(s, "a\"béc");
        assert_eq!(map[0], (1, 2));
        assert_eq!(map[1], (2, 4)); // `\"`
        assert_eq!(map[2], (4, 5));
        assert_eq!(map[3], (5, 11)); // both bytes of é come from `\u00e9`
        assert_eq!(map[4], (5, 11));
        assert_eq!(map[5], (11, 12));
        assert_eq!(end, 12);
    }

    #[test]
    fn decode_handles_multiline_and_literal_strings() {
        let (s, map, _) = decode_raw("\"\"\"\nab \\\n   c\"\"\"").unwrap();
        assert_eq!(s, "ab c");
        assert_eq!(map[3], (12, 13));
        let (s, _, _) = decode_raw("'a\\b'").unwrap();
        assert_eq!(s, "a\\b");
        let (s, _, _) = decode_raw("bare_key").unwrap();
        assert_eq!(s, "bare_key");
    }

    #[test]
    fn formula_spans_point_into_the_toml_text_even_with_escapes() {
        let text = "[invariants]\nx = \"p(\\\"s\\\") & q(Y)\"\n";
        let mut map = SourceMap::new();
        let id = map.add("m.toml", "m.toml", text.to_string());
        let mut cx = Cx::new(id, text);
        let root = cx.parse_root().unwrap();
        let inv = cx.invariants(&root);
        assert!(cx.errors.is_empty(), "{:?}", cx.errors);
        let ExprKind::And(_, q) = &inv[0].formula.expr.kind else {
            panic!()
        };
        assert_eq!(map.slice(q.span), "q(Y)");
        assert_eq!(map.slice(inv[0].formula.expr.span), "p(\\\"s\\\") & q(Y)");
    }
}
