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
//! plan library, PDDL domain, explanation pattern or phrase that names one of them, and an
//! initial fact or constraint, invariant or request that names one unless it is symmetric
//! (`cupAt(cup1, c) & cupAt(cup2, c)` with two cups is), and checks that the initial states
//! and the requests are closed under renaming. Properties that name objects are decided on
//! a search that fixes them ([`RunPlan`]).

mod agents;
mod canonical;
mod rename;
mod runs;
mod soundness;

pub use agents::{AgentPerm, Instances};
pub use rename::Renaming;
pub use runs::{Fixing, RunPlan};

use crate::model::atoms::AtomId;
use crate::model::project::Project;
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::semantics::Semantics;
use crate::syntax::Diagnostic;
use std::collections::HashMap;
use std::sync::Arc;

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
    /// Generators of the renamings (see [`Symmetry::generators`]).
    generators: Vec<Perm>,
    /// Distinct for each symmetry made: its tag for what it derives from a compiled
    /// system's parts ([`crate::semantics::Compiled::derived`]).
    serial: u64,
}

/// The next [`Symmetry`]'s serial.
static SERIAL: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// A renaming: symmetric index -> symmetric index.
type Perm = Vec<u16>;

impl Symmetry {
    /// The symmetry of `project`'s `[bounds] symmetry` types, or `None` when no symmetric
    /// type has two objects. Fails, naming the place, when something names an object of a
    /// symmetric type in a way that renaming would not preserve.
    pub fn new(project: &Project, sem: &Semantics) -> Result<Option<Symmetry>, Vec<Diagnostic>> {
        let Some((sym, type_names)) = Symmetry::build(project, sem, &[]) else {
            return Ok(None);
        };
        let mut errors = sym.check_sources(project, &type_names);
        errors.extend(sym.check_manifest(project, &type_names));
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok(Some(sym))
    }

    /// The renamings that leave each object of `fixed` in place (a subgroup: sound
    /// wherever the whole group is, so nothing is checked again), or `None` when no type
    /// keeps two objects to rename.
    pub fn fixing(&self, project: &Project, sem: &Semantics, fixed: &[u16]) -> Option<Symmetry> {
        let fixed: Vec<ObjectId> = fixed.iter().map(|&s| self.objects[s as usize]).collect();
        Symmetry::build(project, sem, &fixed).map(|(sym, _)| sym)
    }

    /// The symmetry of the `[bounds] symmetry` types with the objects `fixed` left out,
    /// with the types' names and places, unchecked.
    fn build(
        project: &Project,
        sem: &Semantics,
        fixed: &[ObjectId],
    ) -> Option<(Symmetry, Vec<(String, crate::syntax::Span)>)> {
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
                .filter(|&o| u.object_type(o) == ty && !fixed.contains(&o))
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
            return None;
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
            serial: SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            generators: Vec::new(),
        };
        sym.generators = sym.generators_of_groups();
        sym.involves = (0..atoms.len() as u32)
            .map(|a| sym.atom_involves(AtomId(a)))
            .collect();
        sym.request_involves = (0..sym.requests.len())
            .map(|r| sym.request_key(r))
            .collect();
        Some((sym, type_names))
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
    fn generators(&self) -> &[Perm] {
        &self.generators
    }

    fn generators_of_groups(&self) -> Vec<Perm> {
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
}

/// What tests that count classes need: every renaming of the group, and each applied.
#[cfg(test)]
impl Symmetry {
    /// Every renaming the generators make (their closure under composition), the identity
    /// first.
    pub(crate) fn group(&self) -> Vec<Perm> {
        let mut all = vec![self.identity()];
        let mut k = 0;
        while k < all.len() {
            for g in self.generators() {
                let next: Perm = all[k].iter().map(|&x| g[x as usize]).collect();
                if !all.contains(&next) {
                    all.push(next);
                }
            }
            k += 1;
        }
        all
    }

    /// The renaming `perm`, to rename terms and views with.
    pub(crate) fn renaming<'a>(&'a self, perm: &'a [u16]) -> Renaming<'a> {
        Renaming { sym: self, perm }
    }

    /// `s` with every object renamed by `perm`.
    pub(crate) fn renamed(
        &self,
        s: &crate::semantics::State,
        perm: &[u16],
    ) -> crate::semantics::State {
        self.apply(s, perm)
    }
}

/// A 64-bit mixer (splitmix64's finaliser), so that sums of features rarely collide.
pub(super) fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// The next arrangement of every tie, in lexicographic order of the ties (odometer of
/// per-tie permutations). Returns `false` after the last.
pub(super) fn next_arrangement<T: Ord>(ties: &mut [Vec<T>]) -> bool {
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
pub(super) fn next_permutation<T: Ord>(v: &mut [T]) -> bool {
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
