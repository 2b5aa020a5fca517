//! Symmetry reduction (`Symmetry::canonical`): the canonical form of a state is the same
//! for every renaming of interchangeable objects, it is itself a renaming of the state, and
//! the fingerprint is the fingerprint of the canonical form.
//!
//! The states are those of a real project (the kitchen of `specs/kitchen`, whose two cups
//! are symmetric): a state is an initial state and a walk of up to [`MAX_WALK`] successor
//! choices from it. Renamings are applied to whole states (beliefs, events, intentions,
//! substitutions, requests) by code written here, independently of the symmetry module.

use crate::check::explore::fingerprint;
use crate::check::symmetry::Symmetry;
use crate::model::atoms::AtomSet;
use crate::model::project::{load_project, Project};
use crate::model::{ObjectId, Substitution, Term};
use crate::semantics::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Pending, Waiting,
};
use crate::semantics::{Origin, Semantics, State};
use std::path::Path;

/// Longest walk from an initial state.
pub const MAX_WALK: usize = 12;

/// A project, its transition system and its symmetry.
pub struct Fixture {
    /// The project (leaked: the semantics borrow it for the rest of the run).
    pub project: &'static Project,
    /// Its transition system.
    pub sem: Semantics<'static>,
    /// Its symmetry.
    pub symmetry: Symmetry,
    /// Every renaming of the symmetric objects, as object permutations.
    pub renamings: Vec<Vec<ObjectId>>,
}

impl Fixture {
    /// The project at `path`, which must declare a symmetric type with two objects or more.
    pub fn load(path: &Path) -> Fixture {
        let project: &'static Project =
            Box::leak(Box::new(load_project(path).unwrap_or_else(|e| {
                panic!("{}: {:?}", path.display(), e.diagnostics)
            })));
        let sem = Semantics::new(project).unwrap_or_else(|e| panic!("semantics: {e:?}"));
        let symmetry = Symmetry::new(project, &sem)
            .unwrap_or_else(|e| panic!("symmetry: {e:?}"))
            .expect("the project declares a symmetric type");
        let u = &project.universe;
        let mut groups: Vec<Vec<ObjectId>> = Vec::new();
        for t in &project.manifest.bounds.symmetry {
            let ty = u.type_id(&t.value).expect("a declared type");
            let objs: Vec<ObjectId> = u
                .objects_of(ty)
                .iter()
                .copied()
                .filter(|&o| u.object_type(o) == ty)
                .collect();
            groups.push(objs);
        }
        let identity: Vec<ObjectId> = u.objects().collect();
        let mut renamings = vec![identity];
        for g in &groups {
            let mut next = Vec::new();
            for base in &renamings {
                for order in permutations(g) {
                    let mut p = base.clone();
                    for (from, to) in g.iter().zip(&order) {
                        p[from.0 as usize] = *to;
                    }
                    next.push(p);
                }
            }
            renamings = next;
        }
        Fixture {
            project,
            sem,
            symmetry,
            renamings,
        }
    }

    /// The kitchen of `specs/kitchen`.
    pub fn kitchen() -> Fixture {
        Fixture::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen"))
    }

    /// The state reached from initial state `init` (modulo their number) by taking, at each
    /// step, successor `walk[i]` (modulo their number), stopping where none is left.
    pub fn state(&self, init: u16, walk: &[u8]) -> State {
        let initial = self.sem.initial_states();
        let mut s = initial[usize::from(init) % initial.len()].clone();
        for &w in walk {
            let mut next = self.sem.successors(&s);
            if next.is_empty() {
                break;
            }
            let i = usize::from(w) % next.len();
            s = next.swap_remove(i).next;
        }
        s
    }

