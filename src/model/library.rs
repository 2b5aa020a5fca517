//! Plans added and removed at run time: Jason's `.add_plan` and `.remove_plan` (also written
//! `+{P}`, `+>{P}` and `-{P}`), when the plans and labels are written in the step itself.
//!
//! Every plan term such a step adds is compiled at load time into a plan of its own, after
//! the agent's plans in [`PlanLibrary::plans`](super::plans::PlanLibrary::plans); a step
//! holds the indices of its plans, or the labels it removes, and the run keeps which plans
//! the library holds, in Jason's order, with their sources. What the run needs of Jason's
//! `PlanLibrary` is worked out here once: the plans Jason's `Plan.equals` finds equal (an
//! equal plan is not added again, it only gets the new source) and the sources each label
//! carries. Anything not fixed in the text is refused with its place: a plan held in a
//! variable or a string, a variable the added plan shares with the plan that adds it (Jason
//! gives the added plan its value at run time), a label or source that is not an atom.

use super::from_ast::Converter;
use super::know_how::KnowHow;
use super::plans::{compile_plan, BodyStep, Formula, Plan, Step};
use super::term::Term;
use crate::syntax::ast::{
    self, ClearSpans, Expr, ExprKind, Item, ListExpr, Literal, PlanTermKind, StepKind, TriggerKind,
    TriggerOp,
};
use crate::syntax::{Diagnostic, LoadedAgent, Span};
use std::collections::{BTreeMap, BTreeSet, HashSet};

/// A change of the plan library made by one body step.
#[derive(Clone, Debug, PartialEq)]
pub enum LibraryChange {
    /// `.add_plan(Plans, Source, Position)`: the plans in order (indices into
    /// [`PlanLibrary::plans`](super::plans::PlanLibrary::plans), past the agent's own), with
    /// this source (bit of [`LibraryChanges::sources`]), at the beginning or at the end.
    Add {
        /// The plans.
        plans: Vec<u32>,
        /// The source.
        source: u32,
        /// `begin`: before every plan; otherwise after them.
        begin: bool,
    },
    /// `.remove_plan(Labels, Source)`: the source taken from the plans with these labels,
    /// each removed when no source is left.
    Remove {
        /// The labels, in order.
        labels: Vec<String>,
        /// The source.
        source: u32,
    },
}

/// What the run needs to change the library as Jason does, when some step changes it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LibraryChanges {
    /// How many plans are the agent's own (the initial library, in source order); the
    /// others are the plans steps may add, in the order their plan terms are met.
    pub initial: usize,
    /// Every source named (`self` first); a source mask has bit `i` for `sources[i]`.
    pub sources: Vec<String>,
    /// Per plan: the sources its label carries when it enters the library besides the one
    /// it is added with (`@l[source(bob)]`). An agent's own plan with none has `self`, as
    /// `PlanLibrary.add(Plan, boolean)` gives it.
    pub label_sources: Vec<u64>,
    /// Per added plan (index minus `initial`): the plans Jason's `Plan.equals` holds for
    /// with it as the receiver, itself included.
    pub equal: Vec<Vec<u32>>,
    /// Every label a `.remove_plan` names.
    pub removed: BTreeSet<String>,
    /// The added plans some step adds at the beginning (the others always go after the
    /// agent's own plans).
    pub at_begin: BTreeSet<u32>,
    /// The plans other agents may tell this one (`tellHow`, or the answer of its
    /// `askHow`), by the key their messages carry (see [`super::know_how`]).
    pub told: BTreeMap<String, u32>,
    /// The triggers other agents may ask this one the plans of (`askHow`), by key: the
    /// trigger's operator, kind and literal.
    pub asked: BTreeMap<String, (TriggerOp, TriggerKind, Term)>,
    /// The keys of the agent's own plans an `askHow` may answer with, by plan.
    pub answers: BTreeMap<u32, String>,
}

