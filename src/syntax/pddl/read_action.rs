//! Stage 3, actions: an `(:action ...)` with its parameters, its precondition (a goal
//! description) and its effect. Each key is read on its own, so that one broken value does
//! not hide the errors of the others.

use super::ast::{ActionDecl, AtomicFormula, Effect, EffectKind, Gd, GdKind, PddlTerm, TypedVar};
use super::lexer::Atom;
use super::read::{PResult, Reader, Typed, NUMERIC_HELP, TEMPORAL_HELP};
use super::sexpr::{keyword_name, keyword_of, list_end, name_of, SExpr, SKind};
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::source::Span;
use std::collections::HashMap;

impl Reader {
    pub(super) fn action(
        &mut self,
        span: Span,
        args: &[SExpr],
        close: Span,
    ) -> PResult<ActionDecl> {
        let (name, name_span) = match args.first() {
            Some(e) => match name_of(e) {
                Some(n) => (n.to_string(), e.span),
                None => return self.expected_elem(e, "the action's name"),
            },
            None => {
                let (s, f) = list_end(close);
                return self.expected(s, "the action's name", f);
            }
        };
        const KEYS: &str = "`:parameters`, `:precondition` or `:effect`";
        let mut params = Vec::new();
        let mut precondition = None;
        let mut effect = None;
        let mut seen: HashMap<&str, Span> = HashMap::new();
        let mut ok = true;
        let mut i = 1;
        // Each key's value is read on its own, so a broken precondition still lets the effect
        // report its errors; the action is kept only when all are fine.
        while let Some(key) = args.get(i) {
            let Some(kw) = keyword_of(key) else {
                ok = false;
                let _: PResult<()> = self.expected_elem(key, KEYS);
                // Resynchronise at the next keyword.
                i += 1;
                while args.get(i).is_some_and(|e| keyword_of(e).is_none()) {
                    i += 1;
                }
                continue;
            };
            if !matches!(kw, ":parameters" | ":precondition" | ":effect") {
                ok = false;
                let mut d = Diagnostic::syntax(
                    key.span,
                    format!("expected {KEYS}, found keyword `{kw}`"),
                    "unknown action key",
                );
                if matches!(kw, ":duration" | ":condition") {
                    d = d.with_help(TEMPORAL_HELP);
                }
                let _: PResult<()> = self.error(d);
                i += 2;
                continue;
            }
            if let Some(first) = seen.get(kw) {
                ok = false;
                let _: PResult<()> = self.error(
                    Diagnostic::syntax(key.span, format!("`{kw}` is given twice"), "repeated")
                        .with_secondary(*first, "first given here"),
                );
                i += 2;
                continue;
            }
            seen.insert(kw, key.span);
            let value = match args.get(i + 1) {
                Some(v) if keyword_of(v).is_none() => v,
                other => {
                    ok = false;
                    let what = format!("a value after `{kw}`");
                    let _: PResult<()> = match other {
                        Some(v) => self.expected_elem(v, &what),
                        None => {
                            let (s, f) = list_end(close);
                            self.expected(s, &what, f)
                        }
                    };
                    i += 1;
                    continue;
                }
            };
            let r = match kw {
                ":parameters" => self.var_list(value).map(|p| params = p),
                ":precondition" => self.gd(value).map(|g| precondition = Some(g)),
                _ => self.effect(value).map(|e| effect = Some(e)),
            };
            ok &= r.is_ok();
            i += 2;
        }
        if !ok {
            return Err(());
        }
        Ok(ActionDecl {
            name,
            name_span,
            params,
            precondition,
            effect,
            span,
        })
    }

