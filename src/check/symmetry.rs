//! Symmetry reduction over the manifest's `[bounds] symmetry` types.
//!
//! Objects of a symmetric type are interchangeable: renaming them maps runs to runs. The
//! search then stores one state per class of states equal up to such a renaming, under the
//! fingerprint of a canonical member of the class ([`Symmetry::canonical`]). Renaming acts
//! on every part of a state: the beliefs (atoms), the terms inside events, intentions,
//! substitutions and `for` loops, the `requested` bits and the request origins (a request
//! is a ground goal, so renaming maps request indices too).
//!
//! The canonical member is found without trying all `k!` renamings: each object gets a
//! signature that renaming carries along (where it first occurs in the state's terms, and a
//! hash of the atoms and requests that involve it alone); objects are sorted by signature.
//! Equal signatures of objects that occur in no term and in no atom or request together
//! with another symmetric object mean the objects are interchangeable in this state, so
//! their order does not matter; only ties among other objects are broken by trying their
//! orders and keeping the least fingerprint. Whatever the outcome, the stored state is a
//! renaming of the real one, so a less than perfect canonical form only costs reduction,
//! never soundness.
//!
//! Soundness needs the model itself to treat the objects alike: [`Symmetry::new`] refuses a
//! plan library, PDDL domain, explanation pattern or phrase that names one of them, and a
//! manifest formula or request that names one unless it is symmetric (`cupAt(cup1, c) &
//! cupAt(cup2, c)` with two cups is), and checks that the initial states and the requests
//! are closed under renaming.

use super::explore::fingerprint;
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::cond::{Cond, CountCmp};
use crate::model::project::Project;
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::model::Substitution;
use crate::semantics::state::{
    ActionFailure, Cursor, CursorKind, Event, EventTrigger, Frame, Intention, Pending,
};
use crate::semantics::{Origin, Semantics, State};
use crate::syntax::{Diagnostic, Span};
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Most orders tried to break ties between objects that are not interchangeable; beyond
/// it the sorted order is kept as it is (less reduction, still sound).
const MAX_TIE_ORDERS: usize = 5040;

/// How an atom involves symmetric objects.
#[derive(Clone, Copy, Debug)]
enum Involves {
    /// No symmetric object.
    None,
    /// One symmetric object (maybe more than once): the object and the atom's id with
    /// the object replaced by the first object of its type.
    One(u16, u32),
    /// Two or more distinct symmetric objects.
    Many,
}

/// The symmetric types of a project and what renaming their objects needs.
pub struct Symmetry {
    /// For each symmetric type, its objects as symmetric indices (in object id order).
    groups: Vec<Vec<u16>>,
    /// Symmetric index -> object.
    objects: Vec<ObjectId>,
    /// Symmetric index -> object name (as an atom term).
    names: Vec<Arc<str>>,
    by_name: HashMap<Arc<str>, u16>,
    /// Symmetric index -> its group.
    group_of: Vec<u16>,
    /// For each atom: its symmetric arguments as (stride, parameter type, symmetric index).
    atom_args: Vec<Vec<(u32, u16, u16)>>,
    /// For each atom: what symmetric objects it involves.
    involves: Vec<Involves>,
    /// Parameter type -> symmetric index -> the object's position among the type's objects.
    position: Vec<Vec<u32>>,
    /// For each request: what symmetric objects it involves (the key is a request index).
    request_involves: Vec<Involves>,
    requests: Vec<Term>,
    request_index: HashMap<Term, u8>,
    atom_count: usize,
}

/// A renaming: symmetric index -> symmetric index.
type Perm = Vec<u16>;

