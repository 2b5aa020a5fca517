//! The plan library `Π` of the paper's model: every plan compiled from the AST into model
//! terms, with its trigger, context and body, ready for the static checks and for the
//! reasoning cycle.
//!
//! Variables are per plan (one [`Converter`] per plan, so `_` is fresh at each occurrence
//! and named variables are shared by trigger, context and body). Arithmetic that cannot be
//! evaluated at load time (`N + 1`) is kept as a structure whose functor is the operator
//! (`+`, `-`, `*`, `/`, `div`, `mod`, `**`), to be evaluated once its variables are bound;
//! users cannot write such functors unquoted, so they never clash with a literal.

use super::from_ast::{ConvertError, Converter};
use super::know_how::KnowHow;
use super::library::{changes_library, Collector, LibraryChange, LibraryChanges};
use super::term::Term;
use crate::syntax::ast::{
    self, Expr, ExprKind, Item, RelOp, StepKind, TriggerKind, TriggerOp, UnaryOp,
};
use crate::syntax::{Diagnostic, LoadedAgent, Span};

/// A logical formula over terms: a plan context, a test goal, a condition of `if`/`while`.
#[derive(Clone, Debug, PartialEq)]
pub enum Formula {
    /// Always holds.
    True,
    /// A literal queried against the beliefs (it may hold variables).
    Literal(Term),
    /// Negation as failure.
    Not(Box<Formula>),
    /// Both.
    And(Box<Formula>, Box<Formula>),
    /// Either (answers of the left first).
    Or(Box<Formula>, Box<Formula>),
    /// A relation between two terms (arithmetic evaluated when bound).
    Rel(RelOp, Term, Term),
    /// An internal action used as a condition: `.count(q, N)`, `.desire(g)`, `.member(x, l)`.
    Call(Term),
}

impl Formula {
    /// Every literal the formula queries, with whether it occurs under an odd number of
    /// `not`s (a negative occurrence).
    pub fn literals(&self) -> Vec<(&Term, bool)> {
        let mut out = Vec::new();
        self.collect(false, &mut out);
        out
    }

    fn collect<'a>(&'a self, negative: bool, out: &mut Vec<(&'a Term, bool)>) {
        match self {
            Formula::True | Formula::Rel(..) | Formula::Call(_) => {}
            Formula::Literal(t) => out.push((t, negative)),
            Formula::Not(f) => f.collect(!negative, out),
            Formula::And(a, b) | Formula::Or(a, b) => {
                a.collect(negative, out);
                b.collect(negative, out);
            }
        }
    }
}

/// One step of a plan body.
#[derive(Clone, Debug, PartialEq)]
pub enum BodyStep {
    /// An environment action `a(x)`.
    Action(Term),
    /// An internal action `.print(x)`.
    Internal(Term),
    /// `!g` (`new_focus`: `!!g`).
    Achieve {
        /// The goal literal.
        goal: Term,
        /// `!!g`: in a new intention.
        new_focus: bool,
    },
    /// `?f`.
    Test(Formula),
    /// `+b` (also `+>b`, `++b`).
    AddBel(Term),
    /// `-b` (also `--b`).
    DelBel(Term),
    /// `-+b`.
    DelAddBel(Term),
    /// `X = Y + 1`, `N > 0` as a step.
    Constraint(RelOp, Term, Term),
    /// `if (c) {...} elif ... else {...}`.
    If {
        /// Conditions and bodies, in order.
        branches: Vec<(Formula, Vec<Step>)>,
        /// The `else` body (empty when absent).
        else_body: Vec<Step>,
    },
    /// `while (c) {...}`.
    While(Formula, Vec<Step>),
    /// `for (c) {...}`.
    For(Formula, Vec<Step>),
    /// `.wait(...)` (stdlib `wait`): the intention is suspended until the event (`{+b}`)
    /// comes, until the condition holds, or until its timeout; `.wait(N)` waits for the
    /// timeout alone.
    Wait {
        /// The event waited for: `{+b(X)}`.
        event: Option<Trigger>,
        /// The condition waited for: `.wait(b(X) & X > 1)`.
        condition: Option<Formula>,
        /// The timeout in milliseconds, as written (evaluated when the step runs).
        timeout: Option<Term>,
    },
    /// `.add_plan`, `.remove_plan`, `+{P}`, `+>{P}` or `-{P}`, its plans and labels written
    /// in the step (see [`super::library`]).
    Library {
        /// What it changes.
        change: LibraryChange,
        /// The step as Jason text, for traces.
        text: String,
        /// Whether it is written as a call (`.add_plan(...)`): the parser builds the call
        /// of `+{P}`, `+>{P}` and `-{P}` with no place, so their failure events say
        /// `code_line(no_code)` (AS2JavaParser.jj, `body_formula`; `Literal.addSourceInfoAsAnnots`).
        call: bool,
    },
}

