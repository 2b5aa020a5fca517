//! Run properties under symmetry: which formulas the graph reduced by every renaming
//! decides as they are, and which need a graph reduced only by the renamings that fix the
//! objects they name.
//!
//! A formula that every renaming maps to itself reads the same letters on a state and on
//! any renaming of it, so the reduced graph is bisimilar to the full one for it and the
//! product runs on the reduced graph directly. A formula naming `cup1` does not: it is
//! decided on a graph reduced by the renamings that leave `cup1` in place (a subgroup, so
//! as sound as the whole group).
//!
//! One instance does not vouch for its renamings: `C = cup1` holding does not make
//! `C = cup2` hold, since Jason's belief order depends on names (initial beliefs come in
//! an order that names decide, and a query answers in that order), so the runs from the
//! initial states are not closed under renaming (tests/verify/symmetric_order). Every
//! instance is decided.

use super::soundness::{normal, Normal};
use super::Symmetry;
use crate::model::ltl::Ltl;
use crate::model::property::{Atomic, Atomics, RunProperty};
use crate::model::term::Term;

/// Where the instances of the run properties are decided under symmetry.
#[derive(Debug, Default)]
pub struct RunPlan {
    /// Decided on the graph reduced by every renaming: the instances no renaming changes,
    /// each property with its index among those planned.
    pub whole: Vec<(usize, RunProperty)>,
    /// The other instances: decided on a graph reduced by the renamings that fix every
    /// object they name.
    pub fixing: Option<Fixing>,
}

/// The instances decided on a graph reduced by the renamings that fix some objects.
#[derive(Debug)]
pub struct Fixing {
    /// The objects left in place (symmetric indices, sorted).
    pub objects: Vec<u16>,
    /// Their names, for the phase's name.
    pub names: Vec<String>,
    /// Each property with its index among those planned, and its instances decided here.
    pub props: Vec<(usize, RunProperty)>,
}

/// A formula up to the order of `&` and `|` operands, its propositions mapped by a
/// renaming: equal keys mean equal formulas.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    True,
    False,
    Prop(PropKey),
    Not(Box<Key>),
    And(Vec<Key>),
    Or(Vec<Key>),
    Next(Box<Key>),
    Until(Box<Key>, Box<Key>),
    Release(Box<Key>, Box<Key>),
}

/// A proposition as a renaming maps it.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
enum PropKey {
    Beliefs(Normal),
    /// The modality (its position in [`Atomic`]), the agent, the term.
    Term(u8, u8, Term),
}

impl Symmetry {
    /// Plans where each instance of `props` is decided (see the module's documentation):
    /// the instances no renaming changes on the whole graph, the others on one graph that
    /// fixes every object they name. `props` must not include those decided on users'
    /// searches.
    pub fn plan_runs(&self, atomics: &Atomics, props: &[RunProperty]) -> RunPlan {
        let gens = self.generators();
        let id = self.identity();
        let mut plan = RunPlan::default();
        let mut objects: Vec<u16> = Vec::new();
        let mut rest: Vec<(usize, RunProperty)> = Vec::new();
        for (k, p) in props.iter().enumerate() {
            let (mut whole, mut fixed) = (p.clone(), p.clone());
            (whole.instances, fixed.instances) = p.instances.iter().cloned().partition(|i| {
                let named = self.named(atomics, &i.formula);
                let base = self.key(atomics, &i.formula, &id);
                let same = named.is_empty()
                    || gens
                        .iter()
                        .all(|g| self.key(atomics, &i.formula, g) == base);
                if !same {
                    objects.extend(named);
                }
                same
            });
            // A property with no instance (a type without objects) is decided, trivially,
            // on the whole graph.
            if !whole.instances.is_empty() || fixed.instances.is_empty() {
                plan.whole.push((k, whole));
            }
            if !fixed.instances.is_empty() {
                rest.push((k, fixed));
            }
        }
        objects.sort_unstable();
        objects.dedup();
        if !rest.is_empty() {
            plan.fixing = Some(Fixing {
                names: objects
                    .iter()
                    .map(|&o| self.names[o as usize].to_string())
                    .collect(),
                objects,
                props: rest,
            });
        }
        plan
    }

    /// The symmetric objects the propositions of `f` name, sorted.
    fn named(&self, atomics: &Atomics, f: &Ltl) -> Vec<u16> {
        let mut out = Vec::new();
        for p in f.named_props() {
            match &atomics.list[p as usize] {
                Atomic::Beliefs(c) => {
                    for a in c.atoms() {
                        for &(_, _, s) in &self.atom_args[a.0 as usize] {
                            if !out.contains(&s) {
                                out.push(s);
                            }
                        }
                    }
                }
                Atomic::Intends(_, t)
                | Atomic::Desires(_, t)
                | Atomic::Requested(t)
                | Atomic::Did(_, t)
                | Atomic::Explained(t) => self.collect_objects(t, &mut out),
            }
        }
        out.sort_unstable();
        out
    }

    /// `f` renamed by `perm`, as a [`Key`].
    fn key(&self, atomics: &Atomics, f: &Ltl, perm: &[u16]) -> Key {
        let b = |x: &Ltl| Box::new(self.key(atomics, x, perm));
        match f {
            Ltl::True => Key::True,
            Ltl::False => Key::False,
            Ltl::Prop(p) => Key::Prop(self.prop_key(&atomics.list[*p as usize], perm)),
            Ltl::Not(a) => Key::Not(b(a)),
            Ltl::Next(a) => Key::Next(b(a)),
            Ltl::Until(x, y) => Key::Until(b(x), b(y)),
            Ltl::Release(x, y) => Key::Release(b(x), b(y)),
            Ltl::And(..) | Ltl::Or(..) => {
                let and = matches!(f, Ltl::And(..));
                let mut parts = Vec::new();
                operands(f, and, &mut parts);
                let mut keys: Vec<Key> = parts.iter().map(|x| self.key(atomics, x, perm)).collect();
                keys.sort();
                if and {
                    Key::And(keys)
                } else {
                    Key::Or(keys)
                }
            }
        }
    }

    fn prop_key(&self, a: &Atomic, perm: &[u16]) -> PropKey {
        let term = |kind: u8, agent: u8, t: &Term| {
            PropKey::Term(
                kind,
                agent,
                self.rename(t, perm).unwrap_or_else(|| t.clone()),
            )
        };
        match a {
            Atomic::Beliefs(c) => PropKey::Beliefs(normal(c, &|x| self.atom_image(x, perm))),
            Atomic::Intends(k, t) => term(0, *k, t),
            Atomic::Desires(k, t) => term(1, *k, t),
            Atomic::Requested(t) => term(2, 0, t),
            Atomic::Did(k, t) => term(3, *k, t),
            Atomic::Explained(t) => term(4, 0, t),
        }
    }
}

/// The operands of a chain of `&` (`and`) or `|`, nested ones flattened.
fn operands<'f>(f: &'f Ltl, and: bool, out: &mut Vec<&'f Ltl>) {
    match f {
        Ltl::And(x, y) if and => {
            operands(x, and, out);
            operands(y, and, out);
        }
        Ltl::Or(x, y) if !and => {
            operands(x, and, out);
            operands(y, and, out);
        }
        _ => out.push(f),
    }
}
