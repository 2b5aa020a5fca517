//! The AgentSpeak test corpus under `tests/asl/`.
//!
//! * `valid/`: every agent loads with no diagnostic, and the corpus as a whole uses every
//!   variant of the syntax tree (and a list of further constructs), so "the corpus covers
//!   every construct" is checked, not promised.
//! * `invalid/`: every file yields exactly the diagnostics its header announces, one
//!   `// expect: LINE:COLUMN <substring of the message>` line per diagnostic (line and
//!   column 1-based, in the file itself).
//! * Jason's own example agents, when a copy is present at `/tmp/jason/asl`, parse unchanged.
//! * With a checkout of jason-lang/jason (`BDI_CHECK_JASON=/path/to/jason`), its example and
//!   demo agents go through `bdi-check verify` on a generated stub of their environment, and
//!   as many load as README.md says (`-- --nocapture` prints the table of refusals).
//!
//! In both folders, a file whose first line starts with `// included-only` is a library
//! loaded only through an `include` of another file, never on its own.

use bdi_check::syntax::ast::*;
use bdi_check::syntax::loader::load_agent_with;
use bdi_check::syntax::{load_agent, Diagnostic, SourceMap};
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The marker that keeps a file from being loaded on its own.
const INCLUDED_ONLY: &str = "// included-only";

/// The header line announcing one expected diagnostic.
const EXPECT: &str = "// expect:";

/// Where a copy of Jason's examples may be (not part of the repository).
const JASON_DIRS: [&str; 2] = ["/tmp/jason/asl/examples", "/tmp/jason/asl/demos"];

fn corpus_dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("asl")
        .join(sub)
}