    /// `(?x - t ?y)`: parameters or quantified variables.
    fn var_list(&mut self, e: &SExpr) -> PResult<Vec<TypedVar>> {
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, "a list of variables such as `(?x - type)`");
        };
        let list = self.typed_list(items, *close, true, "a variable such as `?x`")?;
        Ok(list.into_iter().map(Typed::into_var).collect())
    }

    /// Checks that `(head ...)` has exactly `N` arguments, named by `what` for the message.
    fn exact<'a, const N: usize>(
        &mut self,
        head: &str,
        args: &'a [SExpr],
        close: Span,
        what: [&str; N],
    ) -> PResult<&'a [SExpr; N]> {
        if args.len() < N {
            let (s, f) = list_end(close);
            return self.expected(s, &format!("{} in `({head} ...)`", what[args.len()]), f);
        }
        if let Some(extra) = args.get(N) {
            return self.expected_elem(extra, &format!("`)` to close `({head} ...)`"));
        }
        <&[SExpr; N]>::try_from(args).map_err(|_| ())
    }

    /// Reads every element, reporting all errors; fails if any failed.
    fn all<T>(
        &mut self,
        args: &[SExpr],
        mut f: impl FnMut(&mut Self, &SExpr) -> PResult<T>,
    ) -> PResult<Vec<T>> {
        let mut out = Vec::with_capacity(args.len());
        let mut ok = true;
        for a in args {
            match f(self, a) {
                Ok(v) => out.push(v),
                Err(()) => ok = false,
            }
        }
        if ok {
            Ok(out)
        } else {
            Err(())
        }
    }

    fn gd(&mut self, e: &SExpr) -> PResult<Gd> {
        const WHAT: &str = "a goal description such as `(p ?x)` or `(and ...)`";
        let span = e.span;
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let close = *close;
        let Some(head) = items.first() else {
            return Ok(Gd {
                kind: GdKind::And(Vec::new()),
                span,
            });
        };
        let args = &items[1..];
        let kind = match &head.kind {
            SKind::Atom(Atom::Name(h)) => match keyword_name(h).as_str() {
                "and" => GdKind::And(self.all(args, Self::gd)?),
                "or" => GdKind::Or(self.all(args, Self::gd)?),
                "not" => {
                    let [g] = self.exact("not", args, close, ["a goal description"])?;
                    GdKind::Not(Box::new(self.gd(g)?))
                }
                "imply" => {
                    let [a, b] = self.exact(
                        "imply",
                        args,
                        close,
                        ["a goal description", "a second goal description"],
                    )?;
                    let (a, b) = (self.gd(a), self.gd(b));
                    GdKind::Imply(Box::new(a?), Box::new(b?))
                }
                q @ ("exists" | "forall") => {
                    let [vs, g] = self.exact(
                        q,
                        args,
                        close,
                        ["a list of variables", "a goal description"],
                    )?;
                    let (vs, g) = (self.var_list(vs), self.gd(g));
                    let (vs, g) = (vs?, Box::new(g?));
                    if q == "exists" {
                        GdKind::Exists(vs, g)
                    } else {
                        GdKind::Forall(vs, g)
                    }
                }
                "when" => {
                    return self.error(
                        Diagnostic::syntax(
                            head.span,
                            "`when` is an effect, not a goal description",
                            "not allowed in a precondition",
                        )
                        .with_help("use `(imply CONDITION GOAL)` in a precondition"),
                    )
                }
                _ => GdKind::Atom(self.atom(head, h, args, span)?),
            },
            SKind::Atom(Atom::Op(o)) if o == "=" => {
                if args.iter().any(|a| matches!(a.kind, SKind::List(..))) {
                    return self.unsupported(
                        head.span,
                        "numeric comparisons are not supported".to_string(),
                        NUMERIC_HELP,
                    );
                }
                let [a, b] = self.exact("=", args, close, ["a term", "a second term"])?;
                let (a, b) = (self.term(a), self.term(b));
                GdKind::Equal(a?, b?)
            }
            SKind::Atom(Atom::Op(o)) if matches!(o.as_str(), "<" | ">" | "<=" | ">=") => {
                return self.unsupported(
                    head.span,
                    "numeric comparisons are not supported".to_string(),
                    NUMERIC_HELP,
                );
            }
            _ => {
                let r = self.expected_elem(head, "a predicate name or a connective such as `and`");
                self.help_last(if matches!(head.kind, SKind::List(..)) {
                    "one pair of parentheses too many? A goal description is `(p t...)`, \
                     `(and ...)`, `(or ...)`, `(not G)`, `(imply G G)`, `(exists (?x) G)`, \
                     `(forall (?x) G)` or `(= t t)`"
                } else {
                    "a goal description is `(p t...)`, `(and ...)`, `(or ...)`, `(not G)`, \
                     `(imply G G)`, `(exists (?x) G)`, `(forall (?x) G)` or `(= t t)`"
                });
                return r;
            }
        };
        Ok(Gd { kind, span })
    }

    /// `(p t...)`, the head already read.
    fn atom(
        &mut self,
        head: &SExpr,
        name: &str,
        args: &[SExpr],
        span: Span,
    ) -> PResult<AtomicFormula> {
        Ok(AtomicFormula {
            predicate: name.to_string(),
            predicate_span: head.span,
            args: self.all(args, Self::term)?,
            span,
        })
    }

    fn term(&mut self, e: &SExpr) -> PResult<PddlTerm> {
        match &e.kind {
            SKind::Atom(Atom::Var(v)) => Ok(PddlTerm::Var {
                name: v.clone(),
                span: e.span,
            }),
            SKind::Atom(Atom::Name(n)) => Ok(PddlTerm::Const {
                name: n.clone(),
                span: e.span,
            }),
            SKind::List(..) => {
                let r = self.expected_elem(e, "a variable or a constant");
                self.help_last(
                    "function terms need `:object-fluents`, which bdi-check does not support",
                );
                r
            }
            _ => self.expected_elem(e, "a variable or a constant"),
        }
    }

    fn effect(&mut self, e: &SExpr) -> PResult<Effect> {
        const WHAT: &str = "an effect such as `(p ?x)` or `(and ...)`";
        let span = e.span;
        let SKind::List(items, close) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let close = *close;
        let Some(head) = items.first() else {
            return Ok(Effect {
                kind: EffectKind::And(Vec::new()),
                span,
            });
        };
        let args = &items[1..];
        let kind = match &head.kind {
            SKind::Atom(Atom::Name(h)) => match keyword_name(h).as_str() {
                "and" => EffectKind::And(self.all(args, Self::effect)?),
                "not" => {
                    let [a] = self.exact("not", args, close, ["an atom"])?;
                    EffectKind::Delete(self.effect_atom(a)?)
                }
                "forall" => {
                    let [vs, eff] =
                        self.exact("forall", args, close, ["a list of variables", "an effect"])?;
                    let (vs, eff) = (self.var_list(vs), self.effect(eff));
                    EffectKind::Forall(vs?, Box::new(eff?))
                }
                "when" => {
                    let [g, eff] = self.exact("when", args, close, ["a condition", "an effect"])?;
                    let (g, eff) = (self.gd(g), self.effect(eff));
                    EffectKind::When(Box::new(g?), Box::new(eff?))
                }
                k @ ("or" | "imply" | "exists") => {
                    return self.error(
                        Diagnostic::syntax(
                            head.span,
                            format!("`{k}` is not allowed in an effect"),
                            "a goal description, not an effect",
                        )
                        .with_help(
                            "an effect is a conjunction of atoms, `(not ATOM)`, `(forall ...)` \
                             and `(when CONDITION EFFECT)`",
                        ),
                    )
                }
                "increase" | "decrease" | "assign" | "scale-up" | "scale-down"
                    if args
                        .first()
                        .is_some_and(|a| matches!(a.kind, SKind::List(..))) =>
                {
                    return self.unsupported(
                        head.span,
                        format!("numeric effect `{h}` is not supported"),
                        NUMERIC_HELP,
                    )
                }
                _ => EffectKind::Add(self.atom(head, h, args, span)?),
            },
            SKind::Atom(Atom::Op(o)) if o == "=" => {
                return self.error(Diagnostic::syntax(
                    head.span,
                    "an equality cannot be an effect",
                    "not an effect",
                ))
            }
            _ => {
                let r = self.expected_elem(head, "a predicate name or a connective such as `and`");
                self.help_last(if matches!(head.kind, SKind::List(..)) {
                    "one pair of parentheses too many? An effect is `(p t...)`, \
                     `(not (p t...))`, `(and ...)`, `(forall (?x) E)` or `(when G E)`"
                } else {
                    "an effect is `(p t...)`, `(not (p t...))`, `(and ...)`, `(forall (?x) E)` \
                     or `(when G E)`"
                });
                return r;
            }
        };
        Ok(Effect { kind, span })
    }

    /// The atom under `(not ...)` in an effect.
    fn effect_atom(&mut self, e: &SExpr) -> PResult<AtomicFormula> {
        const WHAT: &str = "an atom such as `(p ?x)`";
        let SKind::List(items, _) = &e.kind else {
            return self.expected_elem(e, WHAT);
        };
        let Some(head) = items.first() else {
            return self.expected(e.span, WHAT, "`()`".to_string());
        };
        match &head.kind {
            SKind::Atom(Atom::Name(h)) if !is_connective(h) => {
                self.atom(head, h, &items[1..], e.span)
            }
            SKind::Atom(Atom::Op(o)) if o == "=" => self.error(Diagnostic::syntax(
                head.span,
                "an equality cannot be an effect",
                "not an effect",
            )),
            _ => self.expected_elem(head, "a predicate name"),
        }
    }
}

/// Whether a name is one of the logical connectives (in any case).
fn is_connective(n: &str) -> bool {
    matches!(
        n.to_ascii_lowercase().as_str(),
        "and" | "or" | "not" | "imply" | "exists" | "forall" | "when"
    )
}
