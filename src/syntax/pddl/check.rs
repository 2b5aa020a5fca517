//! Stage 4: the structural checks that need no other file: duplicate names, undeclared and
//! cyclic types, undeclared predicates, arities and free variables, with suggestions for
//! misspelt names.

use super::ast::{
    AtomicFormula, Domain, Effect, EffectKind, Gd, GdKind, PddlTerm, PredicateDecl, TypeDecl,
    TypedVar,
};
use super::MAX_ERRORS;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::Span;
use std::collections::{HashMap, HashSet};

pub(super) struct Checker<'d, 'e> {
    d: &'d Domain,
    errors: &'e mut Vec<Diagnostic>,
    types: HashMap<&'d str, &'d TypeDecl>,
    preds: HashMap<&'d str, &'d PredicateDecl>,
    /// Report undeclared types (false when a `(:types` part did not parse).
    check_types: bool,
    /// Report undeclared predicates (false when a `(:predicates` part did not parse).
    check_preds: bool,
}

impl<'d, 'e> Checker<'d, 'e> {
    pub(super) fn new(
        d: &'d Domain,
        check_types: bool,
        check_preds: bool,
        errors: &'e mut Vec<Diagnostic>,
    ) -> Self {
        Checker {
            d,
            errors,
            types: HashMap::new(),
            preds: HashMap::new(),
            check_types,
            check_preds,
        }
    }

    fn report(&mut self, d: Diagnostic) {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
    }

    fn duplicate(&mut self, what: &str, name: &str, span: Span, first: Span) {
        self.report(
            Diagnostic::error("input", format!("{what} `{name}` is declared twice"))
                .with_label(span, "declared again here")
                .with_secondary(first, "first declared here"),
        );
    }

    pub(super) fn run(mut self) {
        let d = self.d;
        // Types: duplicates, then parents, then cycles.
        for t in &d.types {
            match self.types.get(t.name.as_str()) {
                Some(first) => self.duplicate("type", &t.name, t.span, first.span),
                None => {
                    self.types.insert(&t.name, t);
                }
            }
        }
        for t in &d.types {
            self.declared_type(&t.parent, t.parent_span);
        }
        self.type_cycles();
        let mut consts: HashMap<&str, Span> = HashMap::new();
        for c in &d.constants {
            match consts.get(c.name.as_str()) {
                Some(&first) => self.duplicate("constant", &c.name, c.span, first),
                None => {
                    consts.insert(&c.name, c.span);
                }
            }
            self.declared_type(&c.ty, c.ty_span);
        }
        for p in &d.predicates {
            match self.preds.get(p.name.as_str()) {
                Some(first) => self.duplicate("predicate", &p.name, p.name_span, first.name_span),
                None => {
                    self.preds.insert(&p.name, p);
                }
            }
            self.params(&p.params);
        }
        let mut actions: HashMap<&str, Span> = HashMap::new();
        for a in &d.actions {
            match actions.get(a.name.as_str()) {
                Some(&first) => self.duplicate("action", &a.name, a.name_span, first),
                None => {
                    actions.insert(&a.name, a.name_span);
                }
            }
            self.params(&a.params);
            let mut scope: Vec<&str> = a.params.iter().map(|v| v.name.as_str()).collect();
            if let Some(g) = &a.precondition {
                self.gd(g, &mut scope, &a.name);
            }
            if let Some(e) = &a.effect {
                self.effect(e, &mut scope, &a.name);
            }
        }
    }

    /// A type named in a declaration must be `object` or declared.
    fn declared_type(&mut self, ty: &str, span: Option<Span>) {
        let Some(span) = span else { return };
        if !self.check_types || ty == "object" || self.types.contains_key(ty) {
            return;
        }
        let mut d = Diagnostic::error("input", format!("undefined type `{ty}`"))
            .with_label(span, "not declared in `(:types ...)`");
        d = match suggest(ty, self.types.keys().copied()) {
            Some(s) => d.with_help(format!("did you mean `{s}`? (names are case-sensitive)")),
            None => d.with_help(format!("declare it: `(:types ... {ty})`")),
        };
        self.report(d);
    }

    /// Reports each cycle of the parent relation once, at its first-declared type.
    fn type_cycles(&mut self) {
        let mut reported: HashSet<&str> = HashSet::new();
        for t in &self.d.types {
            if reported.contains(t.name.as_str()) {
                continue;
            }
            let mut path: Vec<&str> = vec![&t.name];
            let mut cur = self.types.get(t.parent.as_str()).copied();
            while let Some(p) = cur {
                if p.name == t.name || path.contains(&p.name.as_str()) {
                    break;
                }
                path.push(&p.name);
                cur = self.types.get(p.parent.as_str()).copied();
            }
            let Some(p) = cur else { continue };
            if p.name != t.name {
                // `t` leads into a cycle but is not on it; that cycle is reported from one of
                // its own members.
                continue;
            }
            reported.extend(path.iter().copied());
            let mut chain = path.join(" - ");
            chain.push_str(&format!(" - {}", t.name));
            let mut d =
                Diagnostic::error("input", format!("type `{}` is its own ancestor", t.name))
                    .with_label(t.span, format!("cycle: {chain}"))
                    .with_help(
                        "the parent relation of `(:types ...)` must form a tree rooted at `object`",
                    );
            if let Some(s) = t.parent_span {
                d = d.with_secondary(s, "parent given here");
            }
            self.report(d);
        }
    }

