//! Plans agents tell each other: Jason's know-how performatives, as `kqmlPlans.asl` handles
//! them (`kqmlReceivedTellHow`: `.add_plan(Content, Sender)`; `kqmlReceivedUnTellHow`:
//! `.remove_plan(Content, Sender)`; `kqmlReceivedAskHow`: `.relevant_plans` sent back with
//! `tellHow`).
//!
//! The plans are fixed in the text, as those of `.add_plan` are (see [`super::library`]):
//! a `tellHow` carries a string holding one plan (as Jason's manual writes them), a plan
//! term, or a list of those; an `untellHow` carries labels; an `askHow` carries a trigger
//! (`{+!goto(_,_)}` or `"+!goto(X,Y)"`). Every plan a receiver may be told is compiled at
//! load time into its library as a plan some step may add, with the sender as its source
//! when it arrives. A message carries a plan as a string, its text as bdi-check prints it
//! (the plan's key); the receiver maps the key to its compiled plan.
//!
//! An `askHow` is answered with the receiver's plans relevant for the trigger, which its
//! asker's library holds compiled too, as Jason's `.relevant_plans` and
//! `.remove_source_annot` give them: the label without its sources, every variable
//! anonymous (`Plan.makeVarsAnnon`, so such a plan is equal to no other: asked twice, the
//! second copy's label is already taken). Their keys write the variables `_X`.
//!
//! Refused where written: contents held in variables (`.plan_label(P, hp)` then
//! `tellHow P`), strings that are not one plan, labels that are not atoms, an `askHow`
//! waiting for its answer (the plans would be held in a variable), and an `askHow` of
//! plans that are not fixed (unlabelled, whose labels Jason numbers at run time, or that the
//! receiver may add or remove).

use super::library::{atom, string_label};
use crate::syntax::ast::{
    self, Body, Expr, ExprKind, Item, ListExpr, Literal, PlanTermKind, StepKind,
};
use crate::syntax::printer::{print_plan, print_trigger};
use crate::syntax::{parse_agent, Diagnostic, LoadedAgent, Span};
use std::collections::BTreeSet;

/// The know-how performatives.
pub const PERFORMATIVES: [&str; 3] = ["tellHow", "untellHow", "askHow"];

/// What one plan library (the agents of one plans file) may be told, untold and asked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KnowHow {
    /// The plans others may tell it, or answer its `askHow` with, in the order met.
    pub told: Vec<Told>,
    /// The labels others may untell.
    pub untold: BTreeSet<String>,
    /// The triggers others may ask it the plans of.
    pub asked: Vec<Asked>,
    /// Its own plans (index among them) an `askHow` may answer with, and their keys.
    pub answers: Vec<(usize, String)>,
    /// Every agent's name: the sources a told plan may have.
    pub agents: Vec<String>,
}

impl KnowHow {
    /// Whether any message may change or ask this library's plans.
    pub fn is_empty(&self) -> bool {
        self.told.is_empty() && self.untold.is_empty() && self.asked.is_empty()
    }
}

/// A plan another agent may tell (or answer an `askHow` with).
#[derive(Clone, Debug, PartialEq)]
pub struct Told {
    /// The plan's key: the string the message carries.
    pub key: String,
    /// The plan.
    pub plan: ast::Plan,
    /// It answers an `askHow`: its variables are anonymous and its label has no source.
    pub answer: bool,
}

/// A trigger another agent may ask the plans of.
#[derive(Clone, Debug, PartialEq)]
pub struct Asked {
    /// The trigger's key: the string the message carries.
    pub key: String,
    /// The trigger.
    pub trigger: ast::Trigger,
    /// The `askHow`'s content.
    pub span: Span,
}

fn refuse(span: Span, msg: impl Into<String>, label: &str) -> Diagnostic {
    Diagnostic::error("input", msg.into())
        .with_label(span, label)
        .with_help("write the plans in the `.send` itself: `.send(bob, tellHow, \"+!g <- a.\")`, `.send(bob, tellHow, {+!g <- a})`, `.send(bob, untellHow, l)`, `.send(bob, askHow, {+!g})`")
}

/// The text a string literal holds, parsed as Jason text at its place in the file (so
/// that what it holds is located there).
fn parse_string(s: &str, span: Span, what: &str) -> Result<ast::Plan, Diagnostic> {
    let pad = span.start as usize + 1;
    let mut text = " ".repeat(pad);
    text.push_str(s);
    if !s.trim_end().ends_with('.') {
        text.push('.');
    }
    let (file, errors) = parse_agent(span.file, &text);
    if let Some(e) = errors.into_iter().next() {
        return Err(e);
    }
    match file.items.as_slice() {
        [Item::Plan(p)] => Ok(p.clone()),
        _ => Err(refuse(
            span,
            format!("the string is not {what}"),
            "not one plan",
        )),
    }
}