    fn rename_term(&self, t: &Term, perm: &[ObjectId]) -> Term {
        let u = &self.project.universe;
        match t {
            Term::Atom(n) => match u.object(n) {
                Some(o) => Term::atom(u.object_name(perm[o.0 as usize])),
                None => t.clone(),
            },
            Term::Struct(s) => Term::literal(
                s.functor(),
                s.negated(),
                s.args().iter().map(|a| self.rename_term(a, perm)).collect(),
                s.annots()
                    .iter()
                    .map(|a| self.rename_term(a, perm))
                    .collect(),
            ),
            Term::Cons(c) => Term::cons(
                self.rename_term(c.head(), perm),
                self.rename_term(c.tail(), perm),
            ),
            _ => t.clone(),
        }
    }

    fn rename_subst(&self, s: &Substitution, perm: &[ObjectId]) -> Substitution {
        let mut out = Substitution::new();
        for (v, t) in s.iter() {
            assert!(out.bind(v.clone(), self.rename_term(t, perm)));
        }
        out
    }

    fn rename_trigger(&self, t: &EventTrigger, perm: &[ObjectId]) -> EventTrigger {
        EventTrigger {
            op: t.op,
            kind: t.kind,
            literal: self.rename_term(&t.literal, perm),
        }
    }

    fn rename_request(&self, r: u8, perm: &[ObjectId]) -> u8 {
        let image = self.rename_term(&self.sem.requests[usize::from(r)], perm);
        self.sem
            .requests
            .iter()
            .position(|q| *q == image)
            .expect("the requests are closed under renaming") as u8
    }

    fn rename_origin(&self, o: Origin, perm: &[ObjectId]) -> Origin {
        match o {
            Origin::Request(r) => Origin::Request(self.rename_request(r, perm)),
            other => other,
        }
    }

    fn rename_intention(&self, i: &Intention, perm: &[ObjectId]) -> Intention {
        Intention {
            frames: i
                .frames
                .iter()
                .map(|f| Frame {
                    plan: f.plan,
                    subst: self.rename_subst(&f.subst, perm),
                    cursors: f
                        .cursors
                        .iter()
                        .map(|c| Cursor {
                            block: c.block,
                            pos: c.pos,
                            kind: match &c.kind {
                                CursorKind::For { rest, base } => CursorKind::For {
                                    rest: rest.iter().map(|s| self.rename_subst(s, perm)).collect(),
                                    base: self.rename_subst(base, perm),
                                },
                                CursorKind::While { outer, at, base } => CursorKind::While {
                                    outer: *outer,
                                    at: *at,
                                    base: self.rename_subst(base, perm),
                                },
                                CursorKind::Seq => CursorKind::Seq,
                            },
                        })
                        .collect(),
                    trigger: self.rename_trigger(&f.trigger, perm),
                    calling: f.calling.as_ref().map(|t| self.rename_term(t, perm)),
                })
                .collect(),
            origin: self.rename_origin(i.origin, perm),
        }
    }

    /// `s` with its objects renamed by `perm` (`perm[o]` is the image of object `o`).
    pub fn rename(&self, s: &State, perm: &[ObjectId]) -> State {
        let map = self.project.atoms.permutation_map(perm);
        let beliefs: AtomSet = s.beliefs.permuted(&map);
        let mut requested = 0u64;
        for r in 0..self.sem.requests.len() as u8 {
            if s.requested >> r & 1 == 1 {
                requested |= 1 << self.rename_request(r, perm);
            }
        }
        State {
            beliefs,
            order: s.order.iter().map(|a| map[a.0 as usize]).collect(),
            events: s
                .events
                .iter()
                .map(|e| Event {
                    trigger: self.rename_trigger(&e.trigger, perm),
                    intention: e.intention.as_ref().map(|i| self.rename_intention(i, perm)),
                    origin: self.rename_origin(e.origin, perm),
                    posted_at: e.posted_at,
                })
                .collect(),
            intentions: s
                .intentions
                .iter()
                .map(|i| self.rename_intention(i, perm))
                .collect(),
            pending: s.pending.as_ref().map(|p| Pending {
                intention: self.rename_intention(&p.intention, perm),
                failure: p.failure.as_ref().map(|f| ActionFailure {
                    action: self.rename_term(&f.action, perm),
                    ..f.clone()
                }),
            }),
            waiting: s
                .waiting
                .iter()
                .map(|w| Waiting {
                    intention: self.rename_intention(&w.intention, perm),
                    ask: w
                        .ask
                        .as_ref()
                        .map(|(id, t)| (*id, self.rename_term(t, perm))),
                    ..w.clone()
                })
                .collect(),
            requested,
            library: s.library.clone(),
            told: s.told.clone(),
            asked: s.asked,
            atomic: s.atomic,
        }
    }
}