/// A body step with its place.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// What it does.
    pub kind: BodyStep,
    /// Where it is written.
    pub span: Span,
}

/// A plan's triggering event.
#[derive(Clone, Debug, PartialEq)]
pub struct Trigger {
    /// `+`, `-` or `^`.
    pub op: TriggerOp,
    /// Belief, achievement or test goal.
    pub kind: TriggerKind,
    /// The literal.
    pub literal: Term,
}

impl std::fmt::Display for Trigger {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (op, kind) = (self.op.symbol(), self.kind.symbol());
        write!(f, "{op}{kind}{}", self.literal)
    }
}

/// A plan of the library.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Its position in source order (Jason's default selection picks the first applicable).
    pub index: usize,
    /// `@label`, if any.
    pub label: Option<String>,
    /// The triggering event.
    pub trigger: Trigger,
    /// The context (`True` when absent).
    pub context: Formula,
    /// The body.
    pub body: Vec<Step>,
    /// The plan's span (its start is the plan's location in reports).
    pub span: Span,
    /// The context's span, if written.
    pub context_span: Option<Span>,
    /// Its label says `[atomic]` (`Plan.setLabel`: an annotation equal to the atom
    /// `atomic`): while it is on an intention's stack, that intention runs alone, Jason's
    /// `Circumstance.AI` (see `src/semantics/atomic.rs`).
    pub atomic: bool,
}

impl Plan {
    /// A name for messages: the label, or the trigger.
    pub fn name(&self) -> String {
        match &self.label {
            Some(l) => format!("@{l}"),
            None => self.trigger.to_string(),
        }
    }
}

/// A rule `head :- body.` of the belief base.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// The head literal.
    pub head: Term,
    /// The body.
    pub body: Formula,
    /// Where it is written.
    pub span: Span,
}

/// The plan library, in source order (includes expanded where they stand).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlanLibrary {
    /// Every plan: the agent's own, then those its steps may add at run time (see
    /// [`PlanLibrary::changes`]).
    pub plans: Vec<Plan>,
    /// The rules of the belief base, in source order.
    pub rules: Vec<Rule>,
    /// The agent's initial goals `!g.`, in order.
    pub initial_goals: Vec<(Term, Span)>,
    /// What adding and removing plans at run time needs, when some step does.
    pub changes: Option<LibraryChanges>,
}

