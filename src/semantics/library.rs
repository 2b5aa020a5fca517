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