/// Every `.asl` file under `dir`, recursively, sorted.
fn asl_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        let entries =
            std::fs::read_dir(&d).unwrap_or_else(|e| panic!("cannot list {}: {e}", d.display()));
        for entry in entries {
            let path = entry
                .unwrap_or_else(|e| panic!("cannot list {}: {e}", d.display()))
                .path();
            if path.is_dir() {
                todo.push(path);
            } else if path.extension().is_some_and(|x| x == "asl") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

fn is_included_only(path: &Path) -> bool {
    read(path)
        .lines()
        .next()
        .is_some_and(|l| l.trim_start().starts_with(INCLUDED_ONLY))
}

fn render_all(diags: &[Diagnostic], map: &SourceMap) -> String {
    diags.iter().map(|d| d.render(map, false)).collect()
}

/// Checks that every diagnostic renders with `file:line:column` in its first line.
fn check_rendering(diags: &[Diagnostic], map: &SourceMap, problems: &mut Vec<String>) {
    for d in diags {
        let text = d.render(map, false);
        let first = text.lines().next().unwrap_or_default();
        match d.location(map) {
            Some(loc) => {
                let place = format!("{}:{}:{}", loc.file, loc.line, loc.column);
                if !first.contains(&place) {
                    problems.push(format!(
                        "the first line of a rendered diagnostic lacks `{place}`:\n{text}"
                    ));
                }
            }
            None => problems.push(format!("a diagnostic has no location:\n{text}")),
        }
    }
}

// ----- (a) the valid corpus ----------------------------------------------------------------

#[test]
fn valid_corpus_loads_without_diagnostics_and_covers_every_construct() {
    let files: Vec<PathBuf> = asl_files(&corpus_dir("valid"))
        .into_iter()
        .filter(|p| !is_included_only(p))
        .collect();
    assert!(
        files.len() >= 8,
        "expected the valid corpus to hold at least 8 agents, found {}",
        files.len()
    );
    let mut failures = String::new();
    let mut coverage = Coverage::default();
    for path in &files {
        let mut map = SourceMap::new();
        match load_agent(path, &mut map) {
            Ok(agent) => {
                for (_, file) in &agent.files {
                    coverage.file(file);
                }
            }
            Err(diags) => {
                let _ = writeln!(
                    failures,
                    "{}: {} diagnostic(s)\n{}",
                    path.display(),
                    diags.len(),
                    render_all(&diags, &map)
                );
            }
        }
    }
    assert!(
        failures.is_empty(),
        "valid agents did not load:\n{failures}"
    );

    let unknown: Vec<&str> = coverage
        .seen
        .iter()
        .copied()
        .filter(|s| !ALL_CONSTRUCTS.contains(s))
        .collect();
    assert!(
        unknown.is_empty(),
        "constructs missing from ALL_CONSTRUCTS: {unknown:?}"
    );
    let missing: Vec<&str> = ALL_CONSTRUCTS
        .iter()
        .copied()
        .filter(|s| !coverage.seen.contains(s))
        .collect();
    assert!(
        missing.is_empty(),
        "the valid corpus does not use these constructs: {missing:?}"
    );
}

/// Every construct the corpus must use: each variant of the tree's enums, then further
/// shapes (labels, goal conditions, sub-plans, includes, ...) that no enum names.
const ALL_CONSTRUCTS: &[&str] = &[
    "Item::Belief",
    "Item::Rule",
    "Item::InitialGoal",
    "Item::Plan",
    "Item::Directive",
    "StepKind::Action",
    "StepKind::Achieve",
    "StepKind::AchieveNewFocus",
    "StepKind::Test",
    "StepKind::AddBel",
    "StepKind::AddBelEnd",
    "StepKind::AddBelNewFocus",
    "StepKind::DelBel",
    "StepKind::DelAddBel",
    "StepKind::DelBelNewFocus",
    "StepKind::Constraint",
    "StepKind::If",
    "StepKind::While",
    "StepKind::For",
    "StepKind::Fork",
    "StepKind::Group",
    "ExprKind::Literal",
    "ExprKind::Var",
    "ExprKind::Int",
    "ExprKind::Float",
    "ExprKind::Str",
    "ExprKind::List",
    "ExprKind::Unary",
    "ExprKind::Arith",
    "ExprKind::Rel",
    "ExprKind::Not",
    "ExprKind::And",
    "ExprKind::Or",
    "ExprKind::PlanTerm",
    "RelOp::Lt",
    "RelOp::Le",
    "RelOp::Gt",
    "RelOp::Ge",
    "RelOp::Eq",
    "RelOp::Ne",
    "RelOp::Unify",
    "RelOp::Univ",
    "ArithOp::Add",
    "ArithOp::Sub",
    "ArithOp::Mul",
    "ArithOp::Div",
    "ArithOp::IntDiv",
    "ArithOp::Mod",
    "ArithOp::Pow",
    "UnaryOp::Neg",
    "UnaryOp::Plus",
    "TriggerOp::Add",
    "TriggerOp::Del",
    "TriggerOp::GoalState",
    "TriggerKind::Belief",
    "TriggerKind::Achieve",
    "TriggerKind::Test",
    "NamespaceKind::Named",
    "NamespaceKind::Var",
    "NamespaceKind::Current",
    "PlanTermKind::Plan",
    "PlanTermKind::Trigger",
    "PlanTermKind::Body",
    "PlanTermKind::Rule",
    "ForkOp::And",
    "ForkOp::Or",
    // Shapes no enum names.
    "label @name",
    "label @name[annots]",
    "label @[annots]",
    "label @Var (plan term)",
    "plan without context",
    "plan with context",
    "plan without body",
    "plan goal condition <:",
    "plan sub-plans",
    "directive include(file)",
    "directive include(file, ns)",
    "directive begin ... end",
    "directive annotations",
    "literal strong negation ~",
    "literal annotations",
    "literal internal action",
    "literal quoted atom",
    "literal true",
    "literal false",
    "var _",
    "var _Named",
    "var annotations",
    "list empty",
    "list nested",
    "list tail var",
    "list tail list",
    "if elif",
    "if else",
    "fork branch of several steps",
    "body empty {}",
];

/// Which constructs the walked trees use.
#[derive(Default)]
struct Coverage {
    seen: BTreeSet<&'static str>,
}

impl Coverage {
    fn see(&mut self, name: &'static str) {
        self.seen.insert(name);
    }

    fn file(&mut self, file: &AgentFile) {
        for item in &file.items {
            self.item(item);
        }
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Belief(b) => {
                self.see("Item::Belief");
                self.literal(&b.literal);
            }
            Item::Rule(r) => {
                self.see("Item::Rule");
                self.rule(r);
            }
            Item::InitialGoal(g) => {
                self.see("Item::InitialGoal");
                self.literal(&g.literal);
            }
            Item::Plan(p) => {
                self.see("Item::Plan");
                self.plan(p);
            }
            Item::Directive(d) => {
                self.see("Item::Directive");
                self.directive(d);
            }
        }
    }

    fn directive(&mut self, d: &Directive) {
        if d.name == "include" {
            match d.args.len() {
                1 => self.see("directive include(file)"),
                2 => self.see("directive include(file, ns)"),
                _ => {}
            }
        }
        if let Some(a) = &d.annots {
            self.see("directive annotations");
            self.list(a);
        }
        for e in &d.args {
            self.expr(e);
        }
        if let Some(block) = &d.block {
            self.see("directive begin ... end");
            for item in block {
                self.item(item);
            }
        }
    }

    fn rule(&mut self, r: &Rule) {
        self.literal(&r.head);
        self.expr(&r.body);
    }

    fn plan(&mut self, p: &Plan) {
        if let Some(l) = &p.label {
            self.label(l);
        }
        self.trigger(&p.trigger);
        match &p.context {
            Some(c) => {
                self.see("plan with context");
                self.expr(c);
            }
            None => self.see("plan without context"),
        }
        if let Some(g) = &p.goal_condition {
            self.see("plan goal condition <:");
            self.expr(g);
        }
        match &p.body {
            Some(b) => self.body(b),
            None => self.see("plan without body"),
        }
        if !p.sub_plans.is_empty() {
            self.see("plan sub-plans");
        }
        for sp in &p.sub_plans {
            self.plan(sp);
        }
    }

    fn label(&mut self, l: &Label) {
        match (&l.name, &l.annots) {
            (None, _) => self.see("label @[annots]"),
            (Some(n), _) if n.starts_with(|c: char| c.is_ascii_uppercase() || c == '_') => {
                self.see("label @Var (plan term)")
            }
            (Some(_), Some(_)) => self.see("label @name[annots]"),
            (Some(_), None) => self.see("label @name"),
        }
        if let Some(a) = &l.annots {
            self.list(a);
        }
    }

    fn trigger(&mut self, t: &Trigger) {
        self.see(match t.op {
            TriggerOp::Add => "TriggerOp::Add",
            TriggerOp::Del => "TriggerOp::Del",
            TriggerOp::GoalState => "TriggerOp::GoalState",
        });
        self.see(match t.kind {
            TriggerKind::Belief => "TriggerKind::Belief",
            TriggerKind::Achieve => "TriggerKind::Achieve",
            TriggerKind::Test => "TriggerKind::Test",
        });
        self.expr(&t.literal);
    }

    fn body(&mut self, b: &Body) {
        if b.steps.is_empty() {
            self.see("body empty {}");
        }
        for s in &b.steps {
            self.step(s);
        }
    }

    fn step(&mut self, s: &Step) {
        match &s.kind {
            StepKind::Action(e) => {
                self.see("StepKind::Action");
                self.expr(e);
            }
            StepKind::Achieve(e) => {
                self.see("StepKind::Achieve");
                self.expr(e);
            }
            StepKind::AchieveNewFocus(e) => {
                self.see("StepKind::AchieveNewFocus");
                self.expr(e);
            }
            StepKind::Test(e) => {
                self.see("StepKind::Test");
                self.expr(e);
            }
            StepKind::AddBel(e) => {
                self.see("StepKind::AddBel");
                self.expr(e);
            }
            StepKind::AddBelEnd(e) => {
                self.see("StepKind::AddBelEnd");
                self.expr(e);
            }
            StepKind::AddBelNewFocus(e) => {
                self.see("StepKind::AddBelNewFocus");
                self.expr(e);
            }
            StepKind::DelBel(e) => {
                self.see("StepKind::DelBel");
                self.expr(e);
            }
            StepKind::DelAddBel(e) => {
                self.see("StepKind::DelAddBel");
                self.expr(e);
            }
            StepKind::DelBelNewFocus(e) => {
                self.see("StepKind::DelBelNewFocus");
                self.expr(e);
            }
            StepKind::Constraint(e) => {
                self.see("StepKind::Constraint");
                self.expr(e);
            }
            StepKind::If {
                branches,
                else_body,
            } => {
                self.see("StepKind::If");
                if branches.len() > 1 {
                    self.see("if elif");
                }
                for (c, b) in branches {
                    self.expr(c);
                    self.body(b);
                }
                if let Some(b) = else_body {
                    self.see("if else");
                    self.body(b);
                }
            }
            StepKind::While { cond, body } => {
                self.see("StepKind::While");
                self.expr(cond);
                self.body(body);
            }
            StepKind::For { cond, body } => {
                self.see("StepKind::For");
                self.expr(cond);
                self.body(body);
            }
            StepKind::Fork { op, branches } => {
                self.see("StepKind::Fork");
                self.see(match op {
                    ForkOp::And => "ForkOp::And",
                    ForkOp::Or => "ForkOp::Or",
                });
                for b in branches {
                    if b.steps.len() > 1 {
                        self.see("fork branch of several steps");
                    }
                    self.body(b);
                }
            }
            StepKind::Group(b) => {
                self.see("StepKind::Group");
                self.body(b);
            }
        }
    }

    fn expr(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Literal(l) => {
                self.see("ExprKind::Literal");
                self.literal(l);
            }
            ExprKind::Var(v) => {
                self.see("ExprKind::Var");
                self.var(v);
            }
            ExprKind::Int(_) => self.see("ExprKind::Int"),
            ExprKind::Float(_) => self.see("ExprKind::Float"),
            ExprKind::Str(_) => self.see("ExprKind::Str"),
            ExprKind::List(l) => {
                self.see("ExprKind::List");
                self.list(l);
            }
            ExprKind::Unary(op, x) => {
                self.see("ExprKind::Unary");
                self.see(match op {
                    UnaryOp::Neg => "UnaryOp::Neg",
                    UnaryOp::Plus => "UnaryOp::Plus",
                });
                self.expr(x);
            }
            ExprKind::Arith(op, a, b) => {
                self.see("ExprKind::Arith");
                self.see(match op {
                    ArithOp::Add => "ArithOp::Add",
                    ArithOp::Sub => "ArithOp::Sub",
                    ArithOp::Mul => "ArithOp::Mul",
                    ArithOp::Div => "ArithOp::Div",
                    ArithOp::IntDiv => "ArithOp::IntDiv",
                    ArithOp::Mod => "ArithOp::Mod",
                    ArithOp::Pow => "ArithOp::Pow",
                });
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Rel(op, a, b) => {
                self.see("ExprKind::Rel");
                self.see(match op {
                    RelOp::Lt => "RelOp::Lt",
                    RelOp::Le => "RelOp::Le",
                    RelOp::Gt => "RelOp::Gt",
                    RelOp::Ge => "RelOp::Ge",
                    RelOp::Eq => "RelOp::Eq",
                    RelOp::Ne => "RelOp::Ne",
                    RelOp::Unify => "RelOp::Unify",
                    RelOp::Univ => "RelOp::Univ",
                });
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Not(x) => {
                self.see("ExprKind::Not");
                self.expr(x);
            }
            ExprKind::And(a, b) => {
                self.see("ExprKind::And");
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Or(a, b) => {
                self.see("ExprKind::Or");
                self.expr(a);
                self.expr(b);
            }
            ExprKind::PlanTerm(pt) => {
                self.see("ExprKind::PlanTerm");
                self.plan_term(pt);
            }
        }
    }

    fn plan_term(&mut self, pt: &PlanTerm) {
        match &pt.kind {
            PlanTermKind::Plan(p) => {
                self.see("PlanTermKind::Plan");
                self.plan(p);
            }
            PlanTermKind::Trigger(t) => {
                self.see("PlanTermKind::Trigger");
                self.trigger(t);
            }
            PlanTermKind::Body(b) => {
                self.see("PlanTermKind::Body");
                self.body(b);
            }
            PlanTermKind::Rule(r) => {
                self.see("PlanTermKind::Rule");
                self.rule(r);
            }
        }
    }

    fn namespace(&mut self, ns: &Namespace) {
        self.see(match ns.kind {
            NamespaceKind::Named(_) => "NamespaceKind::Named",
            NamespaceKind::Var(_) => "NamespaceKind::Var",
            NamespaceKind::Current => "NamespaceKind::Current",
        });
    }

    fn literal(&mut self, l: &Literal) {
        if let Some(ns) = &l.namespace {
            self.namespace(ns);
        }
        if l.negated {
            self.see("literal strong negation ~");
        }
        if l.is_internal_action() {
            self.see("literal internal action");
        }
        if l.functor.starts_with('\'') {
            self.see("literal quoted atom");
        }
        match l.functor.as_str() {
            "true" => self.see("literal true"),
            "false" => self.see("literal false"),
            _ => {}
        }
        for a in &l.args {
            self.expr(a);
        }
        if let Some(a) = &l.annots {
            self.see("literal annotations");
            self.list(a);
        }
    }

    fn var(&mut self, v: &Var) {
        if let Some(ns) = &v.namespace {
            self.namespace(ns);
        }
        if v.negated {
            self.see("literal strong negation ~");
        }
        if v.name == "_" {
            self.see("var _");
        } else if v.name.starts_with('_') {
            self.see("var _Named");
        }
        if let Some(a) = &v.annots {
            self.see("var annotations");
            self.list(a);
        }
    }

    fn list(&mut self, l: &ListExpr) {
        if l.elems.is_empty() && l.tail.is_none() {
            self.see("list empty");
        }
        if l.elems.iter().any(|e| matches!(e.kind, ExprKind::List(_))) {
            self.see("list nested");
        }
        for e in &l.elems {
            self.expr(e);
        }
        if let Some(t) = &l.tail {
            match &t.kind {
                ExprKind::Var(_) => self.see("list tail var"),
                ExprKind::List(_) => self.see("list tail list"),
                _ => {}
            }
            self.expr(t);
        }
    }
}

// ----- (b) the invalid corpus --------------------------------------------------------------

/// One `// expect: LINE:COLUMN substring` line of an invalid file's header.
#[derive(Debug)]
struct Expected {
    line: usize,
    column: usize,
    substring: String,
}

fn expectations(path: &Path) -> Vec<Expected> {
    let text = read(path);
    let mut out = Vec::new();
    // Only the header counts: the comment lines the file starts with.
    let header = text
        .lines()
        .enumerate()
        .take_while(|(_, l)| l.trim_start().starts_with("//"));
    for (i, raw) in header {
        let Some(rest) = raw.trim_start().strip_prefix(EXPECT) else {
            continue;
        };
        let rest = rest.trim_start();
        let (place, substring) = rest.split_once(' ').unwrap_or((rest, ""));
        let parsed = place
            .split_once(':')
            .and_then(|(l, c)| Some((l.parse().ok()?, c.parse().ok()?)));
        let Some((line, column)) = parsed else {
            panic!(
                "{}:{}: malformed expectation, want `{EXPECT} LINE:COLUMN message`",
                path.display(),
                i + 1
            );
        };
        out.push(Expected {
            line,
            column,
            substring: substring.trim().to_string(),
        });
    }
    out
}

/// Checks one invalid file; returns what went wrong (nothing when it behaves).
fn check_invalid(path: &Path) -> Vec<String> {
    let expected = expectations(path);
    let mut problems = Vec::new();
    if expected.is_empty() {
        problems.push(format!("no `{EXPECT}` line"));
        return problems;
    }
    let mut map = SourceMap::new();
    let diags = match load_agent(path, &mut map) {
        Ok(_) => {
            problems.push("loaded without any diagnostic".into());
            return problems;
        }
        Err(d) => d,
    };
    let name = path.display().to_string();
    if diags.len() != expected.len() {
        problems.push(format!(
            "expected {} diagnostic(s), got {}",
            expected.len(),
            diags.len()
        ));
    }
    let mut used = vec![false; diags.len()];
    for exp in &expected {
        let hit = diags.iter().enumerate().position(|(i, d)| {
            !used[i]
                && d.location(&map).is_some_and(|loc| {
                    loc.file == name && loc.line == exp.line && loc.column == exp.column
                })
                && d.message.contains(&exp.substring)
        });
        match hit {
            Some(i) => used[i] = true,
            None => problems.push(format!(
                "no diagnostic at {}:{} containing {:?}",
                exp.line, exp.column, exp.substring
            )),
        }
    }
    check_rendering(&diags, &map, &mut problems);
    if !problems.is_empty() {
        problems.push(format!("actual diagnostics:\n{}", render_all(&diags, &map)));
    }
    problems
}

#[test]
fn invalid_corpus_yields_exactly_the_expected_diagnostics() {
    let files: Vec<PathBuf> = asl_files(&corpus_dir("invalid"))
        .into_iter()
        .filter(|p| !is_included_only(p))
        .collect();
    assert!(
        files.len() >= 15,
        "expected at least 15 invalid agents, found {}",
        files.len()
    );
    let mut report = String::new();
    for path in &files {
        let problems = check_invalid(path);
        if !problems.is_empty() {
            let _ = writeln!(report, "== {}", path.display());
            for p in problems {
                let _ = writeln!(report, "  {p}");
            }
        }
    }
    assert!(report.is_empty(), "{report}");
}

#[test]
fn a_file_with_three_errors_reports_all_three() {
    let path = corpus_dir("invalid").join("three_errors.asl");
    assert_eq!(expectations(&path).len(), 3);
    let mut map = SourceMap::new();
    let diags = load_agent(&path, &mut map).expect_err("three_errors.asl must not load");
    assert_eq!(diags.len(), 3, "{}", render_all(&diags, &map));
}

// ----- (c) Jason's own examples ------------------------------------------------------------

#[test]
fn jason_examples_parse_unchanged() {
    // A checkout of jason-lang/jason (`BDI_CHECK_JASON=/path/to/jason`), or a copy of its
    // examples in the old place. Every `.asl` loads with its includes resolved as Jason
    // resolves them: beside the file, then along `jason_source_path`.
    let root = std::env::var_os("BDI_CHECK_JASON").map(PathBuf::from);
    let dirs: Vec<PathBuf> = match &root {
        Some(r) => vec![r.clone()],
        None => JASON_DIRS.iter().map(PathBuf::from).collect(),
    };
    let mut report = String::new();
    let mut checked = 0;
    for dir in dirs.iter().filter(|d| d.is_dir()) {
        for path in asl_files(dir) {
            checked += 1;
            let source_path = jason_source_path(dir, &path);
            let mut map = SourceMap::new();
            if let Err(diags) = load_agent_with(&path, &mut map, &source_path) {
                let _ = writeln!(report, "{}", render_all(&diags, &map));
            }
        }
    }
    if checked > 0 {
        eprintln!("parsed {checked} Jason agents");
    }
    assert!(report.is_empty(), "Jason's agents did not load:\n{report}");
}

// ----- (d) Jason's example agents in `verify` ----------------------------------------------

/// What README.md says this test measures; the numbers follow it (`N of the M example and
/// demo agents`). The README holds the figure and the test reads it from there, so there
/// is one copy of it and the test fails when the text and the measurement disagree.
const README_CLAIM: &str = "Given a PDDL stub of their actions,";

/// The search bounds of each run: enough to load the agent and run its reasoning cycle,
/// not to finish (a cut-short search is exit 3, which counts as accepted).
const VERIFY_ARGS: &[&str] = &["--max-states", "2000", "--timeout", "10", "--threads", "1"];

/// How long one `verify` may take before the test gives up on it (the bounds above end it
/// long before, unless something hangs).
const VERIFY_WALL: std::time::Duration = std::time::Duration::from_secs(120);

#[test]
fn jason_examples_in_verify_match_the_readme() {
    // Every agent of the checkout's `examples/` and `demos/` gets a generated project (a
    // PDDL stub of its environment, see `Stub`) and goes through `bdi-check verify`: it is
    // accepted when it loads and runs (exit 0, 1 or 3), refused with exit 2.
    let Some(root) = std::env::var_os("BDI_CHECK_JASON").map(PathBuf::from) else {
        return;
    };
    let agents = jason_agents(&root);
    assert!(
        !agents.is_empty(),
        "no agents under {}/examples and demos",
        root.display()
    );
    // Where tests/common's `temp_dir` puts its folders (and sweeps them once they end).
    let work = std::env::temp_dir()
        .join("bdi-check-tests")
        .join(std::process::id().to_string())
        .join("jason-verify");
    let _ = std::fs::remove_dir_all(&work);
    let started = std::time::Instant::now();
    let mut accepted = Vec::new();
    let mut refused: Vec<(PathBuf, String)> = Vec::new();
    let mut broken = String::new();
    for (i, path) in agents.iter().enumerate() {
        let rel = path.strip_prefix(&root).unwrap_or(path);
        let dir = work.join(format!("{i:03}"));
        let source_path = jason_source_path(&root, path);
        std::fs::create_dir_all(&dir).unwrap();
        let mut map = SourceMap::new();
        let agent = load_agent_with(path, &mut map, &source_path).unwrap_or_else(|d| {
            panic!(
                "{} does not parse:\n{}",
                rel.display(),
                render_all(&d, &map)
            )
        });
        let stub = Stub::of(&agent);
        std::fs::write(dir.join("stub.pddl"), stub.pddl(rel)).unwrap();
        std::fs::write(
            dir.join("bdi-check.toml"),
            stub.manifest(rel, path, &source_path),
        )
        .unwrap();
        match run_verify(&dir) {
            Ok((code @ (0 | 1 | 3), _)) => accepted.push((rel.to_path_buf(), code)),
            Ok((2, message)) => refused.push((rel.to_path_buf(), message)),
            Ok((code, message)) => {
                let _ = writeln!(
                    broken,
                    "{} (project {}): exit {code}: {message}",
                    rel.display(),
                    dir.display()
                );
            }
            Err(e) => {
                let _ = writeln!(broken, "{} (project {}): {e}", rel.display(), dir.display());
            }
        }
    }

    // The table: the accepted agents, then the refusals grouped by reason, most common first.
    let mut groups: Vec<(String, Vec<&PathBuf>)> = Vec::new();
    for (path, message) in &refused {
        let reason = refusal_reason(message);
        match groups.iter_mut().find(|(r, _)| *r == reason) {
            Some((_, paths)) => paths.push(path),
            None => groups.push((reason, vec![path])),
        }
    }
    groups.sort_by(|a, b| b.1.len().cmp(&a.1.len()).then_with(|| a.0.cmp(&b.0)));
    let mut table = format!(
        "{} of {} agents accepted by `verify` ({:.1}s)\n",
        accepted.len(),
        agents.len(),
        started.elapsed().as_secs_f64()
    );
    for (p, code) in &accepted {
        let _ = writeln!(table, "  accepted (exit {code})  {}", p.display());
    }
    let _ = writeln!(table, "{} refused:", refused.len());
    for (reason, paths) in &groups {
        let _ = writeln!(table, "  {:3}  {reason}", paths.len());
        for p in paths {
            let _ = writeln!(table, "         {}", p.display());
        }
    }
    eprint!("{table}");
    for (path, message) in &refused {
        eprintln!("refused {}: {message}", path.display());
    }
    assert!(
        broken.is_empty(),
        "bdi-check did not answer properly:\n{broken}"
    );

    let readme = read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"));
    let (said, of) = readme_claim(&readme).unwrap_or_else(|| {
        panic!("README.md has no `{README_CLAIM} N of the M example and demo agents`")
    });
    assert_eq!(
        (said, of),
        (accepted.len(), agents.len()),
        "README.md says {said} of the {of} agents load in `verify`; measured {} of {}: update README.md (the projects are in {})",
        accepted.len(),
        agents.len(),
        work.display()
    );
    let _ = std::fs::remove_dir_all(&work);
}

/// The README's claim about Jason's projects of several agents.
const README_MAS_CLAIM: &str = "Given a PDDL stub of their shared environment,";

#[test]
fn jason_projects_in_verify_match_the_readme() {
    // Every `.mas2j` of the checkout's `examples/` and `demos/` gets a generated project
    // (`mas = ` the file itself, and a PDDL stub of what all its agents call and read) and
    // goes through `bdi-check verify`, as the agents one by one do above.
    let Some(root) = std::env::var_os("BDI_CHECK_JASON").map(PathBuf::from) else {
        return;
    };
    let mut projects: Vec<PathBuf> = ["examples", "demos"]
        .iter()
        .map(|d| root.join(d))
        .flat_map(|d| mas2j_files(&d))
        .collect();
    projects.sort();
    assert!(!projects.is_empty(), "no .mas2j under {}", root.display());
    let work = std::env::temp_dir()
        .join("bdi-check-tests")
        .join(std::process::id().to_string())
        .join("jason-mas-verify");
    let _ = std::fs::remove_dir_all(&work);
    let mut accepted = Vec::new();
    let mut refused: Vec<(PathBuf, String)> = Vec::new();
    let mut broken = String::new();
    for (i, path) in projects.iter().enumerate() {
        let rel = path.strip_prefix(&root).unwrap_or(path);
        let dir = work.join(format!("{i:03}"));
        std::fs::create_dir_all(&dir).unwrap();
        // The agents as bdi-check finds them (a project it cannot read is refused by
        // `verify` itself, with its place).
        let mut map = SourceMap::new();
        let text = read(path);
        let id = map.add(path, path.display().to_string(), text.clone());
        let folder = path.parent().unwrap_or(&root);
        let agents: Vec<bdi_check::syntax::LoadedAgent> =
            match bdi_check::syntax::mas2j::parse_mas2j(id, &text) {
                Ok(p) => p
                    .agents
                    .iter()
                    .filter_map(|a| {
                        let f = std::iter::once(folder.join(&a.source))
                            .chain(
                                p.source_path
                                    .iter()
                                    .map(|sp| folder.join(sp).join(&a.source)),
                            )
                            .find(|f| f.is_file())?;
                        load_agent_with(&f, &mut map, &jason_source_path(&root, &f)).ok()
                    })
                    .collect(),
                Err(_) => Vec::new(),
            };
        let stub = Stub::of_all(&agents);
        std::fs::write(dir.join("stub.pddl"), stub.pddl(rel)).unwrap();
        let manifest = stub
            .manifest(rel, path, &jason_source_path(&root, path))
            .replacen("plans = ", "mas = ", 1);
        std::fs::write(dir.join("bdi-check.toml"), manifest).unwrap();
        match run_verify(&dir) {
            Ok((code @ (0 | 1 | 3), _)) => accepted.push((rel.to_path_buf(), code)),
            Ok((2, message)) => refused.push((rel.to_path_buf(), message)),
            Ok((code, message)) => {
                let _ = writeln!(broken, "{}: exit {code}: {message}", rel.display());
            }
            Err(e) => {
                let _ = writeln!(broken, "{}: {e}", rel.display());
            }
        }
    }
    let mut groups: Vec<(String, usize)> = Vec::new();
    for (_, message) in &refused {
        let reason = refusal_reason(message);
        match groups.iter_mut().find(|(r, _)| *r == reason) {
            Some((_, n)) => *n += 1,
            None => groups.push((reason, 1)),
        }
    }
    groups.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    eprintln!(
        "{} of {} projects accepted by `verify`",
        accepted.len(),
        projects.len()
    );
    for (p, code) in &accepted {
        eprintln!("  accepted (exit {code})  {}", p.display());
    }
    for (reason, n) in &groups {
        eprintln!("  {n:3}  {reason}");
    }
    for (path, message) in &refused {
        eprintln!("refused {}: {message}", path.display());
    }
    assert!(
        broken.is_empty(),
        "bdi-check did not answer properly:\n{broken}"
    );
    let readme = read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"));
    let text = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let claim = text
        .find(README_MAS_CLAIM)
        .map(|i| &text[i + README_MAS_CLAIM.len()..])
        .and_then(|rest| {
            let w: Vec<&str> = rest.split_whitespace().take(4).collect();
            match w.as_slice() {
                [n, "of", "the", m] => Some((n.parse::<usize>().ok()?, m.parse::<usize>().ok()?)),
                _ => None,
            }
        })
        .unwrap_or_else(|| panic!("README.md has no `{README_MAS_CLAIM} N of the M`"));
    assert_eq!(
        claim,
        (accepted.len(), projects.len()),
        "README.md's count of Jason projects is not the one measured (projects in {})",
        work.display()
    );
    let _ = std::fs::remove_dir_all(&work);
}

/// Every `.mas2j` under `dir`.
fn mas2j_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(mas2j_files(&p));
        } else if p.extension().is_some_and(|x| x == "mas2j") {
            out.push(p);
        }
    }
    out
}

