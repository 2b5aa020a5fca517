//! The syntax tree of a PDDL domain, every node with the [`Span`] later type errors point at,
//! and its printing in PDDL syntax for messages.

use crate::syntax::source::Span;
use std::collections::HashSet;
use std::fmt;

/// A PDDL domain: the robot's environment actions and the vocabulary they use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Domain {
    /// The name in `(domain NAME)`.
    pub name: String,
    /// Where that name is.
    pub name_span: Span,
    /// `(:requirements ...)`, only supported ones.
    pub requirements: Vec<Requirement>,
    /// `(:types ...)`, in source order (`object` itself is implicit and not listed).
    pub types: Vec<TypeDecl>,
    /// `(:constants ...)`.
    pub constants: Vec<Constant>,
    /// `(:predicates ...)`.
    pub predicates: Vec<PredicateDecl>,
    /// Every `(:action ...)` that parsed.
    pub actions: Vec<ActionDecl>,
    /// The whole `(define ...)`.
    pub span: Span,
}

/// One requirement flag, such as `:typing`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Requirement {
    /// The flag with its colon, lower-cased: `:typing`.
    pub name: String,
    /// Where it is.
    pub span: Span,
}

/// A type declared in `(:types ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypeDecl {
    /// Its name.
    pub name: String,
    /// Its parent: the type after `-`, or `object`.
    pub parent: String,
    /// Where the parent is named (`None` when it defaults to `object`).
    pub parent_span: Option<Span>,
    /// Where the type's name is.
    pub span: Span,
}

/// A constant declared in `(:constants ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Constant {
    /// Its name.
    pub name: String,
    /// Its type (`object` when none is given).
    pub ty: String,
    /// Where the type is named (`None` when it defaults to `object`).
    pub ty_span: Option<Span>,
    /// Where the constant's name is.
    pub span: Span,
}

/// A typed variable: a parameter of a predicate or an action, or one bound by a quantifier.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypedVar {
    /// Its name without the `?`.
    pub name: String,
    /// Its type (`object` when none is given).
    pub ty: String,
    /// Where the type is named (`None` when it defaults to `object`).
    pub ty_span: Option<Span>,
    /// Where the variable is.
    pub span: Span,
}

/// A predicate declared in `(:predicates ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PredicateDecl {
    /// Its name.
    pub name: String,
    /// Where its name is.
    pub name_span: Span,
    /// Its parameters, in order.
    pub params: Vec<TypedVar>,
    /// The whole declaration `(p ?x - t)`.
    pub span: Span,
}

/// An `(:action ...)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActionDecl {
    /// Its name.
    pub name: String,
    /// Where its name is.
    pub name_span: Span,
    /// `:parameters`, empty when absent.
    pub params: Vec<TypedVar>,
    /// `:precondition`, if given.
    pub precondition: Option<Gd>,
    /// `:effect`, if given.
    pub effect: Option<Effect>,
    /// The whole `(:action ...)`.
    pub span: Span,
}

/// A goal description: a precondition or a part of one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Gd {
    /// What it is.
    pub kind: GdKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of goal description.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GdKind {
    /// `(and G...)`; `()` is the empty conjunction, which always holds.
    And(Vec<Gd>),
    /// `(or G...)`.
    Or(Vec<Gd>),
    /// `(not G)`.
    Not(Box<Gd>),
    /// `(imply G1 G2)`.
    Imply(Box<Gd>, Box<Gd>),
    /// `(exists (?x - t ...) G)`.
    Exists(Vec<TypedVar>, Box<Gd>),
    /// `(forall (?x - t ...) G)`.
    Forall(Vec<TypedVar>, Box<Gd>),
    /// `(p t1 t2)`.
    Atom(AtomicFormula),
    /// `(= t1 t2)`.
    Equal(PddlTerm, PddlTerm),
}

/// An effect: what an action changes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Effect {
    /// What it is.
    pub kind: EffectKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EffectKind {
    /// `(and E...)`; `()` is the empty effect.
    And(Vec<Effect>),
    /// `(p t...)`: the atom becomes true.
    Add(AtomicFormula),
    /// `(not (p t...))`: the atom becomes false.
    Delete(AtomicFormula),
    /// `(forall (?x - t ...) E)`.
    Forall(Vec<TypedVar>, Box<Effect>),
    /// `(when G E)`: `E` applies when `G` holds before the action.
    When(Box<Gd>, Box<Effect>),
}

/// `(p t1 ... tn)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AtomicFormula {
    /// The predicate's name.
    pub predicate: String,
    /// Where the predicate's name is.
    pub predicate_span: Span,
    /// The arguments.
    pub args: Vec<PddlTerm>,
    /// The whole atom.
    pub span: Span,
}

