//! The validation context and what every section is read with: TOML values checked for their
//! type and range, unknown and duplicate keys, and formulas parsed from strings. Every error is
//! collected, so one run reports all of them.

use super::spans::{Remap, StrMap};
use super::types::{Formula, Located, StepFormula};
use crate::syntax::ast::*;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::parser::{parse_expr, parse_step};
use crate::syntax::source::{FileId, Span};
use std::ops::Range;
use toml::de::{DeArray, DeString, DeTable, DeValue};
use toml::Spanned;

pub(super) type Entry<'t, 'i> = (&'t Spanned<DeString<'i>>, &'t Spanned<DeValue<'i>>);

/// A table's entries in source order (`DeTable` keeps them sorted by key).
pub(super) fn entries<'t, 'i>(t: &'t DeTable<'i>) -> Vec<Entry<'t, 'i>> {
    let mut v: Vec<_> = t.iter().collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

pub(super) fn a_type(v: &DeValue) -> &'static str {
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
pub(super) fn is_atom(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next().is_some_and(|c| c.is_ascii_lowercase())
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A PDDL type name.
pub(super) fn is_type_name(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next().is_some_and(|c| c.is_ascii_alphabetic())
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// A name for an invariant, a property or a user: it appears in finding ids and `--user`.
pub(super) fn is_name(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Every variable of an expression, with its span, in order.
pub(super) fn vars<'e>(e: &'e Expr, out: &mut Vec<(&'e str, Span)>) {
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
pub(super) struct AtomRule {
    /// "a fact", "a goal", ...
    what: &'static str,
    /// An example of the expected shape.
    example: &'static str,
    /// Whether variables are refused.
    ground: bool,
}

pub(super) const FACT: AtomRule = AtomRule {
    what: "a fact",
    example: "robotAt(table)",
    ground: true,
};
pub(super) const GOAL: AtomRule = AtomRule {
    what: "a goal",
    example: "storeCup(C)",
    ground: false,
};
pub(super) const SCENARIO_ATOM: AtomRule = AtomRule {
    what: "an initial atom",
    example: "cupAt(cup1,table)",
    ground: true,
};
pub(super) const SCENARIO_REQUEST: AtomRule = AtomRule {
    what: "a request",
    example: "storeCup(cup1)",
    ground: true,
};

/// The validation context: the manifest's text and every error found so far.
pub(super) struct Cx<'a> {
    pub(super) file: FileId,
    pub(super) text: &'a str,
    pub(super) errors: Vec<Diagnostic>,
}

impl<'a> Cx<'a> {
    pub(super) fn new(file: FileId, text: &'a str) -> Self {
        Cx {
            file,
            text,
            errors: Vec::new(),
        }
    }

    pub(super) fn span(&self, r: Range<usize>) -> Span {
        Span::new(self.file, r.start, r.end)
    }

    pub(super) fn err(
        &mut self,
        r: Range<usize>,
        message: impl Into<String>,
        label: impl Into<String>,
    ) {
        let d = Diagnostic::error("input", message).with_label(self.span(r), label);
        self.errors.push(d);
    }

    /// Returns the value when no error was recorded; errors sorted by position.
    pub(super) fn finish<T>(mut self, value: Option<T>) -> Result<T, Vec<Diagnostic>> {
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
    pub(super) fn parse_root(&mut self) -> Option<DeTable<'a>> {
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

    /// Reports every key of `t` not in `allowed`; `place` reads "in `[agent]`", "at the top
    /// level".
    pub(super) fn check_keys(&mut self, t: &DeTable, allowed: &[&str], place: &str) {
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

    pub(super) fn table<'t, 'i>(
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
    pub(super) fn section<'t, 'i>(
        &mut self,
        root: &'t DeTable<'i>,
        key: &str,
        allowed: &[&str],
    ) -> Option<&'t DeTable<'i>> {
        let t = self.table(root.get(key)?, &format!("[{key}]"))?;
        self.check_keys(t, allowed, &format!("in [{key}]"));
        Some(t)
    }

    pub(super) fn array<'t, 'i>(
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

    pub(super) fn string(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Located<String>> {
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
    pub(super) fn strings(
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

    pub(super) fn integer(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
        min: u64,
        max: u64,
    ) -> Option<u64> {
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
    pub(super) fn choice(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
        options: &[&str],
    ) -> Option<usize> {
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

    pub(super) fn missing(&mut self, r: Range<usize>, key: &str, place: &str) {
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
    pub(super) fn no_duplicates(&mut self, names: &[Located<String>], what: &str) {
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

    pub(super) fn formula(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Formula> {
        let s = self.string(v, what)?;
        let expr = self.parse_in(&s, v.span(), parse_expr)?;
        Some(Formula {
            text: s.value,
            span: s.span,
            expr,
        })
    }

    /// An `ltl` string: its text and span as a [`Formula`] whose expression is `true`, and
    /// the parsed LTL formula.
    pub(super) fn ltl(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
    ) -> Option<(Formula, super::ltl::LtlExpr)> {
        let s = self.string(v, what)?;
        let ltl = self.parse_in(&s, v.span(), super::ltl::parse_ltl)?;
        let expr = crate::syntax::ast::Expr {
            kind: crate::syntax::ast::ExprKind::Literal(crate::syntax::ast::Literal {
                namespace: None,
                negated: false,
                functor: "true".into(),
                args: Vec::new(),
                annots: None,
                span: ltl.span,
            }),
            span: ltl.span,
        };
        Some((
            Formula {
                text: s.value,
                span: s.span,
                expr,
            },
            ltl,
        ))
    }

    pub(super) fn formulas(&mut self, v: &Spanned<DeValue>, what: &str) -> Vec<Formula> {
        let Some(a) = self.array(v, what, "an array of strings") else {
            return Vec::new();
        };
        a.iter()
            .filter_map(|x| self.formula(x, &format!("an element of {what}")))
            .collect()
    }

    /// An array of atoms obeying `rule`.
    pub(super) fn atoms(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
        rule: AtomRule,
    ) -> Vec<Formula> {
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
    pub(super) fn name_in_string(
        &mut self,
        v: &Spanned<DeValue>,
        what: &str,
    ) -> Option<Located<String>> {
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
    pub(super) fn observed_step(
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
}
