//! Stage 3: the s-expression tree to a [`Domain`]: the `(define (domain NAME) ...)` frame and
//! its sections. A broken section is reported and left out, and reading goes on with the
//! next; actions are read in `read_action`.

use super::ast::{Constant, Domain, PredicateDecl, Requirement, TypeDecl, TypedVar};
use super::lexer::Atom;
use super::sexpr::{
    describe, head_span, keyword_name, keyword_of, list_end, name_of, SExpr, SKind,
};
use super::{MAX_ERRORS, SUPPORTED_REQUIREMENTS};
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::{FileId, Span};
use std::collections::HashMap;

/// `Err(())` means a diagnostic has been recorded.
pub(super) type PResult<T> = Result<T, ()>;

/// One entry of a typed list: a name or variable and its type, if given.
pub(super) struct Typed {
    name: String,
    span: Span,
    ty: Option<(String, Span)>,
}

impl Typed {
    fn ty(&self) -> (String, Option<Span>) {
        match &self.ty {
            Some((t, s)) => (t.clone(), Some(*s)),
            None => ("object".to_string(), None),
        }
    }

    pub(super) fn into_var(self) -> TypedVar {
        let (ty, ty_span) = self.ty();
        TypedVar {
            name: self.name,
            ty,
            ty_span,
            span: self.span,
        }
    }
}

pub(super) struct Reader {
    pub(super) file: FileId,
    pub(super) errors: Vec<Diagnostic>,
    /// A `(:types` part did not parse: undeclared types are then not reported.
    pub(super) types_broken: bool,
    /// A `(:predicates` part did not parse: undeclared predicates are then not reported.
    pub(super) predicates_broken: bool,
}