/// The plans of a `tellHow`'s content (a string, a plan term, or a list of those), each
/// with its key: a string's text, as Jason sends it, or the plan term's as bdi-check prints
/// it.
pub fn told_plans(content: &Expr) -> Result<Vec<(String, ast::Plan)>, Diagnostic> {
    match &content.kind {
        ExprKind::Str(s) => Ok(vec![(
            s.clone(),
            parse_string(s, content.span, "one plan")?,
        )]),
        ExprKind::PlanTerm(t) => match &t.kind {
            PlanTermKind::Plan(p) => Ok(vec![(print_plan(p), p.clone())]),
            _ => Err(refuse(
                content.span,
                "`tellHow` needs a whole plan: this term in braces is a trigger, a body or a rule",
                "not a plan",
            )),
        },
        ExprKind::List(ListExpr {
            elems, tail: None, ..
        }) => {
            let mut out = Vec::new();
            for e in elems {
                if matches!(e.kind, ExprKind::List(_)) {
                    return Err(refuse(
                        e.span,
                        "a list inside the list of plans",
                        "not a plan",
                    ));
                }
                out.extend(told_plans(e)?);
            }
            Ok(out)
        }
        ExprKind::Var(_) => Err(refuse(
            content.span,
            "`tellHow` of a plan held in a variable (known only at run time) is not modelled",
            "a variable",
        )),
        _ => Err(refuse(
            content.span,
            "`tellHow` carries a plan: a string, a plan term or a list of them",
            "not a plan",
        )),
    }
}

/// The labels of an `untellHow`'s content: an atom, `"@l"` (`remove_plan.fixLabel`), or a
/// list of those.
pub fn untold_labels(content: &Expr) -> Result<Vec<String>, Diagnostic> {
    let one = |e: &Expr| -> Result<String, Diagnostic> {
        let name = match &e.kind {
            ExprKind::Str(s) => string_label(s),
            _ => atom(e),
        };
        name.map(str::to_string).ok_or_else(|| {
            refuse(
                e.span,
                "`untellHow` needs a plan's label here (an atom, or a string `\"@l\"`)",
                "not a label",
            )
        })
    };
    match &content.kind {
        ExprKind::List(ListExpr {
            elems, tail: None, ..
        }) => elems.iter().map(one).collect(),
        _ => Ok(vec![one(content)?]),
    }
}

/// The trigger of an `askHow`'s content: a plan term `{+!g}` or a string `"+!g"`.
pub fn asked_trigger(content: &Expr) -> Result<ast::Trigger, Diagnostic> {
    let bare = |p: &ast::Plan| p.label.is_none() && p.context.is_none() && p.body.is_none();
    let trigger = match &content.kind {
        ExprKind::Str(s) => {
            let p = parse_string(s, content.span, "a trigger")?;
            bare(&p).then_some(p.trigger)
        }
        ExprKind::PlanTerm(t) => match &t.kind {
            PlanTermKind::Trigger(t) => Some(t.clone()),
            PlanTermKind::Plan(p) if bare(p) => Some(p.trigger.clone()),
            _ => None,
        },
        _ => None,
    };
    let trigger = trigger.ok_or_else(|| {
        refuse(
            content.span,
            "`askHow` asks for the plans of a trigger written out: `{+!g(_)}` or `\"+!g(X)\"`",
            "not a trigger",
        )
    })?;
    match &trigger.literal.kind {
        ExprKind::Literal(l) if l.functor == "kqml_received" => Err(refuse(
            content.span,
            "`askHow` of the plans for messages is not modelled",
            "kqml_received",
        )),
        ExprKind::Literal(_) => Ok(trigger),
        _ => Err(refuse(
            content.span,
            "a trigger with a variable for its literal",
            "variable",
        )),
    }
}

/// The key of a trigger: its text as bdi-check prints it.
pub fn trigger_key(t: &ast::Trigger) -> String {
    print_trigger(t)
}

/// A plan as `.relevant_plans` and `.remove_source_annot` send it: the label without
/// sources; and its key, which writes every variable anonymous (`_X`).
fn answered(p: &ast::Plan) -> (ast::Plan, String) {
    let mut plan = p.clone();
    if let Some(annots) = plan.label.as_mut().and_then(|l| l.annots.as_mut()) {
        annots.elems.retain(|a| {
            !matches!(&a.kind, ExprKind::Literal(l) if l.functor == "source" && l.args.len() == 1)
        });
    }
    if let Some(l) = plan.label.as_mut() {
        if l.annots.as_ref().is_some_and(|a| a.elems.is_empty()) {
            l.annots = None;
        }
    }
    let key = anonymous_vars(&print_plan(&plan));
    (plan, key)
}