/// The source path Jason would give `path`: the folders above it up to the checkout (a
/// project's `aslSourcePath`), then what `$jasonJar/...` names: the jar's sources
/// (`src/main/resources`, `src` of the interpreter) and the folder Jason's own test agents
/// take `tester_agent.asl` from (the source path its unit-test runner sets).
fn jason_source_path(root: &Path, path: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = path
        .ancestors()
        .skip(1)
        .take_while(|a| a.starts_with(root))
        .map(Path::to_path_buf)
        .collect();
    out.extend(
        [
            "jason-interpreter/src/main/resources",
            "jason-interpreter/src",
            "jason-interpreter/src/test/jason/inc",
        ]
        .iter()
        .map(|p| root.join(p))
        .filter(|p| p.is_dir()),
    );
    out
}

/// The agents of `examples/` and `demos/`: every `.asl` there but those another one
/// includes (`{ include("f.asl") }`, or `.include("f.asl")` at run time). Jason's projects
/// name their agents in `.mas2j` files, which bdi-check does not read; in this checkout
/// every file some other includes is a library of plans and no agent of a project.
fn jason_agents(root: &Path) -> Vec<PathBuf> {
    let files: Vec<PathBuf> = ["examples", "demos"]
        .iter()
        .map(|d| root.join(d))
        .filter(|d| d.is_dir())
        .flat_map(|d| asl_files(&d))
        .collect();
    let mut included = BTreeSet::new();
    for path in &files {
        let mut map = SourceMap::new();
        let Ok(agent) = load_agent_with(path, &mut map, &jason_source_path(root, path)) else {
            continue; // `jason_examples_parse_unchanged` reports it
        };
        for inc in &agent.included {
            included.insert(canonical(&map.file(inc.file).path));
        }
        let dir = path.parent().unwrap_or(root);
        for name in Stub::of(&agent).runtime_includes {
            included.insert(canonical(&dir.join(name)));
        }
    }
    files
        .into_iter()
        .filter(|p| !included.contains(&canonical(p)))
        .collect()
}