    /// Parameters: declared types, no name twice.
    fn params(&mut self, params: &[TypedVar]) {
        let mut seen: HashMap<&str, Span> = HashMap::new();
        for v in params {
            self.declared_type(&v.ty, v.ty_span);
            match seen.get(v.name.as_str()) {
                Some(&first) => self.report(
                    Diagnostic::error("input", format!("variable `?{}` is declared twice", v.name))
                        .with_label(v.span, "declared again here")
                        .with_secondary(first, "first declared here"),
                ),
                None => {
                    seen.insert(&v.name, v.span);
                }
            }
        }
    }

    fn gd(&mut self, g: &'d Gd, scope: &mut Vec<&'d str>, action: &str) {
        match &g.kind {
            GdKind::And(gs) | GdKind::Or(gs) => {
                for g in gs {
                    self.gd(g, scope, action);
                }
            }
            GdKind::Not(g) => self.gd(g, scope, action),
            GdKind::Imply(a, b) => {
                self.gd(a, scope, action);
                self.gd(b, scope, action);
            }
            GdKind::Exists(vs, g) | GdKind::Forall(vs, g) => {
                self.params(vs);
                let n = scope.len();
                scope.extend(vs.iter().map(|v| v.name.as_str()));
                self.gd(g, scope, action);
                scope.truncate(n);
            }
            GdKind::Atom(a) => self.atom(a, scope, action),
            GdKind::Equal(a, b) => {
                self.term(a, scope, action);
                self.term(b, scope, action);
            }
        }
    }

    fn effect(&mut self, e: &'d Effect, scope: &mut Vec<&'d str>, action: &str) {
        match &e.kind {
            EffectKind::And(es) => {
                for e in es {
                    self.effect(e, scope, action);
                }
            }
            EffectKind::Add(a) | EffectKind::Delete(a) => self.atom(a, scope, action),
            EffectKind::Forall(vs, e) => {
                self.params(vs);
                let n = scope.len();
                scope.extend(vs.iter().map(|v| v.name.as_str()));
                self.effect(e, scope, action);
                scope.truncate(n);
            }
            EffectKind::When(g, e) => {
                self.gd(g, scope, action);
                self.effect(e, scope, action);
            }
        }
    }

    fn atom(&mut self, a: &AtomicFormula, scope: &[&str], action: &str) {
        match self.preds.get(a.predicate.as_str()) {
            Some(p) if p.params.len() != a.args.len() => {
                let n = p.params.len();
                self.report(
                    Diagnostic::error(
                        "input",
                        format!(
                            "predicate `{}` takes {n} argument{}, found {}",
                            a.predicate,
                            if n == 1 { "" } else { "s" },
                            a.args.len()
                        ),
                    )
                    .with_label(a.span, format!("{} given", a.args.len()))
                    .with_secondary(p.span, "declared here"),
                );
            }
            Some(_) => {}
            None if self.check_preds => {
                let mut d =
                    Diagnostic::error("input", format!("undefined predicate `{}`", a.predicate))
                        .with_label(a.predicate_span, "not declared in `(:predicates ...)`");
                if let Some(s) = suggest(&a.predicate, self.preds.keys().copied()) {
                    d = d.with_help(format!("did you mean `{s}`? (names are case-sensitive)"));
                }
                self.report(d);
            }
            None => {}
        }
        for t in &a.args {
            self.term(t, scope, action);
        }
    }

    fn term(&mut self, t: &PddlTerm, scope: &[&str], action: &str) {
        if let PddlTerm::Var { name, span } = t {
            if !scope.contains(&name.as_str()) {
                self.report(
                    Diagnostic::error("input", format!("undefined variable `?{name}`")).with_label(
                        *span,
                        format!("not a parameter of `{action}` nor bound by `exists` or `forall`"),
                    ),
                );
            }
        }
    }
}

/// A declared name close to `name`: equal ignoring case, or at most two edits away.
pub(super) fn suggest<'a>(
    name: &str,
    candidates: impl Iterator<Item = &'a str>,
) -> Option<&'a str> {
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let dist = if c.eq_ignore_ascii_case(name) {
            0
        } else {
            edit_distance(name, c)
        };
        if dist <= 2 && dist < name.chars().count() && best.is_none_or(|(b, s)| (dist, c) < (b, s))
        {
            best = Some((dist, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Levenshtein distance; long names count as far apart, to keep this cheap.
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    if a.len() > 64 || b.len() > 64 {
        return usize::MAX;
    }
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}