impl PlanLibrary {
    /// Compiles the plans of a loaded agent, and the plans its steps add (see
    /// [`super::library`]). Constructs the model checker does not model (forks, goal
    /// conditions, sub-plans, plans added that are not written in the step) are refused with
    /// a located error.
    ///
    /// `know_how` is what other agents may tell, untell and ask it
    /// ([`super::know_how::collect`]; empty for an agent alone).
    pub fn compile(
        agent: &LoadedAgent,
        know_how: &KnowHow,
    ) -> Result<PlanLibrary, Vec<Diagnostic>> {
        let mut lib = PlanLibrary::default();
        let mut errors = Vec::new();
        let items = agent.items();
        let own = items.iter().filter(|i| matches!(i, Item::Plan(_))).count();
        let mut added = Collector::new(own);
        for item in items {
            match item {
                Item::Plan(p) => match compile_plan(lib.plans.len(), p, false, &mut added) {
                    Ok(plan) => lib.plans.push(plan),
                    Err(d) => errors.push(d),
                },
                Item::Rule(r) => {
                    let mut conv = Converter::new();
                    let head = conv.literal(&r.head).map_err(convert_error);
                    let body = formula(&mut conv, &r.body);
                    match (head, body) {
                        (Ok(head), Ok(body)) => lib.rules.push(Rule {
                            head,
                            body,
                            span: r.span,
                        }),
                        (Err(d), _) | (_, Err(d)) => errors.push(d),
                    }
                }
                Item::InitialGoal(g) => {
                    let mut conv = Converter::new();
                    match conv.literal(&g.literal) {
                        Ok(t) => lib.initial_goals.push((t, g.span)),
                        Err(e) => errors.push(convert_error(e)),
                    }
                }
                _ => {}
            }
        }
        if let Err(d) = added.know_how(know_how) {
            errors.push(d);
        }
        errors.extend(added.refusals(agent, &lib.plans));
        if !errors.is_empty() {
            return Err(errors);
        }
        let (more, changes) = added.finish(agent, &lib.plans)?;
        lib.plans.extend(more);
        lib.changes = changes;
        // An `askHow` is answered with the plans the receiver holds then: they must be
        // fixed, as the asker's library holds each answer compiled.
        for a in &know_how.asked {
            let changing = (0..lib.plans.len()).find(|&i| {
                lib.may_change(i) && {
                    let p = &lib.plans[i];
                    p.trigger.op == a.trigger.op
                        && p.trigger.kind == a.trigger.kind
                        && matches!(&a.trigger.literal.kind, ExprKind::Literal(l)
                            if p.trigger.literal.functor() == Some(l.functor.as_str())
                                && p.trigger.literal.arity() == l.args.len())
                }
            });
            if let Some(i) = changing {
                errors.push(
                    Diagnostic::error(
                        "input",
                        "`askHow` of plans the receiver may add or remove at run time is not modelled",
                    )
                    .with_label(a.span, "asks for them")
                    .with_secondary(lib.plans[i].span, "may be added or removed"),
                );
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok(lib)
    }

    /// Whether plan `i` is only in the library once a step adds it (`.add_plan`).
    pub fn is_added(&self, i: usize) -> bool {
        self.changes.as_ref().is_some_and(|c| c.is_added(i))
    }

    /// Whether whether plan `i` is in the library, or where, can change at run time: it is
    /// added by a step, or a `.remove_plan` names its label.
    pub fn may_change(&self, i: usize) -> bool {
        self.changes.as_ref().is_some_and(|c| {
            c.is_added(i)
                || self.plans[i]
                    .label
                    .as_ref()
                    .is_some_and(|l| c.removed.contains(l))
        })
    }

    /// Whether plans `i` and `j` can never be in the library at once: Jason's
    /// `PlanLibrary` holds one plan per label (adding a second throws), and a plan equal to
    /// one it holds is not added again (the held one gets the source).
    pub fn never_together(&self, i: usize, j: usize) -> bool {
        let Some(c) = &self.changes else {
            return false;
        };
        let same_label =
            self.plans[i].label.is_some() && self.plans[i].label == self.plans[j].label;
        let equal =
            |a: usize, b: usize| c.is_added(a) && c.equal[a - c.initial].contains(&(b as u32));
        (c.is_added(i) || c.is_added(j)) && (same_label || equal(i, j) || equal(j, i))
    }

    /// Whether some step adds plan `i` at the beginning of the library (before the agent's
    /// own plans).
    pub fn added_at_begin(&self, i: usize) -> bool {
        self.changes
            .as_ref()
            .is_some_and(|c| c.at_begin.contains(&(i as u32)))
    }

    /// The plans relevant for a trigger kind and functor/arity, in source order.
    pub fn relevant<'a>(
        &'a self,
        op: TriggerOp,
        kind: TriggerKind,
        functor: &'a str,
        arity: usize,
    ) -> impl Iterator<Item = &'a Plan> + 'a {
        self.plans.iter().filter(move |p| {
            p.trigger.op == op
                && p.trigger.kind == kind
                && p.trigger.literal.functor() == Some(functor)
                && p.trigger.literal.arity() == arity
        })
    }
}

pub(super) fn convert_error(e: ConvertError) -> Diagnostic {
    Diagnostic::error("input", e.message).with_label(e.span, "here")
}

/// Jason's failure annotations the model does not give (their values name Jason's own
/// variables, file URLs and exception texts).
const FAILURE_ANNOTS_NOT_GIVEN: &[&str] = &["error_msg", "code", "code_src"];

fn unsupported(span: Span, what: &str) -> Diagnostic {
    Diagnostic::error("input", format!("{what} are not modelled by bdi-check yet"))
        .with_label(span, "not supported by the model checker")
        .with_help("rewrite this part of the plan without it, or leave the plan out of the checked library")
}

/// Compiles plan `p` as plan `index`: one of the agent's own, or (`term`) a plan term a
/// step adds, whose body is kept as written (the parser drops a leading `true` only from
/// the agent's own plans). The plans its steps add go to `added`.
pub(super) fn compile_plan(
    index: usize,
    p: &ast::Plan,
    term: bool,
    added: &mut Collector,
) -> Result<Plan, Diagnostic> {
    let first_added = added.mark();
    if p.goal_condition.is_some() {
        return Err(unsupported(p.span, "goal conditions (`<:`)"));
    }
    if !p.sub_plans.is_empty() {
        return Err(unsupported(p.span, "sub-plans"));
    }
    // Label annotations that change how Jason runs the plan (`Plan.setLabel`): `atomic`
    // is modelled; `all_unifs` is refused rather than run as if it were not written.
    if let Some(annots) = p.label.as_ref().and_then(|l| l.annots.as_ref()) {
        for a in &annots.elems {
            if let ExprKind::Literal(l) = &a.kind {
                if l.args.is_empty() && l.functor == "all_unifs" {
                    return Err(unsupported(a.span, "plans labelled `[all_unifs]`"));
                }
            }
        }
    }
    let mut c = Converter::for_plans();
    let literal = match &p.trigger.literal.kind {
        ExprKind::Literal(l) => c.literal(l).map_err(convert_error)?,
        _ => return Err(unsupported(p.trigger.span, "variables as triggers")),
    };
    // Jason annotates a failure event with `error`, `code_line`, `error_msg`, `code` and
    // `code_src` (`JasonException.createBasicErrorAnnots`); the model gives the first two.
    // A trigger that asks for another would never be relevant here while it is in Jason:
    // refused rather than silently dead.
    if p.trigger.op == TriggerOp::Del && p.trigger.kind != TriggerKind::Belief {
        let asked = literal.annots().iter().find_map(|a| {
            a.functor()
                .filter(|f| FAILURE_ANNOTS_NOT_GIVEN.contains(f))
                .map(str::to_string)
        });
        if let Some(name) = asked {
            return Err(Diagnostic::error(
                "input",
                format!("the failure annotation `{name}` is not given by bdi-check yet"),
            )
            .with_label(p.trigger.span, "asks for it")
            .with_help("failure events carry `error(Id)` and `code_line(L)` here; match on those, or leave the annotation out"));
        }
    }
    let context = match &p.context {
        Some(e) => formula(&mut c, e)?,
        None => Formula::True,
    };
    // `<- true` is the empty body (see `ast::Plan::jason_body`).
    let body = if term { p.body.clone() } else { p.jason_body() };
    let body = match &body {
        Some(b) => steps(&mut c, &b.steps, added)?,
        None => Vec::new(),
    };
    let plan = Plan {
        index,
        label: p.label.as_ref().and_then(|l| l.name.clone()),
        trigger: Trigger {
            op: p.trigger.op,
            kind: p.trigger.kind,
            literal,
        },
        context,
        body,
        span: p.span,
        context_span: p.context.as_ref().map(|e| e.span),
        atomic: p.label.as_ref().is_some_and(is_atomic_label),
    };
    added.check_shared(&plan, first_added)?;
    Ok(plan)
}

/// Whether a plan's label makes it atomic: Jason's `Plan.setLabel` marks a plan atomic
/// when one of its label's annotations equals the atom `atomic` (`Atom.equals`: no
/// arguments, annotations, strong negation or namespace).
pub(crate) fn is_atomic_label(label: &ast::Label) -> bool {
    label.annots.as_ref().is_some_and(|a| {
        a.elems.iter().any(|e| {
            matches!(&e.kind, ExprKind::Literal(l) if l.functor == "atomic"
                && l.args.is_empty()
                && l.annots.is_none()
                && !l.negated
                && l.namespace.is_none())
        })
    })
}

/// A `.send` or `.broadcast` of `tellHow`, `untellHow` or `askHow`: its content as the
/// message carries it, the keys of the plans or of the trigger (see
/// [`super::know_how`]), or the labels.
fn know_how_send(c: &mut Converter, l: &ast::Literal, span: Span) -> Result<Term, Diagnostic> {
    use super::know_how::{asked_trigger, told_plans, trigger_key, untold_labels};
    let (performative, _, content) =
        super::know_how::know_how_message(l).expect("a know-how message");
    let content = match performative {
        "tellHow" => {
            let keys: Vec<Term> = told_plans(content)?
                .iter()
                .map(|(key, _)| Term::string(key))
                .collect();
            match content.kind {
                ExprKind::List(_) => Term::list(keys),
                _ => keys.into_iter().next().expect("one plan"),
            }
        }
        "untellHow" => {
            let labels: Vec<Term> = untold_labels(content)?
                .iter()
                .map(|l| Term::atom(l))
                .collect();
            match content.kind {
                ExprKind::List(_) => Term::list(labels),
                _ => labels.into_iter().next().expect("one label"),
            }
        }
        _ => Term::string(&trigger_key(&asked_trigger(content)?)),
    };
    let at = if l.functor == ".send" { 2 } else { 1 };
    let mut args = Vec::with_capacity(l.args.len());
    for (i, a) in l.args.iter().enumerate() {
        args.push(if i == at {
            content.clone()
        } else {
            c.term(a).map_err(convert_error)?
        });
    }
    if l.annots.is_some() || l.namespace.is_some() {
        return Err(unsupported(span, "annotated `.send` steps"));
    }
    Ok(Term::structure(&l.functor, args))
}

/// A term, or an arithmetic expression kept as an operator structure.
fn value(c: &mut Converter, e: &Expr) -> Result<Term, Diagnostic> {
    match &e.kind {
        ExprKind::Arith(op, a, b) => match c.term(e) {
            Ok(t) => Ok(t),
            Err(_) => {
                let name = op.symbol();
                Ok(Term::structure(name, vec![value(c, a)?, value(c, b)?]))
            }
        },
        ExprKind::Unary(UnaryOp::Neg, inner) => match c.term(e) {
            Ok(t) => Ok(t),
            Err(_) => Ok(Term::structure("-", vec![value(c, inner)?])),
        },
        _ => c.term(e).map_err(convert_error),
    }
}

/// `.wait(E)`, `.wait(E, T)` as a step (stdlib `wait.execute`): a number is a timeout
/// alone, `{+b}` an event, anything else a condition; with an event or a condition the
/// second argument is the timeout. The third argument, the time waited, is refused:
/// the model has no clock.
fn wait(c: &mut Converter, l: &ast::Literal) -> Result<BodyStep, Diagnostic> {
    let (Some(first), 1..=2) = (l.args.first(), l.args.len()) else {
        let d = match l.args.get(2) {
            Some(third) => Diagnostic::error(
                "input",
                "the time waited (the third argument of `.wait`) is not modelled by bdi-check: the model has no clock",
            )
            .with_label(third.span, "elapsed time"),
            None => Diagnostic::error("input", "`.wait` takes 1 or 2 arguments")
                .with_label(l.span, "wrong number of arguments"),
        };
        return Err(d);
    };
    let mut step = (None, None, None);
    match &first.kind {
        ExprKind::Int(_)
        | ExprKind::Float(_)
        | ExprKind::Arith(..)
        | ExprKind::Unary(..)
        | ExprKind::Var(_) => step.2 = Some(value(c, first)?),
        ExprKind::PlanTerm(pt) => match wait_trigger(&pt.kind) {
            Some((op, kind, e)) => {
                let ExprKind::Literal(lit) = &e.kind else {
                    return Err(unsupported(e.span, "variables as triggers"));
                };
                step.0 = Some(Trigger {
                    op,
                    kind,
                    literal: c.literal(lit).map_err(convert_error)?,
                });
            }
            None => {
                return Err(Diagnostic::error(
                    "input",
                    "`.wait` waits for an event such as `{+b}`, a condition or a time",
                )
                .with_label(first.span, "not an event"))
            }
        },
        ExprKind::Str(_) => return Err(unsupported(first.span, "events given as strings")),
        _ => step.1 = Some(formula(c, first)?),
    }
    if let (None, Some(t)) = (&step.2, l.args.get(1)) {
        step.2 = Some(value(c, t)?);
    }
    let (event, condition, timeout) = step;
    Ok(BodyStep::Wait {
        event,
        condition,
        timeout,
    })
}

/// The event a plan term names for `.wait` (`Trigger.tryToGetTrigger`): a trigger
/// (`{+!g}`), or a body of one belief addition or deletion (`{+b}`, which Jason's grammar
/// reads as a body).
pub fn wait_trigger(t: &ast::PlanTermKind) -> Option<(TriggerOp, TriggerKind, &Expr)> {
    match t {
        ast::PlanTermKind::Trigger(t) => Some((t.op, t.kind, &t.literal)),
        ast::PlanTermKind::Body(b) if b.steps.len() == 1 => match &b.steps[0].kind {
            StepKind::AddBel(e) => Some((TriggerOp::Add, TriggerKind::Belief, e)),
            StepKind::DelBel(e) => Some((TriggerOp::Del, TriggerKind::Belief, e)),
            _ => None,
        },
        _ => None,
    }
}

/// A logical expression (a context, a test goal, a rule body) as a [`Formula`], with the
/// converter's variables (so several formulas of one clause share them).
pub fn formula(c: &mut Converter, e: &Expr) -> Result<Formula, Diagnostic> {
    Ok(match &e.kind {
        ExprKind::Literal(l) if l.functor == "true" && l.args.is_empty() => Formula::True,
        ExprKind::Literal(l) if l.functor == "false" && l.args.is_empty() => {
            Formula::Not(Box::new(Formula::True))
        }
        ExprKind::Literal(l) if l.functor == ".wait" => {
            return Err(Diagnostic::error(
                "input",
                "`.wait` suspends an intention: it is a step of a plan body, not a condition",
            )
            .with_label(l.span, "in a formula"))
        }
        ExprKind::Literal(l) if l.functor == ".random" => {
            return Err(unsupported(
                l.span,
                "`.random` in contexts and rules (its answers, one per try, would be choices of the deliberation)",
            ))
        }
        ExprKind::Literal(l) if l.is_internal_action() => {
            let args = l
                .args
                .iter()
                .map(|a| value(c, a))
                .collect::<Result<Vec<_>, _>>()?;
            Formula::Call(Term::structure(&l.functor, args))
        }
        ExprKind::Literal(l) => Formula::Literal(c.literal(l).map_err(convert_error)?),
        ExprKind::Not(a) => Formula::Not(Box::new(formula(c, a)?)),
        ExprKind::And(a, b) => Formula::And(Box::new(formula(c, a)?), Box::new(formula(c, b)?)),
        ExprKind::Or(a, b) => Formula::Or(Box::new(formula(c, a)?), Box::new(formula(c, b)?)),
        ExprKind::Rel(op, a, b) => Formula::Rel(*op, value(c, a)?, value(c, b)?),
        ExprKind::Var(_) => return Err(unsupported(e.span, "variables as formulas")),
        _ => {
            return Err(
                Diagnostic::error("input", "not a logical formula").with_label(
                    e.span,
                    "expected a literal, `not`, `&`, `|` or a comparison",
                ),
            )
        }
    })
}

fn steps(
    c: &mut Converter,
    steps_in: &[ast::Step],
    added: &mut Collector,
) -> Result<Vec<Step>, Diagnostic> {
    let mut out = Vec::new();
    for s in steps_in {
        if changes_library(s) {
            let change = library_step(s, added)?;
            let text = crate::syntax::printer::print_step(s);
            let call = matches!(s.kind, StepKind::Action(_));
            out.push(Step {
                kind: BodyStep::Library { change, text, call },
                span: s.span,
            });
            continue;
        }
        let lit = |c: &mut Converter, e: &Expr| -> Result<Term, Diagnostic> {
            match &e.kind {
                ExprKind::Literal(l) => c.literal(l).map_err(convert_error),
                _ => Err(unsupported(e.span, "variables in this position")),
            }
        };
        let kind = match &s.kind {
            StepKind::Action(Expr {
                kind: ExprKind::Literal(l),
                ..
            }) if l.functor == ".wait" => wait(c, l)?,
            StepKind::Action(Expr {
                kind: ExprKind::Literal(l),
                span,
            }) if super::know_how::know_how_message(l).is_some() => {
                BodyStep::Internal(know_how_send(c, l, *span)?)
            }
            StepKind::Action(e) => {
                let t = lit(c, e)?;
                match &e.kind {
                    ExprKind::Literal(l) if l.is_internal_action() => BodyStep::Internal(t),
                    _ => BodyStep::Action(t),
                }
            }
            StepKind::Achieve(e) | StepKind::AchieveNewFocus(e) => {
                let goal = lit(c, e)?;
                // `TransitionSystem.checkHardDeadline`: a timer that fails the goal if it is
                // not achieved in time.
                if goal
                    .annots()
                    .iter()
                    .any(|a| a.functor() == Some("hard_deadline"))
                {
                    return Err(unsupported(e.span, "goals annotated `hard_deadline`"));
                }
                BodyStep::Achieve {
                    goal,
                    new_focus: matches!(s.kind, StepKind::AchieveNewFocus(_)),
                }
            }
            StepKind::Test(e) => BodyStep::Test(formula(c, e)?),
            StepKind::AddBel(e) | StepKind::AddBelEnd(e) | StepKind::AddBelNewFocus(e) => {
                BodyStep::AddBel(lit(c, e)?)
            }
            StepKind::DelBel(e) | StepKind::DelBelNewFocus(e) => BodyStep::DelBel(lit(c, e)?),
            StepKind::DelAddBel(e) => BodyStep::DelAddBel(lit(c, e)?),
            StepKind::Constraint(e) => match &e.kind {
                ExprKind::Rel(op, a, b) => BodyStep::Constraint(*op, value(c, a)?, value(c, b)?),
                _ => return Err(unsupported(e.span, "such constraints")),
            },
            StepKind::If {
                branches,
                else_body,
            } => BodyStep::If {
                branches: branches
                    .iter()
                    .map(|(cond, body)| Ok((formula(c, cond)?, steps(c, &body.steps, added)?)))
                    .collect::<Result<Vec<_>, Diagnostic>>()?,
                else_body: match else_body {
                    Some(b) => steps(c, &b.steps, added)?,
                    None => Vec::new(),
                },
            },
            StepKind::While { cond, body } => {
                BodyStep::While(formula(c, cond)?, steps(c, &body.steps, added)?)
            }
            StepKind::For { cond, body } => {
                BodyStep::For(formula(c, cond)?, steps(c, &body.steps, added)?)
            }
            StepKind::Fork { .. } => return Err(unsupported(s.span, "forks (`|&|`, `|||`)")),
            StepKind::Group(b) => {
                out.extend(steps(c, &b.steps, added)?);
                continue;
            }
        };
        out.push(Step { kind, span: s.span });
    }
    Ok(out)
}

/// A step that changes the plan library (see [`changes_library`]).
fn library_step(s: &ast::Step, added: &mut Collector) -> Result<LibraryChange, Diagnostic> {
    match &s.kind {
        StepKind::Action(e) => match &e.kind {
            ExprKind::Literal(l) if l.functor == ".add_plan" => added.add_plan(l, s.span),
            ExprKind::Literal(l) => added.remove_plan(l, s.span),
            _ => unreachable!("changes_library holds for these steps only"),
        },
        StepKind::AddBel(e) => added.add_term(e, true),
        StepKind::AddBelEnd(e) => added.add_term(e, false),
        StepKind::DelBel(e) => added.remove_term(e),
        _ => unreachable!("changes_library holds for these steps only"),
    }
}
