//! How a renaming of the symmetric objects acts: on terms, substitutions, events,
//! intentions, request indices and whole states; and which symmetric objects a term names.

use super::Symmetry;
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::term::Term;
use crate::model::Substitution;
use crate::semantics::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Pending, Waiting,
};
use crate::semantics::{Origin, State};

/// One renaming of the symmetric objects, for the terms of data kept beside an agent state
/// (see [`Symmetry::fingerprint_with`]).
pub struct Renaming<'a> {
    pub(super) sym: &'a Symmetry,
    pub(super) perm: &'a [u16],
}

impl Renaming<'_> {
    /// A term with its symmetric objects renamed.
    pub fn term(&self, t: &Term) -> Term {
        self.sym.term(t, self.perm)
    }

    /// An intention's origin: a request renamed is another request.
    pub fn origin(&self, o: Origin) -> Origin {
        self.sym.origin(o, self.perm)
    }
}

impl Symmetry {
    /// Appends the symmetric objects in `t`, in order of occurrence.
    pub(super) fn collect_objects(&self, t: &Term, out: &mut Vec<u16>) {
        match t {
            Term::Atom(n) => {
                if let Some(&s) = self.by_name.get(n) {
                    if !out.contains(&s) {
                        out.push(s);
                    }
                }
            }
            Term::Struct(st) => {
                for a in st.args().iter().chain(st.annots()) {
                    self.collect_objects(a, out);
                }
            }
            Term::Cons(c) => {
                self.collect_objects(c.head(), out);
                self.collect_objects(c.tail(), out);
            }
            _ => {}
        }
    }

    /// `t` renamed, or `None` when renaming leaves it as it is.
    pub(super) fn rename(&self, t: &Term, perm: &[u16]) -> Option<Term> {
        match t {
            Term::Atom(n) => {
                let &s = self.by_name.get(n)?;
                let image = perm[s as usize];
                (image != s).then(|| Term::Atom(self.names[image as usize].clone()))
            }
            Term::Struct(st) => {
                let args = self.rename_all(st.args(), perm);
                let annots = self.rename_all(st.annots(), perm);
                if args.is_none() && annots.is_none() {
                    return None;
                }
                Some(Term::literal(
                    st.functor(),
                    st.negated(),
                    args.unwrap_or_else(|| st.args().to_vec()),
                    annots.unwrap_or_else(|| st.annots().to_vec()),
                ))
            }
            Term::Cons(c) => {
                let h = self.rename(c.head(), perm);
                let tl = self.rename(c.tail(), perm);
                if h.is_none() && tl.is_none() {
                    return None;
                }
                Some(Term::cons(
                    h.unwrap_or_else(|| c.head().clone()),
                    tl.unwrap_or_else(|| c.tail().clone()),
                ))
            }
            _ => None,
        }
    }

    fn rename_all(&self, ts: &[Term], perm: &[u16]) -> Option<Vec<Term>> {
        let mut out: Option<Vec<Term>> = None;
        for (i, t) in ts.iter().enumerate() {
            if let Some(r) = self.rename(t, perm) {
                out.get_or_insert_with(|| ts[..i].to_vec()).push(r);
            } else if let Some(o) = &mut out {
                o.push(t.clone());
            }
        }
        out
    }

    fn term(&self, t: &Term, perm: &[u16]) -> Term {
        self.rename(t, perm).unwrap_or_else(|| t.clone())
    }

    fn subst(&self, s: &Substitution, perm: &[u16]) -> Substitution {
        let mut out = Substitution::new();
        for (v, t) in s.iter() {
            out.bind(v.clone(), self.term(t, perm));
        }
        out
    }

    fn trigger(&self, t: &EventTrigger, perm: &[u16]) -> EventTrigger {
        EventTrigger {
            op: t.op,
            kind: t.kind,
            literal: self.term(&t.literal, perm),
        }
    }

    fn request_image(&self, r: u8, perm: &[u16]) -> u8 {
        match self.rename(&self.requests[r as usize], perm) {
            None => r,
            Some(t) => self.request_index.get(&t).copied().unwrap_or(r),
        }
    }

    fn origin(&self, o: Origin, perm: &[u16]) -> Origin {
        match o {
            Origin::Request(r) => Origin::Request(self.request_image(r, perm)),
            other => other,
        }
    }

    fn intention(&self, i: &Intention, perm: &[u16]) -> Intention {
        Intention {
            frames: i
                .frames
                .iter()
                .map(|f| Frame {
                    plan: f.plan,
                    subst: self.subst(&f.subst, perm),
                    cursors: f
                        .cursors
                        .iter()
                        .map(|c| Cursor {
                            block: c.block,
                            pos: c.pos,
                            kind: match &c.kind {
                                CursorKind::For { rest, base } => CursorKind::For {
                                    rest: rest.iter().map(|s| self.subst(s, perm)).collect(),
                                    base: self.subst(base, perm),
                                },
                                CursorKind::While { outer, at, base } => CursorKind::While {
                                    outer: *outer,
                                    at: *at,
                                    base: self.subst(base, perm),
                                },
                                CursorKind::Seq => CursorKind::Seq,
                            },
                        })
                        .collect(),
                    trigger: self.trigger(&f.trigger, perm),
                    calling: f.calling.as_ref().map(|t| self.term(t, perm)),
                })
                .collect(),
            origin: self.origin(i.origin, perm),
        }
    }

    /// The state renamed by `perm`.
    pub(super) fn apply(&self, s: &State, perm: &[u16]) -> State {
        let mut beliefs = AtomSet::empty(self.atom_count);
        for a in s.beliefs.iter() {
            beliefs.insert(self.atom_image(a, perm));
        }
        let mut requested = 0u64;
        for r in 0..64u8 {
            if s.requested >> r & 1 == 1 {
                requested |= 1 << self.request_image(r, perm);
            }
        }
        // Renamed atoms keep their age, and their predicate (so the groups stay as they
        // are).
        let order: Vec<AtomId> = s.order.iter().map(|a| self.atom_image(*a, perm)).collect();
        State {
            beliefs,
            order,
            events: s
                .events
                .iter()
                .map(|e| Event {
                    trigger: self.trigger(&e.trigger, perm),
                    intention: e.intention.as_ref().map(|i| self.intention(i, perm)),
                    origin: self.origin(e.origin, perm),
                    posted_at: e.posted_at,
                })
                .collect(),
            intentions: s
                .intentions
                .iter()
                .map(|i| self.intention(i, perm))
                .collect(),
            pending: s.pending.as_ref().map(|p| Pending {
                intention: self.intention(&p.intention, perm),
                failure: p.failure.as_ref().map(|f| ActionFailure {
                    action: self.term(&f.action, perm),
                    ..f.clone()
                }),
            }),
            waiting: s
                .waiting
                .iter()
                .map(|w| Waiting {
                    intention: self.intention(&w.intention, perm),
                    ..w.clone()
                })
                .collect(),
            requested,
            // Plans name no interchangeable object (`Symmetry::new` refuses them).
            library: s.library.clone(),
            // Symmetry reduction runs on one agent, never told anything.
            told: Vec::new(),
        }
    }
}