impl LibraryChanges {
    /// Whether plan `i` is only in the library once a step adds it.
    pub fn is_added(&self, i: usize) -> bool {
        i >= self.initial
    }
}

/// Collects the plans and changes of the steps while the agent's plans are compiled.
pub(super) struct Collector {
    initial: usize,
    /// The added plans so far (`None` while one is being compiled) and their syntax.
    added: Vec<Option<Plan>>,
    syntax: Vec<ast::Plan>,
    sources: Vec<String>,
    removed: BTreeSet<String>,
    at_begin: BTreeSet<u32>,
    used: bool,
    told: BTreeMap<String, u32>,
    asked: BTreeMap<String, (TriggerOp, TriggerKind, Term)>,
    answers: BTreeMap<u32, String>,
    /// The added plans that answer an `askHow`: their variables are anonymous.
    anonymous: BTreeSet<u32>,
}

/// A label of Jason's own making (`PlanLibrary.getUniqueLabel`): a plan it labels cannot be
/// named reliably, since the number comes from a counter shared by every agent.
fn is_generated(label: &str) -> bool {
    label
        .strip_prefix("p__")
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

fn refuse(span: Span, msg: impl Into<String>, label: &str) -> Diagnostic {
    Diagnostic::error("input", msg.into())
        .with_label(span, label)
        .with_help("write the plans and labels in the step itself: `.add_plan({ @l +!g <- a })`, `.remove_plan(l)`")
}

/// The label a string names (`"@l"`, `remove_plan.fixLabel`), if it names one.
pub(super) fn string_label(s: &str) -> Option<&str> {
    s.strip_prefix('@').filter(|n| {
        n.starts_with(|c: char| c.is_ascii_lowercase())
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    })
}

/// An atom with nothing around it: the only label and source bdi-check reads.
pub(super) fn atom(e: &Expr) -> Option<&str> {
    match &e.kind {
        ExprKind::Literal(l)
            if l.args.is_empty()
                && l.annots.is_none()
                && !l.negated
                && l.namespace.is_none()
                && !l.is_internal_action() =>
        {
            Some(&l.functor)
        }
        _ => None,
    }
}

impl Collector {
    pub(super) fn new(initial: usize) -> Collector {
        Collector {
            initial,
            added: Vec::new(),
            syntax: Vec::new(),
            sources: vec!["self".into()],
            removed: BTreeSet::new(),
            at_begin: BTreeSet::new(),
            used: false,
            told: BTreeMap::new(),
            asked: BTreeMap::new(),
            answers: BTreeMap::new(),
            anonymous: BTreeSet::new(),
        }
    }

    /// How many added plans have been met so far.
    pub(super) fn mark(&self) -> usize {
        self.added.len()
    }

    fn source(&mut self, e: Option<&Expr>) -> Result<u32, Diagnostic> {
        let Some(e) = e else { return Ok(0) };
        let name = atom(e).ok_or_else(|| {
            refuse(
                e.span,
                "the source of a plan must be an atom",
                "not an atom",
            )
        })?;
        let i = match self.sources.iter().position(|s| s == name) {
            Some(i) => i,
            None => {
                self.sources.push(name.to_string());
                self.sources.len() - 1
            }
        };
        if i >= 64 {
            return Err(refuse(
                e.span,
                "more than 64 plan sources are not modelled",
                "one too many",
            ));
        }
        Ok(i as u32)
    }

    /// A plan term's plan, compiled as a plan of its own; its index.
    fn plan_term(&mut self, p: &ast::Plan, span: Span) -> Result<u32, Diagnostic> {
        if let Some(name) = p.label.as_ref().and_then(|l| l.name.as_deref()) {
            if name.starts_with(|c: char| c.is_ascii_uppercase() || c == '_') {
                return Err(refuse(
                    span,
                    "a plan label held in a variable is not modelled",
                    "variable label",
                ));
            }
            if is_generated(name) {
                return Err(refuse(
                    span,
                    format!("the label `{name}` has the form of the labels Jason gives unlabelled plans (`p__N`), which cannot be told apart"),
                    "generated label",
                ));
            }
        }
        if p.trigger.op == ast::TriggerOp::GoalState {
            return Err(refuse(
                span,
                "adding a plan for goal-state events (`^!g`) is not modelled",
                "goal-state trigger",
            ));
        }
        let k = self.added.len();
        let index = self.initial + k;
        self.added.push(None);
        self.syntax.push(p.clone());
        let mut plan = compile_plan(index, p, true, self)?;
        // `PlanLibrary.add(Plan, Term, boolean)` gives `@undefined` (what the parser makes
        // of `@[annots]`) a label of its own making, as a plan without one.
        if plan.label.as_deref() == Some("undefined") || dropped_label(p) {
            plan.label = None;
        }
        self.added[k] = Some(plan);
        Ok(index as u32)
    }

    /// The plans of `.add_plan`'s first argument: a plan term or a list of them.
    fn plans(&mut self, e: &Expr) -> Result<Vec<u32>, Diagnostic> {
        match &e.kind {
            ExprKind::PlanTerm(t) => match &t.kind {
                PlanTermKind::Plan(p) => Ok(vec![self.plan_term(p, e.span)?]),
                _ => Err(refuse(
                    e.span,
                    "`.add_plan` needs a whole plan: this term in braces is a trigger, a body or a rule (Jason refuses it)",
                    "not a plan",
                )),
            },
            ExprKind::List(ListExpr { tail: Some(_), .. }) => Err(refuse(
                e.span,
                "`.add_plan` with a list whose tail is not written out is not modelled",
                "open list",
            )),
            ExprKind::List(ListExpr { elems, .. }) => elems
                .iter()
                .map(|x| match &x.kind {
                    ExprKind::PlanTerm(_) => Ok(self.plans(x)?[0]),
                    _ => Err(self.not_fixed(x)),
                })
                .collect(),
            _ => Err(self.not_fixed(e)),
        }
    }

    fn not_fixed(&self, e: &Expr) -> Diagnostic {
        let what = match &e.kind {
            ExprKind::Var(_) => "a plan held in a variable (known only at run time)",
            ExprKind::Str(_) => "a plan given as a string",
            _ => "this argument",
        };
        refuse(
            e.span,
            format!("`.add_plan` with {what} is not modelled"),
            "not a plan term",
        )
    }

    /// `.add_plan(Plans[, Source[, Position]])`.
    pub(super) fn add_plan(
        &mut self,
        l: &Literal,
        span: Span,
    ) -> Result<LibraryChange, Diagnostic> {
        if l.args.is_empty() || l.args.len() > 3 {
            return Err(refuse(span, "`.add_plan` takes 1 to 3 arguments", "here"));
        }
        let plans = self.plans(&l.args[0])?;
        let source = self.source(l.args.get(1))?;
        // `add_plan.execute`: the position is `begin` when it prints as `begin`.
        let begin = match l.args.get(2) {
            None => false,
            Some(e) => {
                atom(e).ok_or_else(|| {
                    refuse(
                        e.span,
                        "the position of a plan must be `begin` or `end`",
                        "not an atom",
                    )
                })? == "begin"
            }
        };
        self.added(plans, source, begin)
    }

    fn added(
        &mut self,
        plans: Vec<u32>,
        source: u32,
        begin: bool,
    ) -> Result<LibraryChange, Diagnostic> {
        if begin {
            self.at_begin.extend(plans.iter().copied());
        }
        self.used = true;
        Ok(LibraryChange::Add {
            plans,
            source,
            begin,
        })
    }

    /// `+{P}` (at the beginning) and `+>{P}` (at the end): the parser's `.add_plan(P, self,
    /// begin|end)` (AS2JavaParser.jj, `body_formula`).
    pub(super) fn add_term(&mut self, e: &Expr, begin: bool) -> Result<LibraryChange, Diagnostic> {
        let plans = self.plans(e)?;
        self.added(plans, 0, begin)
    }

    /// A label of `.remove_plan`: an atom, `"@l"` (`remove_plan.fixLabel`), or a plan term's.
    fn label(&self, e: &Expr) -> Result<String, Diagnostic> {
        let name = match &e.kind {
            ExprKind::Str(s) => string_label(s),
            ExprKind::PlanTerm(t) => match &t.kind {
                PlanTermKind::Plan(p) => p.label.as_ref().and_then(|l| l.name.as_deref()),
                _ => None,
            },
            _ => atom(e),
        };
        let name = name.ok_or_else(|| {
            refuse(
                e.span,
                "`.remove_plan` needs a plan label here (an atom, or a plan term with a label)",
                "not a label",
            )
        })?;
        if is_generated(name) || name.starts_with(|c: char| c.is_ascii_uppercase() || c == '_') {
            return Err(refuse(
                e.span,
                format!("the label `{name}` cannot name a plan of the model (variables and Jason's generated `p__N` labels are not modelled)"),
                "not a label",
            ));
        }
        Ok(name.to_string())
    }

    /// `.remove_plan(Labels[, Source])`.
    pub(super) fn remove_plan(
        &mut self,
        l: &Literal,
        span: Span,
    ) -> Result<LibraryChange, Diagnostic> {
        if l.args.is_empty() || l.args.len() > 2 {
            return Err(refuse(
                span,
                "`.remove_plan` takes 1 or 2 arguments",
                "here",
            ));
        }
        let labels = match &l.args[0].kind {
            ExprKind::List(ListExpr { elems, tail, .. }) if tail.is_none() => elems
                .iter()
                .map(|x| match x.kind {
                    ExprKind::PlanTerm(_) => Err(refuse(
                        x.span,
                        "a plan term in the list of `.remove_plan` names no label (Jason reads it as a label and finds no plan)",
                        "not a label",
                    )),
                    _ => self.label(x),
                })
                .collect::<Result<Vec<_>, _>>()?,
            _ => vec![self.label(&l.args[0])?],
        };
        let source = self.source(l.args.get(1))?;
        self.removed.extend(labels.iter().cloned());
        self.used = true;
        Ok(LibraryChange::Remove { labels, source })
    }

    /// `-{P}`: the parser's `.remove_plan(P)`.
    pub(super) fn remove_term(&mut self, e: &Expr) -> Result<LibraryChange, Diagnostic> {
        let label = self.label(e)?;
        self.removed.insert(label.clone());
        self.used = true;
        Ok(LibraryChange::Remove {
            labels: vec![label],
            source: 0,
        })
    }

    /// What other agents may tell, untell and ask this library (see [`super::know_how`]):
    /// the told plans compiled as added plans, every agent a source they may have.
    pub(super) fn know_how(&mut self, kh: &KnowHow) -> Result<(), Diagnostic> {
        if kh.is_empty() && kh.answers.is_empty() {
            return Ok(());
        }
        self.used = true;
        for name in &kh.agents {
            if !self.sources.contains(name) {
                self.sources.push(name.clone());
            }
        }
        if self.sources.len() > 64 {
            let span = kh.told.first().map_or(Span::default(), |t| t.plan.span);
            return Err(refuse(
                span,
                "more than 64 plan sources (agents) are not modelled",
                "told here",
            ));
        }
        for t in &kh.told {
            let i = self.plan_term(&t.plan, t.plan.span)?;
            if t.answer {
                self.anonymous.insert(i);
            }
            self.told.insert(t.key.clone(), i);
        }
        self.removed.extend(kh.untold.iter().cloned());
        for a in &kh.asked {
            let ExprKind::Literal(l) = &a.trigger.literal.kind else {
                continue;
            };
            let literal = Converter::for_plans()
                .literal(l)
                .map_err(super::plans::convert_error)?;
            self.asked
                .insert(a.key.clone(), (a.trigger.op, a.trigger.kind, literal));
        }
        for (i, key) in &kh.answers {
            self.answers.insert(*i as u32, key.clone());
        }
        Ok(())
    }

    /// `plan` was just compiled, and the added plans from `first` on were met inside it:
    /// none of them may share a variable with it (Jason's `Plan.capply` gives an added plan
    /// the adding plan's bindings when the step runs).
    pub(super) fn check_shared(&self, plan: &Plan, first: usize) -> Result<(), Diagnostic> {
        let own: HashSet<String> = named_vars(plan).collect();
        for k in first..self.added.len() {
            let Some(inner) = &self.added[k] else {
                continue;
            };
            if let Some(v) = named_vars(inner).find(|v| own.contains(v)) {
                return Err(Diagnostic::error(
                    "input",
                    format!("the added plan shares the variable `{v}` with the plan that adds it: Jason gives it that variable's value when the step runs, which is not modelled"),
                )
                .with_label(inner.span, format!("uses `{v}`"))
                .with_secondary(plan.span, "in this plan too")
                .with_help("rename the variable in the added plan, or write one added plan per value"));
            }
        }
        Ok(())
    }

    /// What an agent whose steps change its library may not have: labels in namespaces, and
    /// two plans of its own with one label. `plans` are the agent's own (those that compiled).
    pub(super) fn refusals(&self, agent: &LoadedAgent, plans: &[Plan]) -> Vec<Diagnostic> {
        let mut errors = Vec::new();
        if !self.used {
            return errors;
        }
        if let Some(span) = namespaced(agent) {
            errors.push(
                Diagnostic::error(
                    "input",
                    "plan labels in namespaces are not modelled in an agent that adds or removes plans",
                )
                .with_label(span, "a namespace"),
            );
        }
        // `PlanLibrary.add(Plan, boolean)` refuses a second plan with a label already taken
        // when the agent loads.
        for (i, p) in plans.iter().enumerate() {
            let Some(l) = &p.label else { continue };
            if let Some(q) = plans[..i].iter().find(|q| q.label.as_ref() == Some(l)) {
                errors.push(
                    Diagnostic::error(
                        "input",
                        format!("two plans have the label `{l}` (Jason refuses the second one)"),
                    )
                    .with_label(p.span, "second")
                    .with_secondary(q.span, "first"),
                );
            }
        }
        errors
    }

    /// The added plans, in index order, and what the run needs to add and remove them
    /// (`None` when no step changes the library). `plans` are the agent's own, every one
    /// compiled, and [`Collector::refusals`] found nothing.
    pub(super) fn finish(
        self,
        agent: &LoadedAgent,
        plans: &[Plan],
    ) -> Result<(Vec<Plan>, Option<LibraryChanges>), Vec<Diagnostic>> {
        if !self.used {
            return Ok((Vec::new(), None));
        }
        let mut errors = Vec::new();
        let own: Vec<&ast::Plan> = agent
            .items()
            .into_iter()
            .filter_map(|i| match i {
                Item::Plan(p) => Some(p),
                _ => None,
            })
            .collect();
        let added: Vec<Plan> = self.added.into_iter().flatten().collect();
        // Jason gives a plan without a source in its label `source(self)`.
        let mut sources = self.sources;
        let mut label_sources = Vec::new();
        let syntax = own.iter().copied().chain(&self.syntax);
        for (i, p) in syntax.clone().enumerate() {
            if i >= plans.len() && dropped_label(p) {
                label_sources.push(0);
                continue;
            }
            match label_sources_of(p, &mut sources) {
                Ok(0) if i < plans.len() => label_sources.push(1),
                Ok(m) => label_sources.push(m),
                Err(d) => errors.push(d),
            }
        }
        let shapes: Vec<Shape> = syntax
            .enumerate()
            .map(|(i, p)| {
                let mut shape = Shape::of(p, i >= plans.len());
                shape.unnamed |= self.anonymous.contains(&(i as u32));
                shape
            })
            .collect();
        let n = plans.len();
        // A plan with an unnamed variable (`_`, `_X`) equals only itself: each occurrence
        // is an `UnnamedVar` with an id of its own.
        let equal = (n..shapes.len())
            .map(|d| {
                (0..shapes.len())
                    .filter(|&p| {
                        // An `askHow`'s answer is a new copy each time
                        // (`Plan.makeVarsAnnon`): not even equal to the last one.
                        p == d && !self.anonymous.contains(&(d as u32))
                            || !shapes[d].unnamed
                                && !shapes[p].unnamed
                                && shapes[d].equals(&shapes[p])
                    })
                    .map(|p| p as u32)
                    .collect()
            })
            .collect();
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok((
            added,
            Some(LibraryChanges {
                initial: n,
                sources,
                label_sources,
                equal,
                removed: self.removed,
                at_begin: self.at_begin,
                told: self.told,
                asked: self.asked,
                answers: self.answers,
            }),
        ))
    }
}

/// Whether `add_plan.transform2plan` drops the label of a plan term, annotations and all:
/// the labels older Jasons generated (`l__N`).
fn dropped_label(p: &ast::Plan) -> bool {
    p.label
        .as_ref()
        .and_then(|l| l.name.as_deref())
        .is_some_and(|l| l.starts_with("l__"))
}

/// The sources a label names (`@l[source(a), source(b)]`), as a mask over `sources` (to
/// which new ones are added).
fn label_sources_of(p: &ast::Plan, sources: &mut Vec<String>) -> Result<u64, Diagnostic> {
    let mut mask = 0;
    let Some(annots) = p.label.as_ref().and_then(|l| l.annots.as_ref()) else {
        return Ok(0);
    };
    for a in &annots.elems {
        let ExprKind::Literal(l) = &a.kind else {
            continue;
        };
        if l.functor != "source" || l.args.len() != 1 {
            continue;
        }
        let name = atom(&l.args[0]).ok_or_else(|| {
            refuse(
                a.span,
                "the source of a plan must be an atom",
                "not an atom",
            )
        })?;
        let i = match sources.iter().position(|x| x == name) {
            Some(i) => i,
            None => {
                sources.push(name.to_string());
                sources.len() - 1
            }
        };
        if i >= 64 {
            return Err(refuse(
                a.span,
                "more than 64 plan sources are not modelled",
                "one too many",
            ));
        }
        mask |= 1 << i;
    }
    Ok(mask)
}

/// The first place where the agent puts items in a namespace, if any.
fn namespaced(agent: &LoadedAgent) -> Option<Span> {
    fn walk(items: &[Item]) -> Option<Span> {
        items.iter().find_map(|i| match i {
            Item::Directive(d) if d.block.is_some() && d.name == "namespace" => Some(d.span),
            Item::Directive(d) => d.block.as_deref().and_then(walk),
            _ => None,
        })
    }
    agent
        .included
        .iter()
        .find(|i| i.namespace.is_some())
        .map(|i| i.directive)
        .or_else(|| agent.files.iter().find_map(|(_, f)| walk(&f.items)))
}

/// What Jason's `Plan.equals` compares: the trigger, the context (`None` when the plan has
/// none: `: true` is a context) and the body as the parser gives it, spans aside.
struct Shape {
    trigger: ast::Trigger,
    context: Option<Expr>,
    body: Vec<ast::Step>,
    /// Whether an unnamed variable occurs in the plan's terms, its plan terms included.
    unnamed: bool,
}

impl Shape {
    fn of(p: &ast::Plan, term: bool) -> Shape {
        let mut trigger = p.trigger.clone();
        trigger.clear_spans();
        let mut context = p.context.clone();
        if let Some(c) = &mut context {
            c.clear_spans();
        }
        // The parser drops a leading `true` from an agent's plan, not from a plan term.
        let body = if term { p.body.clone() } else { p.jason_body() };
        let mut body = body.map(|b| b.steps).unwrap_or_default();
        body.clear_spans();
        let text = crate::syntax::printer::print_plan(p);
        Shape {
            trigger,
            context,
            body,
            unnamed: text_has_unnamed(&text),
        }
    }

    /// `self.equals(other)`: the receiver's missing context equals no context but none,
    /// while a context of the receiver is not compared with a missing one (`Plan.equals`).
    fn equals(&self, other: &Shape) -> bool {
        let context = match (&self.context, &other.context) {
            (None, Some(_)) => false,
            (Some(a), Some(b)) => a == b,
            _ => true,
        };
        context && self.trigger == other.trigger && self.body == other.body
    }
}

/// Whether Jason text holds an unnamed variable (`_`, `_X`) outside strings.
fn text_has_unnamed(text: &str) -> bool {
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            q @ (b'"' | b'\'') => {
                i += 1;
                while i < b.len() && b[i] != q {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
            }
            b'_' if i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_') => {
                return true;
            }
            _ => {}
        }
        i += 1;
    }
    false
}

