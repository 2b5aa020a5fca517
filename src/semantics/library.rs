//! The plan library of a state, for agents whose steps add or remove plans: the plans
//! relevant for an event in the library's order, and the changes as Jason's `PlanLibrary`
//! makes them (`add(Plan, Term, boolean)`, `add(Plan, boolean)`, `remove(Literal, Term)`).
//! The library is one list in Jason's order (`PlanLibrary.plans`): its per-trigger lists
//! (`relPlans`) keep the same order, a plan added at the beginning going first in both.

use super::cycle::{kind_key, op_key, Semantics};
use super::state::{Event, EventTrigger, InLibrary, State};
use crate::model::library::LibraryChange;
use crate::model::term::Term;
use std::borrow::Cow;

/// The failure event of a step with no place in the source (`+{P}`, `+>{P}`): its
/// `code_line` is `no_code` (`Literal.addSourceInfoAsAnnots` with no source info).
pub(super) fn no_code(ev: &mut Event) {
    let lit = &ev.trigger.literal;
    let annots = lit.annots().iter().map(|a| match a.functor() {
        Some("code_line") => Term::structure("code_line", vec![Term::atom("no_code")]),
        _ => a.clone(),
    });
    if let Some(l) = lit.without_annots().add_annots(annots.collect::<Vec<_>>()) {
        ev.trigger.literal = l;
    }
}