fn canonical(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| p.to_path_buf())
}

/// Runs `bdi-check verify` on the project in `dir`: the exit code, and the first error's
/// message (exit 2) or the start of stderr (an unexpected exit).
fn run_verify(dir: &Path) -> Result<(i32, String), String> {
    let report = dir.join("report.json");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_bdi-check"))
        .arg("verify")
        .arg(dir)
        .args(["--format", "json", "-o"])
        .arg(&report)
        .args(VERIFY_ARGS)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run bdi-check: {e}"))?;
    let started = std::time::Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().map_err(|e| e.to_string())? {
            break s;
        }
        if started.elapsed() > VERIFY_WALL {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("no answer in {}s", VERIFY_WALL.as_secs()));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = std::io::Read::read_to_string(&mut e, &mut stderr);
    }
    let Some(code) = status.code() else {
        return Err(format!("killed by a signal ({status}): {stderr}"));
    };
    let first_error = std::fs::read_to_string(&report)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|r| {
            r["findings"].as_array()?.iter().find_map(|f| {
                (f["severity"] == "error" && f["check"] == "input")
                    .then(|| f["message"].as_str().map(str::to_string))
                    .flatten()
            })
        });
    let message = match first_error {
        Some(m) if code == 2 => m,
        _ => stderr.lines().take(3).collect::<Vec<_>>().join(" | "),
    };
    Ok((code, message))
}

