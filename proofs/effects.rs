//! PDDL effect application (`GroundAction::apply`): every `when` is read in the state before
//! the action, then all deletions of the effects that fire, then all their additions.
//!
//! Actions over three atoms with up to [`MAX_EFFECTS`] conditional effects; a `when` is
//! `true`, `false`, an atom or a negated atom; adds and deletes are any subsets. The
//! reference is PDDL's definition, computed on bitmasks.

use crate::model::atoms::{AtomId, AtomSet};
use crate::model::cond::Cond;
use crate::model::ground::{CondEffect, GroundAction};

/// Atoms of the state.
pub const ATOMS: usize = 3;
/// Most conditional effects of one action.
pub const MAX_EFFECTS: usize = 3;
/// `when` codes: `true`, `false`, atoms 0-2, `not` atoms 0-2.
pub const WHENS: u8 = 8;

/// One conditional effect: `when` code, add mask, delete mask.
pub type SmallEffect = [u8; 3];

/// A state (bit `k` = atom `k`) and an action's effects, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallApply {
    state: u8,
    count: u8,
    effects: [SmallEffect; MAX_EFFECTS],
}

impl SmallApply {
    /// The input these codes spell, if canonical: in range, unused effects all 0.
    pub fn new(state: u8, count: u8, effects: [SmallEffect; MAX_EFFECTS]) -> Option<SmallApply> {
        let ok = state < 8
            && usize::from(count) <= MAX_EFFECTS
            && effects.iter().enumerate().all(|(i, e)| {
                if i < usize::from(count) {
                    e[0] < WHENS && e[1] < 8 && e[2] < 8
                } else {
                    *e == [0; 3]
                }
            });
        ok.then_some(SmallApply {
            state,
            count,
            effects,
        })
    }

    /// The number of effects.
    pub fn count(&self) -> usize {
        usize::from(self.count)
    }

    fn effects(&self) -> &[SmallEffect] {
        &self.effects[..self.count()]
    }

    /// The crate's action.
    pub fn action(&self) -> GroundAction {
        GroundAction {
            schema: 0,
            name: "act".into(),
            args: Vec::new(),
            pre: Cond::True,
            effects: self
                .effects()
                .iter()
                .map(|e| CondEffect {
                    when: when(e[0]),
                    add: atoms_of(e[1]),
                    del: atoms_of(e[2]),
                })
                .collect(),
        }
    }

    /// Whether effect `i`'s `when` holds in the state before the action.
    pub fn fires(&self, i: usize) -> bool {
        let w = self.effects[i][0];
        match w {
            0 => true,
            1 => false,
            2..=4 => self.state >> (w - 2) & 1 == 1,
            _ => self.state >> (w - 5) & 1 == 0,
        }
    }

    /// The reference: PDDL's successor state, as a bitmask.
    pub fn reference(&self) -> u8 {
        let (mut add, mut del) = (0u8, 0u8);
        for (i, e) in self.effects().iter().enumerate() {
            if self.fires(i) {
                add |= e[1];
                del |= e[2];
            }
        }
        (self.state & !del) | add
    }
}

fn when(code: u8) -> Cond {
    match code {
        0 => Cond::True,
        1 => Cond::False,
        2..=4 => Cond::Atom(AtomId(u32::from(code - 2))),
        _ => Cond::Not(Box::new(Cond::Atom(AtomId(u32::from(code - 5))))),
    }
}

fn atoms_of(mask: u8) -> Vec<AtomId> {
    (0..ATOMS as u32)
        .filter(|k| mask >> k & 1 == 1)
        .map(AtomId)
        .collect()
}

/// The bitmask of a state.
pub fn bits(s: &AtomSet) -> u8 {
    (0..ATOMS as u32)
        .filter(|&k| s.contains(AtomId(k)))
        .fold(0, |acc, k| acc | 1 << k)
}

/// The state of a bitmask.
pub fn state(bits: u8) -> AtomSet {
    let mut s = AtomSet::empty(ATOMS);
    atoms_of(bits).into_iter().for_each(|a| s.insert(a));
    s
}

/// Every canonical input with at most `max` effects.
pub fn all_applies(max: usize) -> Vec<SmallApply> {
    let one: Vec<SmallEffect> = (0..WHENS)
        .flat_map(|w| (0..8).flat_map(move |a| (0..8).map(move |d| [w, a, d])))
        .collect();
    let mut lists: Vec<Vec<SmallEffect>> = vec![Vec::new()];
    let mut frontier: Vec<Vec<SmallEffect>> = vec![Vec::new()];
    for _ in 0..max.min(MAX_EFFECTS) {
        frontier = frontier
            .iter()
            .flat_map(|l| {
                one.iter().map(move |e| {
                    let mut l = l.clone();
                    l.push(*e);
                    l
                })
            })
            .collect();
        lists.extend(frontier.iter().cloned());
    }
    let mut out = Vec::new();
    for s in 0..8u8 {
        for l in &lists {
            let mut effects = [[0u8; 3]; MAX_EFFECTS];
            effects[..l.len()].copy_from_slice(l);
            out.push(SmallApply::new(s, l.len() as u8, effects).expect("canonical"));
        }
    }
    out
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// An atom was both deleted and added by firing effects.
    pub delete_and_add: bool,
    /// An effect fired whose `when` the earlier effects falsify (so it must read the old
    /// state), or did not fire although they make its `when` true.
    pub reads_old_state: bool,
}

/// The property, with `apply` the kernel (`GroundAction::apply`): the successor equals
/// PDDL's (all `when`s read before the action, deletions then additions); in particular an
/// atom both deleted and added ends true, and untouched atoms keep their value.
pub fn apply_is_delete_then_add(
    input: &SmallApply,
    apply: impl Fn(&GroundAction, &AtomSet) -> AtomSet,
) -> Result<Seen, String> {
    let action = input.action();
    let got = bits(&apply(&action, &state(input.state)));
    let want = input.reference();
    if got != want {
        return Err(format!(
            "state {:03b}, effects {:?}: apply gives {got:03b}, PDDL {want:03b}",
            input.state,
            input.effects()
        ));
    }
    let (mut add, mut del) = (0u8, 0u8);
    let mut reads_old_state = false;
    let mut running = input.state;
    for (i, e) in input.effects().iter().enumerate() {
        let on_running = SmallApply {
            state: running,
            ..*input
        }
        .fires(i);
        reads_old_state |= on_running != input.fires(i);
        if input.fires(i) {
            add |= e[1];
            del |= e[2];
            running = (running & !e[2]) | e[1];
        }
    }
    Ok(Seen {
        delete_and_add: add & del != 0,
        reads_old_state,
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// 3 atoms, up to 3 conditional effects, every state.
    #[kani::proof]
    #[kani::unwind(9)]
    fn effects_apply_delete_then_add_reading_the_old_state() {
        let input = SmallApply::new(kani::any(), kani::any(), kani::any());
        kani::assume(input.is_some());
        let input = input.unwrap();
        let seen = apply_is_delete_then_add(&input, GroundAction::apply);
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.delete_and_add),
            "an atom deleted and added"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.reads_old_state),
            "a when the earlier effects change"
        );
        assert!(seen.is_ok());
    }
}
