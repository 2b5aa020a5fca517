//! How a renaming of the symmetric objects acts: on terms, substitutions, events,
//! intentions, request indices and whole states; and which symmetric objects a term names.

use super::Symmetry;
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::term::Term;
use crate::model::Substitution;
use crate::semantics::compiled::Base;
use crate::semantics::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Pending, Told,
    Waiting,
};
use crate::semantics::{Origin, PartMap, State};
use std::sync::Arc;

/// One renaming of the symmetric objects, for the terms of data kept beside an agent state
/// (see [`Symmetry::fingerprint_with`]).
pub struct Renaming<'a> {
    pub(super) sym: &'a Symmetry,
    pub(super) perm: &'a [u16],
}

impl Renaming<'_> {
    /// The renaming as the image of each symmetric object (by index): one slice, one
    /// renaming, for keys of what is computed per renaming.
    pub fn perm(&self) -> &[u16] {
        self.perm
    }

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
        rename_names(t, &|n| {
            let &s = self.by_name.get(n)?;
            let image = perm[s as usize];
            (image != s).then(|| self.names[image as usize].clone())
        })
    }

    fn term(&self, t: &Term, perm: &[u16]) -> Term {
        self.rename(t, perm).unwrap_or_else(|| t.clone())
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

    /// The state renamed by `perm`.
    pub(super) fn apply(&self, s: &State, perm: &[u16]) -> State {
        rename_state(&Renaming { sym: self, perm }, s)
    }
}

/// How a renaming acts on the parts of an agent state; [`rename_state`] does the rest.
pub trait Rename {
    /// A term renamed, or `None` when renaming leaves it as it is.
    fn rename(&self, t: &Term) -> Option<Term>;
    /// An atom's image.
    fn atom(&self, a: AtomId) -> AtomId;
    /// How many atoms there are.
    fn atom_count(&self) -> usize;
    /// A request index's image (a request renamed is another request).
    fn request(&self, r: u8) -> u8 {
        r
    }
    /// The image of a set of agents, one bit each (who told a belief).
    fn agents(&self, bits: u64) -> u64 {
        bits
    }
}

impl Rename for Renaming<'_> {
    fn rename(&self, t: &Term) -> Option<Term> {
        self.sym.rename(t, self.perm)
    }

    fn atom(&self, a: AtomId) -> AtomId {
        self.sym.atom_image(a, self.perm)
    }

    fn atom_count(&self) -> usize {
        self.sym.atom_count
    }

    fn request(&self, r: u8) -> u8 {
        self.sym.request_image(r, self.perm)
    }
}