/// A refusal's reason, for grouping: an unmodelled internal action or function of Jason's
/// by its name (a library's by its package, `.set.*`), the project's own (written in Java,
/// no dot in front) together, and any other message with the names in backquotes left out.
fn refusal_reason(message: &str) -> String {
    const OWN: &str = "internal actions and functions in Java of the agent's own project";
    if let Some(rest) = message.strip_prefix("internal action `") {
        let name = rest.split('`').next().unwrap_or_default();
        return match name.strip_prefix('.') {
            Some(n) => match n.split_once('.') {
                Some((lib, _)) => format!("internal action `.{lib}.*`"),
                None => format!("internal action `{name}`"),
            },
            None => OWN.to_string(),
        };
    }
    if let Some((name, _)) = message
        .strip_prefix('`')
        .and_then(|m| m.split_once("` is not an arithmetic function"))
    {
        return if name.starts_with("math.") || name == "system.time" {
            format!("function `{name}`")
        } else {
            OWN.to_string()
        };
    }
    let mut out = String::new();
    for (i, part) in message.split('`').enumerate() {
        out.push_str(if i % 2 == 0 { part } else { "…" });
    }
    // The explanation after the colon is the same for every name.
    match out.split_once(": ") {
        Some((reason, _)) => reason.to_string(),
        None => out,
    }
}