impl Reader {
    pub(super) fn error<T>(&mut self, d: Diagnostic) -> PResult<T> {
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(d);
        }
        Err(())
    }

    /// "expected WHAT, found FOUND" at `span`.
    pub(super) fn expected<T>(&mut self, span: Span, what: &str, found: String) -> PResult<T> {
        self.error(Diagnostic::syntax(
            span,
            format!("expected {what}, found {found}"),
            format!("expected {what}"),
        ))
    }

    /// "expected WHAT" about element `e` (silent when `e` was already reported).
    pub(super) fn expected_elem<T>(&mut self, e: &SExpr, what: &str) -> PResult<T> {
        if matches!(e.kind, SKind::Bad) {
            return Err(());
        }
        self.expected(head_span(e), what, describe(e))
    }

    /// Adds help to the diagnostic just reported.
    pub(super) fn help_last(&mut self, help: &str) {
        if let Some(d) = self.errors.last_mut() {
            d.help = Some(help.to_string());
        }
    }

    pub(super) fn unsupported<T>(&mut self, span: Span, msg: String, help: &str) -> PResult<T> {
        self.error(
            Diagnostic::error("input", msg)
                .with_label(span, "not supported by bdi-check")
                .with_help(help),
        )
    }

    pub(super) fn domain(&mut self, top: &[SExpr], text_len: usize) -> Option<Domain> {
        let eof = Span::new(self.file, text_len, text_len);
        let Some(def_index) = top.iter().position(|e| matches!(e.kind, SKind::List(..))) else {
            match top.iter().find(|e| !matches!(e.kind, SKind::Bad)) {
                Some(e) => {
                    let _: PResult<()> = self.expected_elem(e, "`(define (domain NAME) ...)`");
                }
                None if top.is_empty() => {
                    let _: PResult<()> = self.expected(
                        eof,
                        "`(define (domain NAME) ...)`",
                        "the end of the file".to_string(),
                    );
                }
                None => {}
            }
            return None;
        };
        if let Some(e) = top[..def_index]
            .iter()
            .find(|e| !matches!(e.kind, SKind::Bad))
        {
            let _: PResult<()> = self.expected_elem(e, "`(define (domain NAME) ...)`");
        }
        let def = &top[def_index];
        let SKind::List(items, close) = &def.kind else {
            return None;
        };
        // `(define`
        match items.first() {
            Some(h) if name_of(h).map(keyword_name).as_deref() == Some("define") => {}
            Some(h) => {
                if !matches!(h.kind, SKind::Bad) {
                    let _: PResult<()> = self.expected_elem(def, "`(define (domain NAME) ...)`");
                }
                return None;
            }
            None => {
                let (s, f) = list_end(*close);
                let _: PResult<()> = self.expected(s, "`define`", f);
                return None;
            }
        }
        // `(domain NAME)`
        let header = self.header(items.get(1), *close);
        let mut d = Domain {
            name: String::new(),
            name_span: def.span.shrink_to_start(),
            requirements: Vec::new(),
            types: Vec::new(),
            constants: Vec::new(),
            predicates: Vec::new(),
            actions: Vec::new(),
            span: def.span,
        };
        let header_ok = match header {
            Ok(Some((name, span))) => {
                d.name = name;
                d.name_span = span;
                true
            }
            Ok(None) => return None,
            Err(()) => false,
        };
        let mut seen = HashMap::new();
        for e in items.iter().skip(2) {
            self.section(e, &mut d, &mut seen);
        }
        // After the domain: sections that an extra `)` pushed out are reported and still read,
        // anything else is reported once.
        let mut stray_reported = false;
        for e in &top[def_index + 1..] {
            let is_section = match &e.kind {
                SKind::List(items, _) => items.first().and_then(keyword_of).is_some(),
                _ => false,
            };
            if is_section {
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(
                        e.span,
                        format!("section {} is outside `(define ...)`", describe(e)),
                        "after the end of the domain",
                    )
                    .with_secondary(def.span.shrink_to_start(), "the domain starts here")
                    .with_help("an extra `)` before this section closes `(define` too early"),
                );
                self.section(e, &mut d, &mut seen);
            } else if !stray_reported && !matches!(e.kind, SKind::Bad) {
                stray_reported = true;
                let _: PResult<()> = self.expected_elem(e, "the end of the file");
                self.help_last("a file holds one domain, and nothing after it");
            }
        }
        header_ok.then_some(d)
    }

    /// Reads `(domain NAME)`: `Ok(None)` for a problem file (reported), `Err` when malformed.
    fn header(&mut self, e: Option<&SExpr>, close: Span) -> PResult<Option<(String, Span)>> {
        const WHAT: &str = "`(domain NAME)`";
        let Some(e) = e else {
            let (s, f) = list_end(close);
            return self.expected(s, WHAT, f);
        };
        let SKind::List(items, hclose) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let head = match items.first() {
            Some(h) => h,
            None => return self.expected(e.span, WHAT, "`()`".to_string()),
        };
        match name_of(head).map(keyword_name).as_deref() {
            Some("domain") => {}
            Some("problem") => {
                let _: PResult<()> = self.unsupported(
                    e.span,
                    "this is a PDDL problem, not a domain".to_string(),
                    "bdi-check reads only the domain: the manifest (bdi-check.toml) gives the \
                     objects and the initial facts",
                );
                return Ok(None);
            }
            _ => return self.expected_elem(head, "`domain`"),
        }
        let name = match items.get(1) {
            Some(n) => match name_of(n) {
                Some(s) => (s.to_string(), n.span),
                None => return self.expected_elem(n, "the domain's name"),
            },
            None => {
                let (s, f) = list_end(*hclose);
                return self.expected(s, "the domain's name", f);
            }
        };
        if let Some(extra) = items.get(2) {
            return self.expected_elem(extra, "`)` after the domain's name");
        }
        Ok(Some(name))
    }

    fn section(&mut self, e: &SExpr, d: &mut Domain, seen: &mut HashMap<String, Span>) {
        const WHAT: &str = "a section such as `(:action ...)`";
        let (items, close) = match &e.kind {
            SKind::List(items, close) => (items, *close),
            _ => {
                let _: PResult<()> = self.expected_elem(e, WHAT);
                return;
            }
        };
        let Some(head) = items.first() else {
            let _: PResult<()> = self.expected(e.span, WHAT, "`()`".to_string());
            return;
        };
        let Some(kw) = keyword_of(head) else {
            let _: PResult<()> = self.expected_elem(head, WHAT);
            return;
        };
        let args = &items[1..];
        if matches!(
            kw,
            ":requirements" | ":types" | ":constants" | ":predicates"
        ) {
            if let Some(first) = seen.get(kw) {
                // Still read it: merging loses nothing, and skipping would make every name it
                // declares look undeclared.
                let _: PResult<()> = self.error(
                    Diagnostic::error("input", format!("a second `({kw}` section"))
                        .with_label(head.span, "repeated section")
                        .with_secondary(*first, "the first one is here")
                        .with_help("merge the two sections into one"),
                );
            } else {
                seen.insert(kw.to_string(), head.span);
            }
        }
        match kw {
            ":requirements" => self.requirements(args, d),
            ":types" => {
                if self.types(args, close, d).is_err() {
                    self.types_broken = true;
                }
            }
            ":constants" => {
                if let Ok(list) = self.typed_list(args, close, false, "a constant name") {
                    d.constants.extend(list.into_iter().map(|t| {
                        let (ty, ty_span) = t.ty();
                        Constant {
                            name: t.name,
                            ty,
                            ty_span,
                            span: t.span,
                        }
                    }));
                }
            }
            ":predicates" => self.predicates(args, d),
            ":action" => {
                if let Ok(a) = self.action(e.span, args, close) {
                    d.actions.push(a);
                }
            }
            ":functions" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:functions ...)` is not supported".to_string(),
                    NUMERIC_HELP,
                );
            }
            ":durative-action" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:durative-action ...)` is not supported".to_string(),
                    TEMPORAL_HELP,
                );
            }
            ":derived" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:derived ...)` is not supported".to_string(),
                    DERIVED_HELP,
                );
            }
            ":constraints" => {
                let _: PResult<()> = self.unsupported(
                    head.span,
                    "`(:constraints ...)` is not supported".to_string(),
                    CONSTRAINTS_HELP,
                );
            }
            _ => {
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(
                        head.span,
                        format!("unknown section `{kw}`"),
                        "expected a section keyword",
                    )
                    .with_help(
                        "a domain holds `(:requirements ...)`, `(:types ...)`, \
                         `(:constants ...)`, `(:predicates ...)` and `(:action ...)` sections",
                    ),
                );
            }
        }
    }

    fn requirements(&mut self, args: &[SExpr], d: &mut Domain) {
        for e in args {
            let Some(k) = keyword_of(e) else {
                let _: PResult<()> = self.expected_elem(e, "a requirement such as `:strips`");
                continue;
            };
            if SUPPORTED_REQUIREMENTS.contains(&k) {
                d.requirements.push(Requirement {
                    name: k.to_string(),
                    span: e.span,
                });
                continue;
            }
            let help = match k {
                ":numeric-fluents" | ":fluents" | ":object-fluents" | ":action-costs" => {
                    NUMERIC_HELP
                }
                ":durative-actions"
                | ":duration-inequalities"
                | ":continuous-effects"
                | ":timed-initial-literals" => TEMPORAL_HELP,
                ":derived-predicates" => DERIVED_HELP,
                ":preferences" | ":constraints" => CONSTRAINTS_HELP,
                _ => {
                    let _: PResult<()> = self.error(
                        Diagnostic::error("input", format!("unknown requirement `{k}`"))
                            .with_label(e.span, "not a requirement bdi-check knows")
                            .with_help(format!(
                                "supported requirements: {}",
                                SUPPORTED_REQUIREMENTS.join(" ")
                            )),
                    );
                    continue;
                }
            };
            let _: PResult<()> =
                self.unsupported(e.span, format!("requirement `{k}` is not supported"), help);
        }
    }

    fn types(&mut self, args: &[SExpr], close: Span, d: &mut Domain) -> PResult<()> {
        for t in self.typed_list(args, close, false, "a type name")? {
            if t.name == "object" {
                // `object` is the implicit root; declaring it is harmless unless it gets a parent.
                match &t.ty {
                    Some((p, s)) if p != "object" => {
                        return self.error(
                            Diagnostic::error("input", "`object` cannot have a parent type")
                                .with_label(*s, "`object` is the root of every type"),
                        );
                    }
                    _ => continue,
                }
            }
            let (parent, parent_span) = t.ty();
            d.types.push(TypeDecl {
                name: t.name,
                parent,
                parent_span,
                span: t.span,
            });
        }
        Ok(())
    }

    fn predicates(&mut self, args: &[SExpr], d: &mut Domain) {
        const WHAT: &str = "a predicate declaration such as `(at ?x - object)`";
        for e in args {
            let decl = (|| {
                let SKind::List(items, close) = &e.kind else {
                    return self.expected_elem(e, WHAT);
                };
                let Some(head) = items.first() else {
                    return self.expected(e.span, WHAT, "`()`".to_string());
                };
                let Some(name) = name_of(head) else {
                    return self.expected_elem(head, "a predicate name");
                };
                let params =
                    self.typed_list(&items[1..], *close, true, "a variable such as `?x`")?;
                Ok(PredicateDecl {
                    name: name.to_string(),
                    name_span: head.span,
                    params: params.into_iter().map(Typed::into_var).collect(),
                    span: e.span,
                })
            })();
            match decl {
                Ok(p) => d.predicates.push(p),
                Err(()) => self.predicates_broken = true,
            }
        }
    }

    /// A list of names (`vars` false) or variables (`vars` true), some followed by `- type`.
    pub(super) fn typed_list(
        &mut self,
        items: &[SExpr],
        close: Span,
        vars: bool,
        what: &str,
    ) -> PResult<Vec<Typed>> {
        let mut out: Vec<Typed> = Vec::new();
        // Entries from here on have no type yet.
        let mut untyped_from = 0;
        let mut i = 0;
        while let Some(e) = items.get(i) {
            match &e.kind {
                SKind::Atom(Atom::Dash) => {
                    if untyped_from == out.len() {
                        return self.expected(e.span, what, "`-`".to_string());
                    }
                    let ty = self.type_name(items.get(i + 1), close)?;
                    for t in &mut out[untyped_from..] {
                        t.ty = Some(ty.clone());
                    }
                    untyped_from = out.len();
                    i += 2;
                    continue;
                }
                SKind::Atom(Atom::Var(v)) if vars => out.push(Typed {
                    name: v.clone(),
                    span: e.span,
                    ty: None,
                }),
                SKind::Atom(Atom::Name(n)) if !vars => out.push(Typed {
                    name: n.clone(),
                    span: e.span,
                    ty: None,
                }),
                _ => return self.expected_elem(e, what),
            }
            i += 1;
        }
        Ok(out)
    }

    /// The type after a `-`.
    fn type_name(&mut self, e: Option<&SExpr>, close: Span) -> PResult<(String, Span)> {
        const WHAT: &str = "a type name after `-`";
        let Some(e) = e else {
            let (s, f) = list_end(close);
            return self.expected(s, WHAT, f);
        };
        match &e.kind {
            SKind::Atom(Atom::Name(n)) => Ok((n.clone(), e.span)),
            SKind::List(items, _)
                if items.first().and_then(name_of).map(keyword_name).as_deref()
                    == Some("either") =>
            {
                self.unsupported(
                    e.span,
                    "`either` types are not supported".to_string(),
                    "declare a common parent type in `(:types ...)` and use it instead",
                )
            }
            _ => self.expected_elem(e, WHAT),
        }
    }
}

pub(super) const NUMERIC_HELP: &str =
    "bdi-check's state is a finite set of ground atoms: numbers, \
    functions and action costs are not modelled; encode quantities as objects";
pub(super) const TEMPORAL_HELP: &str =
    "bdi-check's actions are instantaneous, like Jason's environment \
    actions: use `(:action ...)` with `:precondition` and `:effect`";
const DERIVED_HELP: &str = "derived predicates are not supported: write the rule in the agent \
    (a Jason rule) or state the predicate's effect in each action";
const CONSTRAINTS_HELP: &str = "state constraints and preferences as `[invariants]` or \
    `[[property]]` in bdi-check.toml instead";
