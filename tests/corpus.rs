//! The AgentSpeak test corpus under `tests/asl/`.
//!
//! * `valid/`: every agent loads with no diagnostic, and the corpus as a whole uses every
//!   variant of the syntax tree (and a list of further constructs), so "the corpus covers
//!   every construct" is checked, not promised.
//! * `invalid/`: every file yields exactly the diagnostics its header announces, one
//!   `// expect: LINE:COLUMN <substring of the message>` line per diagnostic (line and
//!   column 1-based, in the file itself).
//! * Jason's own example agents, when a copy is present at `/tmp/jason/asl`, parse unchanged.
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
    // resolves them: beside the file, then along a source path (the folders above it, up
    // to the checkout, as a project's `aslSourcePath` would give), and `$jasonJar/...`
    // from the jar's sources (`src/main/resources`, `src` of the interpreter).
    let root = std::env::var_os("BDI_CHECK_JASON").map(PathBuf::from);
    let dirs: Vec<PathBuf> = match &root {
        Some(r) => vec![r.clone()],
        None => JASON_DIRS.iter().map(PathBuf::from).collect(),
    };
    let mut report = String::new();
    let mut checked = 0;
    for dir in dirs.iter().filter(|d| d.is_dir()) {
        // The jar's sources, and the folder Jason's own test agents take `tester_agent.asl`
        // from (the source path its unit-test runner sets).
        let jar: Vec<PathBuf> = [
            "jason-interpreter/src/main/resources",
            "jason-interpreter/src",
            "jason-interpreter/src/test/jason/inc",
        ]
        .iter()
        .map(|p| dir.join(p))
        .filter(|p| p.is_dir())
        .collect();
        for path in asl_files(dir) {
            checked += 1;
            let mut source_path: Vec<PathBuf> = path
                .ancestors()
                .skip(1)
                .take_while(|a| a.starts_with(dir))
                .map(Path::to_path_buf)
                .collect();
            source_path.extend(jar.iter().cloned());
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