/// `N` and `M` of README's `Given a PDDL stub of their actions, N of the M example and demo
/// agents`, whatever the line breaks.
fn readme_claim(readme: &str) -> Option<(usize, usize)> {
    let text = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let rest = &text[text.find(README_CLAIM)? + README_CLAIM.len()..];
    let words: Vec<&str> = rest.split_whitespace().take(6).collect();
    match words.as_slice() {
        [n, "of", "the", m, "example", "and"] => Some((n.parse().ok()?, m.parse().ok()?)),
        _ => None,
    }
}

/// A stub of an agent's environment, read off its plans: what a project needs for
/// `verify` to load the agent, and nothing that would hide a construct bdi-check refuses.
///
/// * every environment action its plans call, by name and with the arity of its first
///   call, its parameters of type `object`, always possible and changing nothing;
/// * every belief it reads (in a context, a rule, a condition, a trigger, a `.findall`,
///   `.count` or `.wait`) but never adds itself: in Jason those come from the environment,
///   so the stub declares them as PDDL predicates (percepts, false in every state);
///   strongly negated `~p` gives `p` (unless `p` is a mental note); a belief only tested
///   (`?b`) or deleted is left undeclared, as bdi-check does not need it to load;
/// * an object for every atom in an argument of a belief, goal, rule or action, and
///   `[bounds] numbers` spanning the integers there (`[bounds] random`, a few values, when
///   a plan draws a random number);
/// * `[requests]`: the goals it has plans for but never posts itself (in Jason another
///   agent or the user asks for them), at most one per run. Initial goals are the agent's.
#[derive(Default)]
struct Stub {
    /// Environment actions, name and arity, in order of first call.
    actions: Vec<(String, usize)>,
    /// Beliefs read (`~p` for a strongly negated one), name and arity, first read first.
    reads: Vec<(String, usize)>,
    /// Beliefs the agent adds (or believes initially).
    added: BTreeSet<String>,
    /// Rule heads.
    rules: BTreeSet<String>,
    /// Goals with a `+!g` plan, in order.
    handled: Vec<(String, usize)>,
    /// Goals the agent posts itself (subgoals, initial goals).
    posted: BTreeSet<(String, usize)>,
    objects: BTreeSet<String>,
    /// The least and greatest integer argument.
    ints: Option<(i64, i64)>,
    /// Files loaded by `.include("f.asl")`.
    runtime_includes: Vec<String>,
    /// Whether a plan draws a random number (`.random(X)`, not from a list).
    random: bool,
}