/// Jason text with every named variable written as an unnamed one (`X` as `_X`).
fn anonymous_vars(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 8);
    let mut quote = None;
    let mut prev: Option<char> = None;
    let mut escaped = false;
    for c in text.chars() {
        match quote {
            Some(q) => {
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == q {
                    quote = None;
                }
            }
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c.is_ascii_uppercase()
                && !prev.is_some_and(|p| p.is_ascii_alphanumeric() || p == '_') =>
            {
                out.push('_');
            }
            None => {}
        }
        out.push(c);
        prev = Some(c);
    }
    out
}

/// The plans of the plan terms an expression holds (`.add_plan`'s first argument).
fn plan_terms<'a>(e: &'a Expr, out: &mut Vec<&'a ast::Plan>) {
    match &e.kind {
        ExprKind::PlanTerm(t) => {
            if let PlanTermKind::Plan(p) = &t.kind {
                out.push(p);
            }
        }
        ExprKind::List(l) => l.elems.iter().for_each(|x| plan_terms(x, out)),
        _ => {}
    }
}

/// The `.send` and `.broadcast` steps of a body, nested bodies and the plans it adds
/// included.
fn messages<'a>(b: &'a Body, out: &mut Vec<&'a Literal>) {
    for s in &b.steps {
        let mut added = Vec::new();
        match &s.kind {
            StepKind::Action(Expr {
                kind: ExprKind::Literal(l),
                ..
            }) if l.functor == ".add_plan" => {
                l.args
                    .iter()
                    .take(1)
                    .for_each(|a| plan_terms(a, &mut added));
            }
            StepKind::AddBel(e) | StepKind::AddBelEnd(e) => plan_terms(e, &mut added),
            _ => {}
        }
        for p in added {
            if let Some(b) = &p.body {
                messages(b, out);
            }
        }
        match &s.kind {
            StepKind::Action(Expr {
                kind: ExprKind::Literal(l),
                ..
            }) if matches!(l.functor.as_str(), ".send" | ".broadcast") => out.push(l),
            StepKind::If {
                branches,
                else_body,
            } => {
                for (_, b) in branches {
                    messages(b, out);
                }
                if let Some(b) = else_body {
                    messages(b, out);
                }
            }
            StepKind::While { body, .. } | StepKind::For { body, .. } | StepKind::Group(body) => {
                messages(body, out)
            }
            StepKind::Fork { branches, .. } => branches.iter().for_each(|b| messages(b, out)),
            _ => {}
        }
    }
}

/// The performative (written out), receiver (`None` for `.broadcast`) and content of a
/// message step with a know-how performative.
pub fn know_how_message(l: &Literal) -> Option<(&str, Option<&Expr>, &Expr)> {
    let (receiver, ilf, content) = match (l.functor.as_str(), l.args.as_slice()) {
        (".send", [r, ilf, content, ..]) => (Some(r), ilf, content),
        (".broadcast", [ilf, content]) => (None, ilf, content),
        _ => return None,
    };
    match &ilf.kind {
        ExprKind::Literal(p) if PERFORMATIVES.contains(&p.functor.as_str()) => {
            Some((p.functor.as_str(), receiver, content))
        }
        _ => None,
    }
}