/// An argument of an atom: a variable or a constant.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PddlTerm {
    /// `?x`, stored without the `?`.
    Var {
        /// The name without `?`.
        name: String,
        /// Where it is.
        span: Span,
    },
    /// A constant or object name.
    Const {
        /// The name.
        name: String,
        /// Where it is.
        span: Span,
    },
}

impl PddlTerm {
    /// The name (without `?` for a variable).
    pub fn name(&self) -> &str {
        match self {
            PddlTerm::Var { name, .. } | PddlTerm::Const { name, .. } => name,
        }
    }

    /// Where the term is.
    pub fn span(&self) -> Span {
        match self {
            PddlTerm::Var { span, .. } | PddlTerm::Const { span, .. } => *span,
        }
    }

    /// Whether it is a `?variable`.
    pub fn is_var(&self) -> bool {
        matches!(self, PddlTerm::Var { .. })
    }
}

impl Gd {
    /// Every atom in the goal, in source order (equalities are not atoms).
    pub fn atoms(&self) -> Vec<&AtomicFormula> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms<'a>(&'a self, out: &mut Vec<&'a AtomicFormula>) {
        match &self.kind {
            GdKind::And(gs) | GdKind::Or(gs) => gs.iter().for_each(|g| g.collect_atoms(out)),
            GdKind::Not(g) | GdKind::Exists(_, g) | GdKind::Forall(_, g) => g.collect_atoms(out),
            GdKind::Imply(a, b) => {
                a.collect_atoms(out);
                b.collect_atoms(out);
            }
            GdKind::Atom(a) => out.push(a),
            GdKind::Equal(..) => {}
        }
    }

    /// Every term in the goal, in source order.
    fn collect_terms<'a>(&'a self, out: &mut Vec<&'a PddlTerm>) {
        match &self.kind {
            GdKind::And(gs) | GdKind::Or(gs) => gs.iter().for_each(|g| g.collect_terms(out)),
            GdKind::Not(g) | GdKind::Exists(_, g) | GdKind::Forall(_, g) => g.collect_terms(out),
            GdKind::Imply(a, b) => {
                a.collect_terms(out);
                b.collect_terms(out);
            }
            GdKind::Atom(a) => out.extend(a.args.iter()),
            GdKind::Equal(a, b) => out.extend([a, b]),
        }
    }
}

impl Effect {
    /// Every atom the effect may add (`true`) or delete (`false`), in source order, including
    /// those under `when` and `forall` (the conditions of `when` are not included).
    pub fn atoms(&self) -> Vec<(bool, &AtomicFormula)> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms<'a>(&'a self, out: &mut Vec<(bool, &'a AtomicFormula)>) {
        match &self.kind {
            EffectKind::And(es) => es.iter().for_each(|e| e.collect_atoms(out)),
            EffectKind::Add(a) => out.push((true, a)),
            EffectKind::Delete(a) => out.push((false, a)),
            EffectKind::Forall(_, e) | EffectKind::When(_, e) => e.collect_atoms(out),
        }
    }

    fn collect_terms<'a>(&'a self, out: &mut Vec<&'a PddlTerm>) {
        match &self.kind {
            EffectKind::And(es) => es.iter().for_each(|e| e.collect_terms(out)),
            EffectKind::Add(a) | EffectKind::Delete(a) => out.extend(a.args.iter()),
            EffectKind::Forall(_, e) => e.collect_terms(out),
            EffectKind::When(g, e) => {
                g.collect_terms(out);
                e.collect_terms(out);
            }
        }
    }
}

impl Domain {
    /// Whether a requirement is declared, counting the ones `:adl` and
    /// `:quantified-preconditions` imply.
    pub fn requires(&self, flag: &str) -> bool {
        let has = |f: &str| self.requirements.iter().any(|r| r.name == f);
        has(flag)
            || (has(":adl")
                && matches!(
                    flag,
                    ":strips"
                        | ":typing"
                        | ":negative-preconditions"
                        | ":disjunctive-preconditions"
                        | ":equality"
                        | ":existential-preconditions"
                        | ":universal-preconditions"
                        | ":quantified-preconditions"
                        | ":conditional-effects"
                ))
            || (has(":quantified-preconditions")
                && matches!(
                    flag,
                    ":existential-preconditions" | ":universal-preconditions"
                ))
    }

    /// The declaration of a type, if it is declared (`object` is implicit and has none).
    pub fn type_decl(&self, name: &str) -> Option<&TypeDecl> {
        self.types.iter().find(|t| t.name == name)
    }

    /// The declaration of a constant.
    pub fn constant(&self, name: &str) -> Option<&Constant> {
        self.constants.iter().find(|c| c.name == name)
    }

    /// The declaration of a predicate.
    pub fn predicate(&self, name: &str) -> Option<&PredicateDecl> {
        self.predicates.iter().find(|p| p.name == name)
    }