/// One renaming of the symmetric objects, for the terms of data kept beside an agent state
/// (see [`Symmetry::fingerprint_with`]).
pub struct Renaming<'a> {
    sym: &'a Symmetry,
    perm: &'a [u16],
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
    /// The symmetry of `project`'s `[bounds] symmetry` types, or `None` when no symmetric
    /// type has two objects. Fails, naming the place, when something names an object of a
    /// symmetric type in a way that renaming would not preserve.
    pub fn new(project: &Project, sem: &Semantics) -> Result<Option<Symmetry>, Vec<Diagnostic>> {
        let u = &project.universe;
        let mut groups = Vec::new();
        let mut objects = Vec::new();
        let mut type_names = Vec::new();
        for t in &project.manifest.bounds.symmetry {
            let Some(ty) = u.type_id(&t.value) else {
                continue;
            };
            // The objects of exactly this type: a subtype's objects are not interchangeable
            // with them.
            let objs: Vec<ObjectId> = u
                .objects_of(ty)
                .iter()
                .copied()
                .filter(|&o| u.object_type(o) == ty)
                .collect();
            if objs.len() < 2 {
                continue;
            }
            let start = objects.len() as u16;
            groups.push((start..start + objs.len() as u16).collect::<Vec<u16>>());
            objects.extend(objs);
            type_names.push((t.value.clone(), t.span));
        }
        if groups.is_empty() {
            return Ok(None);
        }
        let names: Vec<Arc<str>> = objects.iter().map(|&o| u.object_name_arc(o)).collect();
        let by_name = names
            .iter()
            .enumerate()
            .map(|(i, n)| (n.clone(), i as u16))
            .collect();
        let mut group_of = vec![0u16; objects.len()];
        for (g, members) in groups.iter().enumerate() {
            for &m in members {
                group_of[m as usize] = g as u16;
            }
        }
        let mut sym_of: HashMap<ObjectId, u16> = HashMap::new();
        for (i, &o) in objects.iter().enumerate() {
            sym_of.insert(o, i as u16);
        }
        let position: Vec<Vec<u32>> = (0..u.type_count())
            .map(|t| {
                let members = u.objects_of(crate::model::universe::TypeId(t as u16));
                objects
                    .iter()
                    .map(|o| {
                        members
                            .iter()
                            .position(|m| m == o)
                            .map_or(u32::MAX, |p| p as u32)
                    })
                    .collect()
            })
            .collect();
        let atoms = &project.atoms;
        let mut atom_args = Vec::with_capacity(atoms.len());
        for a in 0..atoms.len() as u32 {
            let (p, args) = atoms.decode(AtomId(a));
            let params = atoms.pred_params(p);
            let mut stride = 1u32;
            let mut list = Vec::new();
            for i in (0..args.len()).rev() {
                if let Some(&s) = sym_of.get(&args[i]) {
                    list.push((stride, params[i].0, s));
                }
                stride *= u.objects_of(params[i]).len() as u32;
            }
            atom_args.push(list);
        }
        let mut sym = Symmetry {
            groups,
            objects,
            names,
            by_name,
            group_of,
            atom_args,
            involves: Vec::new(),
            position,
            request_involves: Vec::new(),
            requests: sem.requests.clone(),
            request_index: sem
                .requests
                .iter()
                .enumerate()
                .map(|(i, r)| (r.clone(), i as u8))
                .collect(),
            atom_count: atoms.len(),
        };
        sym.involves = (0..atoms.len() as u32)
            .map(|a| sym.atom_involves(AtomId(a)))
            .collect();
        let mut errors = sym.check_sources(project, &type_names);
        errors.extend(sym.check_manifest(project, &type_names));
        if !errors.is_empty() {
            return Err(errors);
        }
        sym.request_involves = (0..sym.requests.len())
            .map(|r| sym.request_key(r))
            .collect();
        Ok(Some(sym))
    }

    /// The symmetric types' names and object counts, for reports.
    pub fn describe(&self, project: &Project) -> Vec<(String, usize)> {
        self.groups
            .iter()
            .map(|g| {
                let o = self.objects[g[0] as usize];
                let t = project.universe.object_type(o);
                (project.universe.type_name(t).to_string(), g.len())
            })
            .collect()
    }

    fn identity(&self) -> Perm {
        (0..self.objects.len() as u16).collect()
    }

    /// Generators of the renamings: per type, a swap of its first two objects and a
    /// rotation of all of them (they generate every permutation).
    fn generators(&self) -> Vec<Perm> {
        let mut out = Vec::new();
        for g in &self.groups {
            let mut swap = self.identity();
            swap.swap(g[0] as usize, g[1] as usize);
            out.push(swap);
            if g.len() > 2 {
                let mut rot = self.identity();
                for (i, &m) in g.iter().enumerate() {
                    rot[m as usize] = g[(i + 1) % g.len()];
                }
                out.push(rot);
            }
        }
        out
    }

    /// The image of an atom under a renaming.
    fn atom_image(&self, a: AtomId, perm: &[u16]) -> AtomId {
        let mut id = i64::from(a.0);
        for &(stride, t, s) in &self.atom_args[a.0 as usize] {
            let pos = &self.position[t as usize];
            id += i64::from(stride)
                * (i64::from(pos[perm[s as usize] as usize]) - i64::from(pos[s as usize]));
        }
        AtomId(id as u32)
    }

    fn atom_involves(&self, a: AtomId) -> Involves {
        let args = &self.atom_args[a.0 as usize];
        let Some(&(_, _, first)) = args.first() else {
            return Involves::None;
        };
        if args.iter().any(|&(_, _, s)| s != first) {
            return Involves::Many;
        }
        let mut perm = self.identity();
        let g = &self.groups[self.group_of[first as usize] as usize];
        perm[first as usize] = g[0];
        // Not a bijection, but the image of this one atom is all that is asked.
        Involves::One(first, self.atom_image(a, &perm).0)
    }

    fn request_key(&self, r: usize) -> Involves {
        let mut found: Vec<u16> = Vec::new();
        self.collect_objects(&self.requests[r], &mut found);
        found.dedup();
        match found.as_slice() {
            [] => Involves::None,
            [s] => {
                let mut perm = self.identity();
                perm[*s as usize] = self.groups[self.group_of[*s as usize] as usize][0];
                let key = self
                    .rename(&self.requests[r], &perm)
                    .and_then(|t| self.request_index.get(&t).copied())
                    .map_or(u32::MAX, u32::from);
                Involves::One(*s, key)
            }
            _ => Involves::Many,
        }
    }

    /// Appends the symmetric objects in `t`, in order of occurrence.
    fn collect_objects(&self, t: &Term, out: &mut Vec<u16>) {
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
    fn rename(&self, t: &Term, perm: &[u16]) -> Option<Term> {
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
    fn apply(&self, s: &State, perm: &[u16]) -> State {
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
            requested,
        }
    }

    /// The symmetric objects in the order they first occur in the state's terms.
    fn occurrences(&self, s: &State) -> Vec<u16> {
        let mut out = Vec::new();
        for e in &s.events {
            self.collect_objects(&e.trigger.literal, &mut out);
            self.origin_objects(e.origin, &mut out);
            if let Some(i) = &e.intention {
                self.intention_objects(i, &mut out);
            }
        }
        for i in s
            .intentions
            .iter()
            .chain(s.pending.iter().map(|p| &p.intention))
        {
            self.intention_objects(i, &mut out);
        }
        // The belief-base order tells interchangeable objects apart too: `cupAt(cup2, _)`
        // added after `cupAt(cup1, _)` is answered first.
        for a in &s.order {
            for &(_, _, o) in &self.atom_args[a.0 as usize] {
                if !out.contains(&o) {
                    out.push(o);
                }
            }
        }
        out
    }

    fn origin_objects(&self, o: Origin, out: &mut Vec<u16>) {
        if let Origin::Request(r) = o {
            self.collect_objects(&self.requests[r as usize], out);
        }
    }

    fn intention_objects(&self, i: &Intention, out: &mut Vec<u16>) {
        self.origin_objects(i.origin, out);
        for f in &i.frames {
            self.collect_objects(&f.trigger.literal, out);
            for (_, t) in f.subst.iter() {
                self.collect_objects(t, out);
            }
            for c in &f.cursors {
                let subs: Vec<&Substitution> = match &c.kind {
                    CursorKind::For { rest, base } => {
                        rest.iter().chain(std::iter::once(base)).collect()
                    }
                    CursorKind::While { base, .. } => vec![base],
                    CursorKind::Seq => Vec::new(),
                };
                for sub in subs {
                    for (_, t) in sub.iter() {
                        self.collect_objects(t, out);
                    }
                }
            }
        }
    }

    /// The renaming that takes `s` to its canonical member (see the module documentation),
    /// and whether ties between objects that are not interchangeable remain to be tried.
    fn sorting(&self, s: &State) -> (Perm, Vec<Vec<u16>>) {
        let n = self.objects.len();
        // (first occurrence, hash of the atoms and requests that involve the object alone,
        // whether it shares an atom or a request with another symmetric object)
        let mut first = vec![u32::MAX; n];
        for (k, o) in self.occurrences(s).into_iter().enumerate() {
            first[o as usize] = k as u32;
        }
        let mut hash = vec![0u64; n];
        let mut shared = vec![false; n];
        for a in s.beliefs.iter() {
            match self.involves[a.0 as usize] {
                Involves::None => {}
                Involves::One(o, key) => {
                    hash[o as usize] = hash[o as usize].wrapping_add(mix(u64::from(key)));
                }
                Involves::Many => {
                    for &(_, _, o) in &self.atom_args[a.0 as usize] {
                        shared[o as usize] = true;
                    }
                }
            }
        }
        for (r, inv) in self.request_involves.iter().enumerate() {
            if s.requested >> r & 1 == 0 {
                continue;
            }
            match *inv {
                Involves::None => {}
                Involves::One(o, key) => {
                    // Tagged apart from atom ids.
                    let key = u64::from(key) | 1 << 40;
                    hash[o as usize] = hash[o as usize].wrapping_add(mix(key));
                }
                Involves::Many => {
                    let mut objs = Vec::new();
                    self.collect_objects(&self.requests[r], &mut objs);
                    objs.iter().for_each(|&o| shared[o as usize] = true);
                }
            }
        }
        let mut perm = self.identity();
        let mut ties = Vec::new();
        for g in &self.groups {
            let mut order = g.clone();
            order.sort_by_key(|&o| (first[o as usize], hash[o as usize], shared[o as usize], o));
            for (slot, &o) in order.iter().enumerate() {
                perm[o as usize] = g[slot];
            }
            // Runs of equal signatures among objects that are not interchangeable.
            let key = |o: u16| (first[o as usize], hash[o as usize], shared[o as usize]);
            let mut i = 0;
            while i < order.len() {
                let mut j = i + 1;
                while j < order.len() && key(order[j]) == key(order[i]) {
                    j += 1;
                }
                if j - i > 1 && shared[order[i] as usize] {
                    ties.push(g[i..j].to_vec());
                }
                i = j;
            }
        }
        (perm, ties)
    }

    /// The renamings that may take `s` to its canonical member: the sorting order, and
    /// when objects tie, that order with every arrangement of each tie (none beyond
    /// [`MAX_TIE_ORDERS`]).
    fn candidates(&self, s: &State) -> Vec<Perm> {
        let (perm, ties) = self.sorting(s);
        let orders: usize = ties
            .iter()
            .map(|t| (1..=t.len()).product::<usize>())
            .try_fold(1usize, |acc, k| acc.checked_mul(k))
            .unwrap_or(usize::MAX);
        if ties.is_empty() || orders > MAX_TIE_ORDERS {
            return vec![perm];
        }
        // Every order of every tie (slots within a tie are permuted after sorting).
        let mut out = Vec::new();
        let mut arrangement: Vec<Vec<u16>> = ties.clone();
        loop {
            let mut p = perm.clone();
            for (tie, arr) in ties.iter().zip(&arrangement) {
                let mut remap = self.identity();
                for (k, &slot) in tie.iter().enumerate() {
                    remap[slot as usize] = arr[k];
                }
                p.iter_mut().for_each(|x| *x = remap[*x as usize]);
            }
            out.push(p);
            if !next_arrangement(&mut arrangement) {
                break;
            }
        }
        out
    }

    /// The canonical member of `s`'s class and its fingerprint.
    pub fn canonical(&self, s: &State) -> (u64, Option<State>) {
        let candidates = self.candidates(s);
        if let [p] = candidates.as_slice() {
            if p.iter().enumerate().all(|(i, &x)| x as usize == i) {
                return (fingerprint(s), None);
            }
        }
        let (fp, c) = candidates
            .iter()
            .map(|p| {
                let c = self.apply(s, p);
                (fingerprint(&c), c)
            })
            .min_by_key(|(fp, _)| *fp)
            .expect("at least one candidate");
        (fp, Some(c))
    }

    /// The fingerprint of a renaming of `s` together with data about it (`extra`, given the
    /// same renaming to apply to its terms): the least over the renamings [`canonical`]
    /// tries. A model whose states are an agent state and more (a user's view of the run)
    /// stores them under it; since every renaming is applied to the whole, two states are
    /// only merged when one is a renaming of the other.
    ///
    /// [`canonical`]: Symmetry::canonical
    pub fn fingerprint_with<H: std::hash::Hash>(
        &self,
        s: &State,
        extra: impl Fn(&Renaming) -> H,
    ) -> u64 {
        self.candidates(s)
            .iter()
            .map(|p| {
                let r = Renaming { sym: self, perm: p };
                fingerprint(&(self.apply(s, p), extra(&r)))
            })
            .min()
            .expect("at least one candidate")
    }

    /// Whether the reasoning cycle treats the objects alike at `s`: for each generator `g`
    /// of the renamings, the successors of `g(s)` are renamings of the successors of `s`
    /// (compared as multisets of canonical fingerprints). Reduction is exact when this holds
    /// at every state; Jason's first-answer selection can break it (answers come in belief
    /// order, so `cup1` before `cup2`). `None` when it holds, otherwise the renaming that
    /// breaks it, as object names.
    pub fn equivariance_violation(&self, sem: &Semantics, s: &State) -> Option<String> {
        self.equivariance_violation_with(s, |st| {
            sem.successors(st).into_iter().map(|t| t.next).collect()
        })
    }

    /// [`Symmetry::equivariance_violation`], with the successor states computed by
    /// `successors` (the compiled reasoning cycle's, say).
    pub fn equivariance_violation_with(
        &self,
        s: &State,
        successors: impl Fn(&State) -> Vec<State>,
    ) -> Option<String> {
        let classes = |st: &State| {
            let mut v: Vec<u64> = successors(st).iter().map(|t| self.fingerprint(t)).collect();
            v.sort_unstable();
            v
        };
        let here = classes(s);
        self.generators().into_iter().find_map(|g| {
            (classes(&self.apply(s, &g)) != here).then(|| {
                let moved: Vec<String> = g
                    .iter()
                    .enumerate()
                    .filter(|(i, &j)| *i != j as usize)
                    .map(|(i, &j)| format!("{} -> {}", self.names[i], self.names[j as usize]))
                    .collect();
                moved.join(", ")
            })
        })
    }

    /// The canonical fingerprint of `s`.
    pub fn fingerprint(&self, s: &State) -> u64 {
        self.canonical(s).0
    }

    // ---- soundness checks ----

    fn refuse(&self, span: Span, name: &str, what: &str, types: &[(String, Span)]) -> Diagnostic {
        let s = self.by_name[name];
        let (ty, ty_span) = &types[self.group_of[s as usize] as usize];
        Diagnostic::error(
            "symmetry",
            format!(
                "{what} names `{name}`, an object of type `{ty}`, which `[bounds] symmetry` declares interchangeable: symmetry reduction would be unsound"
            ),
        )
        .with_label(span, format!("names `{name}`"))
        .with_secondary(*ty_span, "declared symmetric here")
        .with_help(format!(
            "use a variable instead of `{name}`, remove \"{ty}\" from `[bounds] symmetry`, or run with `--no-symmetry`"
        ))
    }

    /// Plan library and PDDL files: no symmetric object may be named.
    fn check_sources(&self, project: &Project, types: &[(String, Span)]) -> Vec<Diagnostic> {
        let mut out = Vec::new();
        for f in project.map.files() {
            let ext = f.path.extension().and_then(|e| e.to_str()).unwrap_or("");
            let (what, pddl) = match ext {
                "asl" => ("the plan library", false),
                "pddl" => ("the PDDL domain", true),
                _ => continue,
            };
            for (start, word) in words(&f.text, pddl) {
                let hit = if pddl {
                    self.names.iter().find(|n| n.eq_ignore_ascii_case(word))
                } else {
                    self.names.iter().find(|n| &***n == word)
                };
                if let Some(n) = hit {
                    let span = Span::new(f.id, start, start + word.len());
                    out.push(self.refuse(span, n, what, types));
                }
            }
        }
        out
    }

    /// Manifest formulas and requests that name a symmetric object must be symmetric;
    /// explanation patterns and phrases must not name one; initial states and requests must
    /// be closed under renaming.
    fn check_manifest(&self, project: &Project, types: &[(String, Span)]) -> Vec<Diagnostic> {
        let m = &project.manifest;
        let mut out = Vec::new();
        let named = |text: &str| -> Option<&Arc<str>> {
            words(text, false)
                .into_iter()
                .find_map(|(_, w)| self.names.iter().find(|n| &***n == w))
        };
        let mut formulas: Vec<(&str, Span, &crate::syntax::ast::Expr, String)> = Vec::new();
        for f in &m.initial.facts {
            formulas.push((&f.text, f.span, &f.expr, "the initial fact".into()));
        }
        for f in &m.initial.constraints {
            formulas.push((&f.text, f.span, &f.expr, "the initial constraint".into()));
        }
        for i in &m.invariants {
            let what = format!("invariant `{}`", i.name.value);
            formulas.push((&i.formula.text, i.formula.span, &i.formula.expr, what));
        }
        for p in &m.properties {
            let what = format!("property `{}`", p.name.value);
            formulas.push((&p.formula.text, p.formula.span, &p.formula.expr, what));
        }
        let gens = self.generators();
        for (text, span, expr, what) in formulas {
            let Some(name) = named(text) else { continue };
            let symmetric = crate::model::formula::compile(expr, &project.atoms, &project.universe)
                .map(|c| {
                    let base = self.normal(&c, &self.identity());
                    gens.iter().all(|g| self.normal(&c, g) == base)
                })
                .unwrap_or(false);
            if !symmetric {
                let what = format!("{what}, which is not symmetric in these objects,");
                out.push(self.refuse(span, name, &what, types));
            }
        }
        // Requests: renaming must map requests to requests.
        let closed = (0..self.requests.len()).all(|r| {
            gens.iter().all(|g| {
                self.rename(&self.requests[r], g)
                    .is_none_or(|t| self.request_index.contains_key(&t))
            })
        });
        if !closed {
            for f in &m.requests.goals {
                if let Some(name) = named(&f.text) {
                    out.push(self.refuse(f.span, name, "the request", types));
                }
            }
        }
        if let Some(e) = &m.explanation {
            let mut patterns: Vec<(&str, Span, &str)> = Vec::new();
            for p in &e.phrases {
                patterns.push((&p.pattern.text, p.pattern.span, "the phrase pattern"));
                patterns.push((&p.template.value, p.template.span, "the phrase"));
            }
            for u in &e.users {
                for pair in &u.expected {
                    for side in [&pair.before, &pair.after] {
                        patterns.push((&side.text, side.span, "the expected pair"));
                    }
                }
            }
            for (text, span, what) in patterns {
                if let Some(name) = named(text) {
                    out.push(self.refuse(span, name, what, types));
                }
            }
        }
        // The initial states: a set closed under renaming (facts and constraints that name
        // no object are; this catches the rest).
        if out.is_empty() {
            let init: HashSet<&AtomSet> = project.initial.states.iter().collect();
            let open = project.initial.states.iter().find(|s| {
                gens.iter().any(|g| {
                    let mut img = AtomSet::empty(self.atom_count);
                    s.iter().for_each(|a| img.insert(self.atom_image(a, g)));
                    !init.contains(&img)
                })
            });
            if open.is_some() {
                let span = m
                    .initial
                    .facts
                    .first()
                    .map_or(m.bounds.symmetry[0].span, |f| f.span);
                out.push(
                    Diagnostic::error(
                        "symmetry",
                        "the initial states are not symmetric in the objects `[bounds] symmetry` declares interchangeable: renaming them turns an initial state into one that is not initial",
                    )
                    .with_label(span, "the initial states")
                    .with_help("remove the type from `[bounds] symmetry`, or run with `--no-symmetry`"),
                );
            }
        }
        out
    }

    /// A condition under a renaming, in a form where the order of `&`, `|` and `.count`
    /// operands does not matter.
    fn normal(&self, c: &Cond, perm: &[u16]) -> Normal {
        match c {
            Cond::True => Normal::True,
            Cond::False => Normal::False,
            Cond::Atom(a) => Normal::Atom(self.atom_image(*a, perm).0),
            Cond::Not(inner) => Normal::Not(Box::new(self.normal(inner, perm))),
            Cond::And(parts) | Cond::Or(parts) => {
                let mut v: Vec<Normal> = parts.iter().map(|p| self.normal(p, perm)).collect();
                v.sort();
                if matches!(c, Cond::And(_)) {
                    Normal::And(v)
                } else {
                    Normal::Or(v)
                }
            }
            Cond::Count { atoms, cmp, n } => {
                let mut v: Vec<u32> = atoms.iter().map(|a| self.atom_image(*a, perm).0).collect();
                v.sort();
                let cmp = match cmp {
                    CountCmp::Eq => 0,
                    CountCmp::Lt => 1,
                    CountCmp::Le => 2,
                    CountCmp::Gt => 3,
                    CountCmp::Ge => 4,
                    CountCmp::Ne => 5,
                };
                Normal::Count(v, cmp, *n)
            }
        }
    }
}