impl Stub {
    fn of(agent: &bdi_check::syntax::LoadedAgent) -> Stub {
        let mut s = Stub::default();
        for item in agent.items() {
            s.item(item);
        }
        s
    }

    /// The stub of the environment several agents share: what any of them calls, reads,
    /// adds or posts. Requests are the first agent's goals that no agent posts.
    fn of_all(agents: &[bdi_check::syntax::LoadedAgent]) -> Stub {
        let mut s = Stub::default();
        for a in agents {
            for item in a.items() {
                s.item(item);
            }
        }
        let first = agents.first().map(Stub::of).unwrap_or_default();
        s.handled = first.handled;
        s
    }

    /// The PDDL domain.
    fn pddl(&self, agent: &Path) -> String {
        let params = |n: usize| -> String { (1..=n).map(|i| format!(" ?x{i} - object")).collect() };
        let mut out = format!(
            ";; A stub of the environment of {} (generated by tests/suite/corpus.rs): the actions it\n\
             ;; calls, always possible and changing nothing; the beliefs it reads and never adds.\n\
             (define (domain stub)\n  (:requirements :strips :typing)\n",
            agent.display()
        );
        let percepts = self.percepts();
        if !percepts.is_empty() {
            out.push_str("  (:predicates");
            for (name, n) in &percepts {
                let _ = write!(out, "\n    ({name}{})", params(*n));
            }
            out.push_str(")\n");
        }
        for (name, n) in &self.actions {
            let _ = writeln!(
                out,
                "  (:action {name} :parameters ({}) :precondition (and) :effect (and))",
                params(*n).trim_start()
            );
        }
        out.push_str(")\n");
        out
    }