impl Semantics<'_> {
    /// The plans relevant for `t` in library `lib` (`None`: the agent's own plans), in the
    /// library's order: `PlanLibrary.getCandidatePlans`.
    pub(super) fn relevant_in(
        &self,
        lib: Option<&[InLibrary]>,
        t: &EventTrigger,
    ) -> Cow<'_, [u32]> {
        let all = self.relevant_plans(t);
        // The static list holds every plan that may be relevant: the agent's own, those its
        // steps may add, then Jason's for messages, which are always in the library.
        let own = all.partition_point(|&p| (p as usize) < self.own_plans);
        let kqml = &all[all.partition_point(|&p| !self.is_kqml_plan(p))..];
        match lib {
            None if own + kqml.len() == all.len() => Cow::Borrowed(all),
            None => Cow::Owned(all[..own].iter().chain(kqml).copied().collect()),
            Some(lib) => Cow::Owned(
                lib.iter()
                    .map(|e| e.plan)
                    .filter(|p| {
                        let pt = &self.plan(*p).trigger;
                        op_key(pt.op) == op_key(t.op)
                            && kind_key(pt.kind) == kind_key(t.kind)
                            && pt.literal.functor() == t.literal.functor()
                            && pt.literal.arity() == t.literal.arity()
                    })
                    .chain(kqml.iter().copied())
                    .collect(),
            ),
        }
    }

    /// Applies a change of the library to `s`. `Err` says why `.add_plan` threw (a label
    /// already taken, `PlanLibrary.add(Plan, boolean)`); the plans before that one are in.
    pub(super) fn change_library(
        &self,
        s: &mut State,
        change: &LibraryChange,
    ) -> Result<(), String> {
        let Some(ch) = &self.project.plans.changes else {
            unreachable!("a library step implies the library's changes");
        };
        let plans = &self.project.plans.plans;
        let label = |p: u32| plans[p as usize].label.as_deref();
        let mut lib: Vec<InLibrary> = match &s.library {
            Some(l) => l.to_vec(),
            None => self.own_library(),
        };
        let mut result = Ok(());
        match change {
            LibraryChange::Add {
                plans: added,
                source,
                begin,
            } => {
                for &d in added {
                    // `add(Plan, Term, boolean)`: a plan `Plan.equals` already holds only
                    // gets the source (`plans.indexOf`: the first such one).
                    let equal = &ch.equal[d as usize - ch.initial];
                    if let Some(e) = lib.iter_mut().find(|e| equal.contains(&e.plan)) {
                        e.sources |= 1 << source;
                        continue;
                    }
                    // `add(Plan, boolean)`: a label already taken throws.
                    if let Some(l) = label(d) {
                        if lib.iter().any(|e| label(e.plan) == Some(l)) {
                            result = Err(format!("there already is a plan with label {l}"));
                            break;
                        }
                    }
                    let e = InLibrary {
                        plan: d,
                        sources: ch.label_sources[d as usize] | 1 << source,
                    };
                    if *begin {
                        lib.insert(0, e);
                    } else {
                        lib.push(e);
                    }
                }
            }
            LibraryChange::Remove { labels, source } => {
                // `remove(Literal, Term)`: the source goes, and the plan with its last one.
                for l in labels {
                    let Some(k) = lib.iter().position(|e| label(e.plan) == Some(l)) else {
                        continue;
                    };
                    if lib[k].sources >> source & 1 == 1 {
                        lib[k].sources &= !(1 << source);
                        if lib[k].sources == 0 {
                            lib.remove(k);
                        }
                    }
                }
            }
        }
        // Back to the agent's own plans, the state is the one it was before the changes.
        s.library = (lib != self.own_library()).then(|| lib.into());
        result
    }

    /// The change `.kqml_tell_how(Content, Sender)` or `.kqml_untell_how(Content, Sender)`
    /// (`term`, evaluated) makes: Jason's `.add_plan(Content, Sender)` of the plans the
    /// content's keys name, or `.remove_plan(Content, Sender)` of its labels.
    pub(super) fn know_how_change(&self, f: &str, term: &Term) -> Result<LibraryChange, String> {
        let [content, sender] = term.args() else {
            unreachable!("the kqml plans give two arguments")
        };
        let ch = self.project.plans.changes.as_ref();
        let name = sender.functor().unwrap_or_default();
        let source = ch
            .and_then(|c| c.sources.iter().position(|n| n == name))
            .ok_or_else(|| format!("`{sender}` is not an agent that may tell this one plans"))?
            as u32;
        let items = match content.list_elements() {
            Some((elems, None)) => elems,
            Some(_) => return Err(format!("the content `{content}` is not a list")),
            None => vec![content.clone()],
        };
        if f == ".kqml_untell_how" {
            let labels = items
                .iter()
                .map(|t| match t {
                    Term::Atom(l) => Ok(l.to_string()),
                    Term::Str(l) if l.starts_with('@') => Ok(l[1..].to_string()),
                    _ => Err(format!("`{t}` is not a plan's label")),
                })
                .collect::<Result<_, _>>()?;
            return Ok(LibraryChange::Remove { labels, source });
        }
        let plans = items
            .iter()
            .map(|t| match t {
                Term::Str(key) => ch.and_then(|c| c.told.get(&**key)).copied().ok_or_else(|| {
                    format!("the plan {t} was not compiled for this agent (it is told in a way bdi-check does not follow)")
                }),
                _ => Err(format!("`{t}` is not a plan")),
            })
            .collect::<Result<_, _>>()?;
        Ok(LibraryChange::Add {
            plans,
            source,
            begin: false,
        })
    }

    /// `.relevant_plans(Trigger, Plans)` for the trigger an `askHow` names by its key: the
    /// plans of the library of `s` whose trigger unifies with it (a `source(_)` added when
    /// it has none), in the library's order, each as its key.
    pub(super) fn relevant_keys(&self, s: &State, key: &Term) -> Result<Term, String> {
        let ch = self.project.plans.changes.as_ref();
        let asked = match key {
            Term::Str(k) => ch.and_then(|c| c.asked.get(&**k)),
            _ => None,
        };
        let Some((op, kind, literal)) = asked else {
            return Err(format!("the trigger {key} was not compiled for this agent"));
        };
        // Apart from the plans' variables (`Plan.makeVarsAnnon` of the event's copy).
        let literal = literal.rename_apart(crate::model::term::MESSAGE_GENERATION);
        let literal = if literal
            .annots()
            .iter()
            .any(|a| a.functor() == Some("source"))
        {
            literal
        } else {
            let var = Term::var("Src").rename_apart(crate::model::term::MESSAGE_GENERATION + 1);
            let source = Term::structure("source", vec![var]);
            literal.add_annots([source]).unwrap_or(literal)
        };
        let trigger = EventTrigger {
            op: *op,
            kind: *kind,
            literal,
        };
        let mut keys = Vec::new();
        for &p in self.relevant_in(s.library.as_deref(), &trigger).iter() {
            if self.is_kqml_plan(p) {
                continue;
            }
            let mut u = crate::model::Substitution::new();
            if !crate::model::unify(&self.plan(p).trigger.literal, &trigger.literal, &mut u) {
                continue;
            }
            let answer = ch.and_then(|c| c.answers.get(&p));
            match answer {
                Some(k) => keys.push(Term::string(k)),
                None => {
                    return Err(format!(
                        "the plan {} answers an `askHow` bdi-check did not compile",
                        self.plan(p).name()
                    ))
                }
            }
        }
        Ok(Term::list(keys))
    }

    /// The agent's own plans as Jason loads them, each with its label's sources.
    fn own_library(&self) -> Vec<InLibrary> {
        let sources = self
            .project
            .plans
            .changes
            .as_ref()
            .map_or(&[][..], |c| &c.label_sources[..]);
        (0..self.own_plans)
            .map(|p| InLibrary {
                plan: p as u32,
                sources: sources.get(p).copied().unwrap_or(1),
            })
            .collect()
    }
}