/// A condition with sorted operands (see [`Symmetry::normal`]).
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Normal {
    True,
    False,
    Atom(u32),
    Not(Box<Normal>),
    And(Vec<Normal>),
    Or(Vec<Normal>),
    Count(Vec<u32>, u8, i64),
}

/// A 64-bit mixer (splitmix64's finaliser), so that sums of features rarely collide.
fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// The next arrangement of every tie, in lexicographic order of the ties (odometer of
/// per-tie permutations). Returns `false` after the last.
fn next_arrangement(ties: &mut [Vec<u16>]) -> bool {
    for t in ties.iter_mut().rev() {
        if next_permutation(t) {
            return true;
        }
        // Wrapped around: `t` is sorted again; carry to the previous tie.
    }
    false
}

/// The next permutation in lexicographic order, or `false` (and the first one) after the
/// last.
fn next_permutation(v: &mut [u16]) -> bool {
    let n = v.len();
    if n < 2 {
        return false;
    }
    let mut i = n - 1;
    while i > 0 && v[i - 1] >= v[i] {
        i -= 1;
    }
    if i == 0 {
        v.reverse();
        return false;
    }
    let mut j = n - 1;
    while v[j] <= v[i - 1] {
        j -= 1;
    }
    v.swap(i - 1, j);
    v[i..].reverse();
    true
}