fn permutations(items: &[ObjectId]) -> Vec<Vec<ObjectId>> {
    if items.len() <= 1 {
        return vec![items.to_vec()];
    }
    let mut out = Vec::new();
    for i in 0..items.len() {
        let mut rest = items.to_vec();
        let first = rest.remove(i);
        for mut p in permutations(&rest) {
            p.insert(0, first);
            out.push(p);
        }
    }
    out
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// The renaming changed the state.
    pub renaming_moved: bool,
    /// The state was not its own canonical form.
    pub not_canonical: bool,
}

/// The property, with `canonical` the kernel (`Symmetry::canonical`) and `perm` a renaming
/// of the symmetric objects: `s` and its renaming have the same canonical form (the state
/// itself when the kernel returns none) and the same fingerprint; the fingerprint is the
/// fingerprint of the canonical form; the canonical form is a renaming of `s`.
pub fn canonical_form_is_invariant(
    fx: &Fixture,
    s: &State,
    perm: &[ObjectId],
    canonical: impl Fn(&State) -> (u64, Option<State>),
) -> Result<Seen, String> {
    let t = fx.rename(s, perm);
    let (fs, cs) = canonical(s);
    let (ft, ct) = canonical(&t);
    let cs = cs.unwrap_or_else(|| s.clone());
    let ct = ct.unwrap_or_else(|| t.clone());
    let names = |p: &[ObjectId]| -> String {
        let u = &fx.project.universe;
        p.iter()
            .enumerate()
            .filter(|(i, o)| *i != o.0 as usize)
            .map(|(i, o)| {
                format!(
                    "{} -> {}",
                    u.object_name(ObjectId(i as u16)),
                    u.object_name(*o)
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    if cs != ct {
        return Err(format!(
            "renaming {{{}}} changes the canonical form of {s:?}: {cs:?} against {ct:?}",
            names(perm)
        ));
    }
    if fs != ft {
        return Err(format!(
            "renaming {{{}}} changes the fingerprint of {s:?}: {fs:x} against {ft:x}",
            names(perm)
        ));
    }
    if fs != fingerprint(&cs) {
        return Err(format!(
            "the fingerprint {fs:x} of {s:?} is not that of its canonical form {cs:?}"
        ));
    }
    if !fx.renamings.iter().any(|p| fx.rename(s, p) == cs) {
        return Err(format!(
            "the canonical form {cs:?} of {s:?} is no renaming of it"
        ));
    }
    Ok(Seen {
        renaming_moved: t != *s,
        not_canonical: cs != *s,
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// Kitchen states up to 12 steps from any of its initial states, every renaming of the
    /// two cups.
    #[kani::proof]
    #[kani::unwind(13)]
    fn canonical_form_is_the_same_for_every_renaming() {
        let fx = Fixture::kitchen();
        let init: u16 = kani::any();
        let walk: [u8; MAX_WALK] = kani::any();
        let perm: usize = kani::any();
        kani::assume(perm < fx.renamings.len());
        let s = fx.state(init, &walk);
        let seen =
            canonical_form_is_invariant(&fx, &s, &fx.renamings[perm], |s| fx.symmetry.canonical(s));
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.renaming_moved),
            "a renaming that moves the state"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.not_canonical),
            "a state that is not canonical"
        );
        assert!(seen.is_ok());
    }
}