/// The named variables of a compiled plan (those of the plans it adds are not in it).
fn named_vars(p: &Plan) -> impl Iterator<Item = String> + '_ {
    plan_vars(p)
        .filter(|v| !v.is_anonymous())
        .map(|v| v.name().to_string())
}

fn plan_vars(p: &Plan) -> impl Iterator<Item = super::term::Var> + '_ {
    let mut terms: Vec<&Term> = vec![&p.trigger.literal];
    formula_terms(&p.context, &mut terms);
    steps_terms(&p.body, &mut terms);
    terms.into_iter().flat_map(|t| t.vars())
}

fn formula_terms<'a>(f: &'a Formula, out: &mut Vec<&'a Term>) {
    match f {
        Formula::True => {}
        Formula::Literal(t) | Formula::Call(t) => out.push(t),
        Formula::Not(g) => formula_terms(g, out),
        Formula::And(a, b) | Formula::Or(a, b) => {
            formula_terms(a, out);
            formula_terms(b, out);
        }
        Formula::Rel(_, a, b) => {
            out.push(a);
            out.push(b);
        }
    }
}

fn steps_terms<'a>(steps: &'a [Step], out: &mut Vec<&'a Term>) {
    for s in steps {
        match &s.kind {
            BodyStep::Action(t)
            | BodyStep::Internal(t)
            | BodyStep::Achieve { goal: t, .. }
            | BodyStep::AddBel(t)
            | BodyStep::DelBel(t)
            | BodyStep::DelAddBel(t) => out.push(t),
            BodyStep::Test(f) => formula_terms(f, out),
            BodyStep::Constraint(_, a, b) => {
                out.push(a);
                out.push(b);
            }
            BodyStep::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    formula_terms(c, out);
                    steps_terms(b, out);
                }
                steps_terms(else_body, out);
            }
            BodyStep::While(c, b) | BodyStep::For(c, b) => {
                formula_terms(c, out);
                steps_terms(b, out);
            }
            BodyStep::Wait {
                event,
                condition,
                timeout,
            } => {
                out.extend(event.iter().map(|e| &e.literal));
                if let Some(c) = condition {
                    formula_terms(c, out);
                }
                out.extend(timeout.iter());
            }
            BodyStep::Library { .. } => {}
        }
    }
}

/// Whether a body step of the syntax changes the plan library (so the step is compiled by
/// this module).
pub(super) fn changes_library(s: &ast::Step) -> bool {
    match &s.kind {
        StepKind::Action(e) => matches!(&e.kind, ExprKind::Literal(l)
            if matches!(l.functor.as_str(), ".add_plan" | ".remove_plan")),
        // The parser allows a plan term after these only (AS2JavaParser.jj, `body_formula`).
        StepKind::AddBel(e) | StepKind::AddBelEnd(e) | StepKind::DelBel(e) => {
            matches!(e.kind, ExprKind::PlanTerm(_))
        }
        _ => false,
    }
}