    /// `bdi-check.toml`, for the agent at `path` (absolute; `rel` names it).
    fn manifest(&self, rel: &Path, path: &Path, source_path: &[PathBuf]) -> String {
        let list = |items: &mut dyn Iterator<Item = String>| -> String {
            items
                .map(|s| format!("{s:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut out = format!(
            "# A stub project for {} (generated by tests/suite/corpus.rs).\n\n[agent]\nplans = {:?}\nactions = \"stub.pddl\"\nsource_path = [{}]\n",
            rel.display(),
            path.display().to_string(),
            list(&mut source_path.iter().map(|p| p.display().to_string()))
        );
        if !self.objects.is_empty() {
            let _ = write!(
                out,
                "\n[objects]\nobject = [{}]\n",
                list(&mut self.objects.iter().cloned())
            );
        }
        let requests: Vec<String> = self
            .handled
            .iter()
            .filter(|g| !self.posted.contains(g))
            .map(|(name, n)| {
                if *n == 0 {
                    name.clone()
                } else {
                    let vars: Vec<String> = (1..=*n).map(|i| format!("X{i}")).collect();
                    format!("{name}({})", vars.join(", "))
                }
            })
            .collect();
        let _ = write!(
            out,
            "\n[requests]\ngoals = [{}]\nmax = {}\narrival = \"idle\"\n",
            list(&mut requests.iter().cloned()),
            usize::from(!requests.is_empty())
        );
        if self.ints.is_some() || self.random {
            out.push_str("\n[bounds]\n");
        }
        if let Some((lo, hi)) = self.ints {
            // The widest range bdi-check takes: a number beyond it is refused by bdi-check
            // itself, where the agent has it.
            let hi = hi.min(lo + bdi_check::syntax::manifest::MAX_NUMBERS - 1);
            let _ = writeln!(out, "numbers = [{lo}, {hi}]");
        }
        if self.random {
            // What `.random(X)` may give: the model needs a few values, any will load.
            out.push_str("random = [0.0, 0.5, 0.9]\n");
        }
        out
    }

    /// The beliefs the stub declares as PDDL predicates.
    fn percepts(&self) -> Vec<(String, usize)> {
        let mut out: Vec<(String, usize)> = Vec::new();
        for (name, n) in &self.reads {
            let base = name.trim_start_matches('~');
            let skip = self.added.contains(name)
                || self.rules.contains(name)
                || (base != name && (self.added.contains(base) || self.rules.contains(base)))
                || base.starts_with('\'');
            if !skip && !out.iter().any(|(p, _)| p == base) {
                out.push((base.to_string(), *n));
            }
        }
        out
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Belief(b) => {
                self.added.insert(b.literal.belief_name().into_owned());
                self.args(&b.literal, true);
            }
            Item::Rule(r) => self.rule(r),
            Item::InitialGoal(g) => {
                self.posted
                    .insert((g.literal.functor.clone(), g.literal.args.len()));
                self.args(&g.literal, false);
            }
            Item::Plan(p) => self.plan(p),
            Item::Directive(_) => {}
        }
    }

    fn rule(&mut self, r: &Rule) {
        self.rules.insert(r.head.belief_name().into_owned());
        self.args(&r.head, false);
        self.formula(&r.body, true);
    }

    fn plan(&mut self, p: &Plan) {
        self.trigger(&p.trigger);
        for c in [&p.context, &p.goal_condition].into_iter().flatten() {
            self.formula(c, true);
        }
        if let Some(b) = p.jason_body() {
            self.body(&b);
        }
        for sp in &p.sub_plans {
            self.plan(sp);
        }
    }

    fn trigger(&mut self, t: &Trigger) {
        let ExprKind::Literal(l) = &t.literal.kind else {
            return;
        };
        match t.kind {
            TriggerKind::Achieve if t.op == TriggerOp::Add => {
                let g = (l.functor.clone(), l.args.len());
                if !self.handled.contains(&g) {
                    self.handled.push(g);
                }
            }
            TriggerKind::Belief => self.read(l),
            _ => {}
        }
        self.args(l, t.kind == TriggerKind::Belief);
    }

    fn body(&mut self, b: &Body) {
        for s in &b.steps {
            self.step(s);
        }
    }

    fn step(&mut self, s: &Step) {
        let lit = |e: &Expr| match &e.kind {
            ExprKind::Literal(l) => Some(l.clone()),
            _ => None,
        };
        match &s.kind {
            StepKind::Action(e) => match lit(e) {
                Some(l) if l.is_internal_action() => self.internal(&l),
                Some(l) => {
                    if !self.actions.iter().any(|(a, _)| *a == l.functor) {
                        self.actions.push((l.functor.clone(), l.args.len()));
                    }
                    self.args(&l, true);
                }
                None => {}
            },
            StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => {
                if let Some(l) = lit(e) {
                    self.posted.insert((l.functor.clone(), l.args.len()));
                    self.args(&l, false);
                }
            }
            StepKind::Test(e) => self.formula(e, false),
            StepKind::AddBel(e)
            | StepKind::AddBelEnd(e)
            | StepKind::AddBelNewFocus(e)
            | StepKind::DelAddBel(e) => match lit(e) {
                Some(l) => {
                    self.added.insert(l.belief_name().into_owned());
                    self.args(&l, true);
                }
                None => self.term(e),
            },
            StepKind::DelBel(e) | StepKind::DelBelNewFocus(e) => match lit(e) {
                Some(l) => self.args(&l, true),
                None => self.term(e),
            },
            StepKind::Constraint(e) => self.formula(e, true),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    self.formula(c, true);
                    self.body(b);
                }
                if let Some(b) = else_body {
                    self.body(b);
                }
            }
            StepKind::While { cond, body } | StepKind::For { cond, body } => {
                self.formula(cond, true);
                self.body(body);
            }
            StepKind::Fork { branches, .. } => branches.iter().for_each(|b| self.body(b)),
            StepKind::Group(b) => self.body(b),
        }
    }

    /// A logical formula; `reading`: its literals are belief queries (not in a test goal).
    fn formula(&mut self, e: &Expr, reading: bool) {
        match &e.kind {
            ExprKind::Literal(l) if l.is_internal_action() => self.internal(l),
            ExprKind::Literal(l) if matches!(l.functor.as_str(), "true" | "false") => {}
            ExprKind::Literal(l) => {
                if reading {
                    self.read(l);
                }
                self.args(l, true);
            }
            ExprKind::Not(x) => self.formula(x, reading),
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                self.formula(a, reading);
                self.formula(b, reading);
            }
            _ => self.term(e),
        }
    }

    /// A term: only the queries and plans inside it matter.
    fn term(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Literal(l) if l.functor == ".count" && l.args.len() == 1 => {
                self.formula(&l.args[0], true)
            }
            ExprKind::Literal(l) if l.is_internal_action() => {
                l.args.iter().for_each(|a| self.term(a))
            }
            ExprKind::Literal(l) => l.args.iter().for_each(|a| self.term(a)),
            ExprKind::List(le) => {
                le.elems.iter().for_each(|a| self.term(a));
                if let Some(t) = &le.tail {
                    self.term(t);
                }
            }
            ExprKind::Unary(_, a) | ExprKind::Not(a) => self.term(a),
            ExprKind::Arith(_, a, b)
            | ExprKind::Rel(_, a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b) => {
                self.term(a);
                self.term(b);
            }
            ExprKind::PlanTerm(pt) => match &pt.kind {
                PlanTermKind::Plan(p) => self.plan(p),
                PlanTermKind::Trigger(t) => self.trigger(t),
                PlanTermKind::Body(b) => self.body(b),
                PlanTermKind::Rule(r) => self.rule(r),
            },
            ExprKind::Var(_) | ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) => {}
        }
    }

    /// An internal action: the queries among its arguments are reads.
    fn internal(&mut self, l: &Literal) {
        match (l.functor.as_str(), l.args.as_slice()) {
            // What one agent tells another is a belief the receiver has (not a percept);
            // what it asks to achieve, a goal posted.
            (".send", [_, ilf, c, ..]) | (".broadcast", [ilf, c]) => {
                let performative = match &ilf.kind {
                    ExprKind::Literal(p) => p.functor.as_str(),
                    _ => "",
                };
                if let ExprKind::Literal(c) = &c.kind {
                    match performative {
                        "tell" => {
                            self.added.insert(c.belief_name().into_owned());
                        }
                        "achieve" => {
                            self.posted.insert((c.functor.clone(), c.args.len()));
                        }
                        _ => {}
                    }
                }
                l.args.iter().for_each(|a| self.term(a));
            }
            (".findall", [t, q, r]) => {
                self.term(t);
                self.formula(q, true);
                self.term(r);
            }
            (".count", [q, n]) => {
                self.formula(q, true);
                self.term(n);
            }
            (".wait", args) => {
                for a in args {
                    match &a.kind {
                        ExprKind::Literal(_)
                        | ExprKind::Not(_)
                        | ExprKind::And(..)
                        | ExprKind::Or(..)
                        | ExprKind::Rel(..) => self.formula(a, true),
                        _ => self.term(a),
                    }
                }
            }
            (".random", [x, rest @ ..]) => {
                self.random |= !matches!(x.kind, ExprKind::List(_));
                self.term(x);
                rest.iter().for_each(|a| self.term(a));
            }
            (".include", [f, ..]) => {
                if let ExprKind::Str(name) = &f.kind {
                    self.runtime_includes.push(name.clone());
                }
            }
            (_, args) => args.iter().for_each(|a| self.term(a)),
        }
    }

    fn read(&mut self, l: &Literal) {
        let name = l.belief_name();
        if !self.reads.iter().any(|(r, _)| *r == name) {
            self.reads.push((name.into_owned(), l.args.len()));
        }
    }

    /// The arguments of a belief, goal, rule head or action: their atoms are objects, also
    /// inside lists and structures (from where the plans may pass them to an action); an
    /// integer widens the numbers where bdi-check wants objects (`strict`: beliefs and
    /// actions; a goal's or rule's argument may be any term).
    fn args(&mut self, l: &Literal, strict: bool) {
        for a in &l.args {
            match &a.kind {
                ExprKind::Int(i) if strict => self.int(*i),
                ExprKind::Unary(UnaryOp::Neg, x) if strict => {
                    if let ExprKind::Int(i) = x.kind {
                        self.int(-i);
                    }
                }
                _ => {
                    self.atoms_in(a);
                    self.term(a);
                }
            }
        }
    }

    fn atoms_in(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Literal(x) if x.is_internal_action() || x.functor.starts_with('\'') => {}
            ExprKind::Literal(x)
                if x.args.is_empty()
                    && x.annots.is_none()
                    && !x.negated
                    && !matches!(x.functor.as_str(), "true" | "false") =>
            {
                self.objects.insert(x.functor.clone());
            }
            ExprKind::Literal(x) => x.args.iter().for_each(|a| self.atoms_in(a)),
            ExprKind::List(le) => {
                le.elems.iter().for_each(|a| self.atoms_in(a));
                if let Some(t) = &le.tail {
                    self.atoms_in(t);
                }
            }
            _ => {}
        }
    }

    fn int(&mut self, i: i64) {
        self.ints = Some(match self.ints {
            Some((lo, hi)) => (lo.min(i), hi.max(i)),
            None => (i, i),
        });
    }
}