/// The lower-case identifiers of a source text (object names are those), with their byte
/// offsets; comments and strings skipped. `pddl` selects `;` comments, otherwise `//` and
/// `/* */`. An identifier right after `.` (an internal action) or `?` (a PDDL variable) is
/// not a name.
fn words(text: &str, pddl: bool) -> Vec<(usize, &str)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if pddl && c == b';' || !pddl && c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if !pddl && c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                i += 1;
            }
            i += 2;
        } else if c == b'"' || !pddl && c == b'\'' {
            i += 1;
            while i < b.len() && b[i] != c {
                if b[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || pddl && b[i] == b'-')
            {
                i += 1;
            }
            let prev = start.checked_sub(1).map(|p| b[p]);
            let variable = !pddl && (c.is_ascii_uppercase() || c == b'_');
            if !variable && prev != Some(b'.') && prev != Some(b'?') {
                out.push((start, &text[start..i]));
            }
        } else {
            i += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_skip_comments_strings_variables_and_internal_actions() {
        let asl = "+!g(C) : cupAt(C, cup1) // cup2\n <- .print(\"cup3\"); /* cup4 */ go(cup5).";
        let w: Vec<&str> = words(asl, false).into_iter().map(|(_, w)| w).collect();
        assert_eq!(w, ["g", "cupAt", "cup1", "go", "cup5"]);
        let pddl = "(:action a :parameters (?cup1 - cup) ; cup2\n :effect (used cup3))";
        let w: Vec<&str> = words(pddl, true).into_iter().map(|(_, w)| w).collect();
        assert!(w.contains(&"cup3") && !w.contains(&"cup1") && !w.contains(&"cup2"));
    }

    #[test]
    fn arrangements_cover_every_order_once() {
        let mut ties = vec![vec![0, 1, 2], vec![3, 4]];
        let mut seen = HashSet::new();
        loop {
            assert!(seen.insert(ties.clone()));
            if !next_arrangement(&mut ties) {
                break;
            }
        }
        assert_eq!(seen.len(), 12);
        assert_eq!(ties, vec![vec![0, 1, 2], vec![3, 4]]);
    }
}