/// `t` with every atom `image` renames (it gives `None` for a name left as it is)
/// renamed, or `None` when nothing in it is.
pub fn rename_names(t: &Term, image: &impl Fn(&str) -> Option<Arc<str>>) -> Option<Term> {
    match t {
        Term::Atom(n) => image(n).map(Term::Atom),
        Term::Struct(st) => {
            let args = rename_all(st.args(), image);
            let annots = rename_all(st.annots(), image);
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
            let h = rename_names(c.head(), image);
            let tl = rename_names(c.tail(), image);
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

fn rename_all(ts: &[Term], image: &impl Fn(&str) -> Option<Arc<str>>) -> Option<Vec<Term>> {
    let mut out: Option<Vec<Term>> = None;
    for (i, t) in ts.iter().enumerate() {
        if let Some(r) = rename_names(t, image) {
            out.get_or_insert_with(|| ts[..i].to_vec()).push(r);
        } else if let Some(o) = &mut out {
            o.push(t.clone());
        }
    }
    out
}

fn term<R: Rename>(r: &R, t: &Term) -> Term {
    r.rename(t).unwrap_or_else(|| t.clone())
}

fn subst<R: Rename>(r: &R, s: &Substitution) -> Substitution {
    let mut out = Substitution::new();
    for (v, t) in s.iter() {
        out.bind(v.clone(), term(r, t));
    }
    out
}

fn trigger<R: Rename>(r: &R, t: &EventTrigger) -> EventTrigger {
    EventTrigger {
        op: t.op,
        kind: t.kind,
        literal: term(r, &t.literal),
    }
}

fn origin<R: Rename>(r: &R, o: Origin) -> Origin {
    match o {
        Origin::Request(i) => Origin::Request(r.request(i)),
        other => other,
    }
}

/// An intention renamed.
pub fn rename_intention<R: Rename>(r: &R, i: &Intention) -> Intention {
    Intention {
        frames: i
            .frames
            .iter()
            .map(|f| Frame {
                plan: f.plan,
                subst: subst(r, &f.subst),
                cursors: f
                    .cursors
                    .iter()
                    .map(|c| Cursor {
                        block: c.block,
                        pos: c.pos,
                        kind: match &c.kind {
                            CursorKind::For { rest, base } => CursorKind::For {
                                rest: rest.iter().map(|s| subst(r, s)).collect(),
                                base: subst(r, base),
                            },
                            CursorKind::While { outer, at, base } => CursorKind::While {
                                outer: *outer,
                                at: *at,
                                base: subst(r, base),
                            },
                            CursorKind::Seq => CursorKind::Seq,
                        },
                    })
                    .collect(),
                trigger: trigger(r, &f.trigger),
                calling: f.calling.as_ref().map(|t| term(r, t)),
            })
            .collect(),
        origin: origin(r, i.origin),
    }
}

/// Beliefs and their order renamed: renamed atoms keep their age, and their predicate (so
/// the groups stay as they are).
fn rename_base<R: Rename>(r: &R, beliefs: &AtomSet, order: &[AtomId]) -> (AtomSet, Vec<AtomId>) {
    let mut out = AtomSet::empty(r.atom_count());
    for a in beliefs.iter() {
        out.insert(r.atom(a));
    }
    (out, order.iter().map(|a| r.atom(*a)).collect())
}

/// The requests made (a bit each) renamed.
fn rename_requests<R: Rename>(r: &R, requested: u64) -> u64 {
    let mut out = 0u64;
    for i in 0..64u8 {
        if requested >> i & 1 == 1 {
            out |= 1 << r.request(i);
        }
    }
    out
}

/// An event renamed.
fn rename_event<R: Rename>(r: &R, e: &Event) -> Event {
    Event {
        trigger: trigger(r, &e.trigger),
        intention: e.intention.as_ref().map(|i| rename_intention(r, i)),
        origin: origin(r, e.origin),
        posted_at: e.posted_at,
    }
}

/// An intention that waits for its action's feedback renamed.
fn rename_pending<R: Rename>(r: &R, p: &Pending) -> Pending {
    Pending {
        intention: rename_intention(r, &p.intention),
        failure: p.failure.as_ref().map(|f| ActionFailure {
            action: term(r, &f.action),
            ..f.clone()
        }),
    }
}

/// A renaming of objects acts on a compiled state part by part.
impl PartMap for Renaming<'_> {
    fn base(&self, b: &Base) -> Base {
        rename_base(self, &b.0, &b.1)
    }
    fn event(&self, e: &Event) -> Event {
        rename_event(self, e)
    }
    fn intention(&self, i: &Intention) -> Intention {
        rename_intention(self, i)
    }
    fn pending(&self, p: &Pending) -> Pending {
        rename_pending(self, p)
    }
    fn requested(&self, r: u64) -> u64 {
        rename_requests(self, r)
    }
}

/// An agent state renamed: its beliefs, the terms of its events, intentions and
/// substitutions, its requests, and who told it what.
pub fn rename_state<R: Rename>(r: &R, s: &State) -> State {
    let (beliefs, order) = rename_base(r, &s.beliefs, &s.order);
    let requested = rename_requests(r, s.requested);
    let mut told: Vec<Told> = s
        .told
        .iter()
        .map(|t| Told {
            atom: r.atom(t.atom),
            from: r.agents(t.from),
            own: t.own,
        })
        .collect();
    told.sort_by_key(|t| t.atom);
    State {
        beliefs,
        order,
        events: s.events.iter().map(|e| rename_event(r, e)).collect(),
        intentions: s
            .intentions
            .iter()
            .map(|i| rename_intention(r, i))
            .collect(),
        pending: s.pending.as_ref().map(|p| rename_pending(r, p)),
        waiting: s
            .waiting
            .iter()
            .map(|w| Waiting {
                intention: rename_intention(r, &w.intention),
                ask: w.ask.as_ref().map(|(id, t)| (*id, term(r, t))),
                ..w.clone()
            })
            .collect(),
        requested,
        // Plans name no interchangeable object or agent (the reductions refuse them).
        library: s.library.clone(),
        told,
        asked: s.asked,
        atomic: s.atomic,
    }
}