    /// The action of that name.
    pub fn action(&self, name: &str) -> Option<&ActionDecl> {
        self.actions.iter().find(|a| a.name == name)
    }

    /// The proper ancestors of a type, nearest first, ending with `object` (empty for `object`
    /// itself). An undeclared type has just `object`; a cycle stops the walk.
    pub fn type_ancestors(&self, ty: &str) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mut cur = ty;
        while let Some(t) = self.type_decl(cur) {
            if t.parent == ty || out.contains(&t.parent) || t.parent == "object" {
                break;
            }
            out.push(t.parent.clone());
            cur = &t.parent;
        }
        if ty != "object" {
            out.push("object".to_string());
        }
        out
    }

    /// Whether every object of type `a` is also of type `b` (a type is a subtype of itself, and
    /// every type of `object`).
    pub fn is_subtype(&self, a: &str, b: &str) -> bool {
        a == b || b == "object" || self.type_ancestors(a).iter().any(|t| t == b)
    }

    /// Every constant term in the actions' preconditions and effects, in source order, with
    /// where it is (declared or not).
    pub fn constant_uses(&self) -> Vec<(&str, Span)> {
        let mut terms = Vec::new();
        for a in &self.actions {
            if let Some(g) = &a.precondition {
                g.collect_terms(&mut terms);
            }
            if let Some(e) = &a.effect {
                e.collect_terms(&mut terms);
            }
        }
        terms
            .into_iter()
            .filter(|t| !t.is_var())
            .map(|t| (t.name(), t.span()))
            .collect()
    }

    /// The constant terms used in actions that `(:constants ...)` does not declare, every
    /// occurrence in source order. They are not errors here: in this project they may be
    /// objects of the manifest, so the caller checks them (and reports at these spans).
    pub fn undeclared_constants(&self) -> Vec<(&str, Span)> {
        let declared: HashSet<&str> = self.constants.iter().map(|c| c.name.as_str()).collect();
        self.constant_uses()
            .into_iter()
            .filter(|(n, _)| !declared.contains(n))
            .collect()
    }
}

// ----- printing, in PDDL syntax (for messages) -------------------------------------------------

impl fmt::Display for PddlTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PddlTerm::Var { name, .. } => write!(f, "?{name}"),
            PddlTerm::Const { name, .. } => f.write_str(name),
        }
    }
}

impl fmt::Display for AtomicFormula {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}", self.predicate)?;
        for a in &self.args {
            write!(f, " {a}")?;
        }
        f.write_str(")")
    }
}

impl fmt::Display for TypedVar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "?{} - {}", self.name, self.ty)
    }
}

/// `(?x - t ?y - u)`.
fn write_vars(f: &mut fmt::Formatter<'_>, vars: &[TypedVar]) -> fmt::Result {
    f.write_str("(")?;
    for (i, v) in vars.iter().enumerate() {
        if i > 0 {
            f.write_str(" ")?;
        }
        write!(f, "{v}")?;
    }
    f.write_str(")")
}

/// `(op a b ...)` for a list of displayable parts.
fn write_list<T: fmt::Display>(f: &mut fmt::Formatter<'_>, op: &str, parts: &[T]) -> fmt::Result {
    write!(f, "({op}")?;
    for p in parts {
        write!(f, " {p}")?;
    }
    f.write_str(")")
}

impl fmt::Display for Gd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            GdKind::And(gs) => write_list(f, "and", gs),
            GdKind::Or(gs) => write_list(f, "or", gs),
            GdKind::Not(g) => write!(f, "(not {g})"),
            GdKind::Imply(a, b) => write!(f, "(imply {a} {b})"),
            GdKind::Exists(vs, g) | GdKind::Forall(vs, g) => {
                let q = if matches!(self.kind, GdKind::Exists(..)) {
                    "exists"
                } else {
                    "forall"
                };
                write!(f, "({q} ")?;
                write_vars(f, vs)?;
                write!(f, " {g})")
            }
            GdKind::Atom(a) => write!(f, "{a}"),
            GdKind::Equal(a, b) => write!(f, "(= {a} {b})"),
        }
    }
}

impl fmt::Display for Effect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            EffectKind::And(es) => write_list(f, "and", es),
            EffectKind::Add(a) => write!(f, "{a}"),
            EffectKind::Delete(a) => write!(f, "(not {a})"),
            EffectKind::Forall(vs, e) => {
                f.write_str("(forall ")?;
                write_vars(f, vs)?;
                write!(f, " {e})")
            }
            EffectKind::When(g, e) => write!(f, "(when {g} {e})"),
        }
    }
}

/// A goal description in PDDL syntax, for messages (the same as its `Display`).
pub fn print_gd(gd: &Gd) -> String {
    gd.to_string()
}

/// An effect in PDDL syntax, for messages (the same as its `Display`).
pub fn print_effect(effect: &Effect) -> String {
    effect.to_string()
}