/// What every plans file (`files`, in order) may be told, untold and asked, from the
/// messages of every file. `agents` are the agents' names and files. Each message's
/// receivers are the agent it names, or every agent when it names a variable (or
/// broadcasts).
pub fn collect(
    files: &[&LoadedAgent],
    agents: &[(String, usize)],
) -> Result<Vec<KnowHow>, Vec<Diagnostic>> {
    let names: Vec<String> = agents.iter().map(|(n, _)| n.clone()).collect();
    let mut out: Vec<KnowHow> = files
        .iter()
        .map(|_| KnowHow {
            agents: names.clone(),
            ..KnowHow::default()
        })
        .collect();
    let mut errors = Vec::new();
    // (asker file, receiver files, trigger)
    let mut asks: Vec<(usize, Vec<usize>, Asked)> = Vec::new();
    for (f, agent) in files.iter().enumerate() {
        for item in agent.items() {
            let Item::Plan(p) = item else { continue };
            let mut sends = Vec::new();
            if let Some(b) = &p.body {
                messages(b, &mut sends);
            }
            for l in sends {
                let Some((performative, receiver, content)) = know_how_message(l) else {
                    continue;
                };
                let receivers: Vec<usize> = match receiver.map(|r| &r.kind) {
                    Some(ExprKind::Literal(r)) if r.functor == "self" => vec![f],
                    Some(ExprKind::Literal(r)) => {
                        match agents.iter().find(|(n, _)| *n == r.functor) {
                            Some((_, file)) => vec![*file],
                            // A receiver that is no agent: `.send` fails at run time.
                            None => Vec::new(),
                        }
                    }
                    _ => (0..files.len()).collect(),
                };
                match performative {
                    "tellHow" => match told_plans(content) {
                        Ok(plans) => {
                            for (key, p) in plans {
                                if let Some(d) = label_sources(&p) {
                                    errors.push(d);
                                    continue;
                                }
                                for &r in &receivers {
                                    if !out[r].told.iter().any(|t| t.key == key) {
                                        out[r].told.push(Told {
                                            key: key.clone(),
                                            plan: p.clone(),
                                            answer: false,
                                        });
                                    }
                                }
                            }
                        }
                        Err(d) => errors.push(d),
                    },
                    "untellHow" => match untold_labels(content) {
                        Ok(labels) => {
                            for &r in &receivers {
                                out[r].untold.extend(labels.iter().cloned());
                            }
                        }
                        Err(d) => errors.push(d),
                    },
                    _ => {
                        if let Some(extra) = l.args.get(3) {
                            errors.push(refuse(
                                extra.span,
                                "an `askHow` that waits for its answer (the plans would be held in a variable) is not modelled",
                                "the answer",
                            ).with_help("leave out the fourth argument: the plans are then added to the asker's library when the answer comes"));
                            continue;
                        }
                        match asked_trigger(content) {
                            Ok(trigger) => asks.push((
                                f,
                                receivers,
                                Asked {
                                    key: trigger_key(&trigger),
                                    trigger,
                                    span: content.span,
                                },
                            )),
                            Err(d) => errors.push(d),
                        }
                    }
                }
            }
        }
    }
    // The answers: each receiver's own plans for the trigger, told to the asker.
    for (asker, receivers, asked) in asks {
        for r in receivers {
            let own = files[r].items().into_iter().filter_map(|i| match i {
                Item::Plan(p) => Some(p),
                _ => None,
            });
            for (i, p) in own.enumerate() {
                if !same_event(&p.trigger, &asked.trigger) {
                    continue;
                }
                if p.label.as_ref().and_then(|l| l.name.as_ref()).is_none() {
                    errors.push(
                        refuse(
                            asked.span,
                            "`askHow` of unlabelled plans is not modelled (Jason labels them `p__N`, numbered at run time, and the asker gets that label)",
                            "asks for it",
                        )
                        .with_secondary(p.span, "no label")
                        .with_help("give the plans a label: `@goto1 +!goto(X, Y) <- ...`"),
                    );
                    continue;
                }
                let (plan, key) = answered(p);
                if !out[r].answers.iter().any(|(j, _)| *j == i) {
                    out[r].answers.push((i, key.clone()));
                }
                if !out[asker].told.iter().any(|t| t.key == key) {
                    out[asker].told.push(Told {
                        key,
                        plan,
                        answer: true,
                    });
                }
            }
            if !out[r].asked.iter().any(|a| a.key == asked.key) {
                out[r].asked.push(asked.clone());
            }
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

/// A told plan whose label names sources: refused (a string keeps them, a plan term loses
/// them to `.remove_source_annot`).
fn label_sources(p: &ast::Plan) -> Option<Diagnostic> {
    let label = p.label.as_ref()?;
    let a = label
        .annots
        .as_ref()?
        .elems
        .iter()
        .find(|a| matches!(&a.kind, ExprKind::Literal(l) if l.functor == "source"))?;
    Some(refuse(
        a.span,
        "a told plan whose label names its sources is not modelled",
        "a source",
    ))
}

/// Whether a plan's trigger may be relevant for the asked trigger: the same operator, kind,
/// functor and arity (the receiver unifies them when it answers).
pub fn same_event(plan: &ast::Trigger, asked: &ast::Trigger) -> bool {
    let name = |t: &ast::Trigger| match &t.literal.kind {
        ExprKind::Literal(l) => Some((l.functor.clone(), l.args.len(), l.negated)),
        _ => None,
    };
    plan.op == asked.op
        && plan.kind == asked.kind
        && name(plan).is_some()
        && name(plan) == name(asked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anonymous_vars_prefix_named_variables_outside_strings() {
        assert_eq!(
            anonymous_vars("@g +!goto(X, Y)[source(Ag)] <- .print(\"X\", X); _Z = 1."),
            "@g +!goto(_X, _Y)[source(_Ag)] <- .print(\"X\", _X); _Z = 1."
        );
    }
}
