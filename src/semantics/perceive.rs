//! Perception and belief updates: the beliefs an action or a step added and removed become
//! `-p`/`+p` events (deletions first), in the order Jason's belief update meets them (the
//! bucket order of `Agent.buf`'s `java.util.HashSet` of percepts), and [`State::order`]
//! keeps the order of the beliefs whose order a query can see. Mirrors `Agent.buf` (the
//! belief update of Jason's sense phase) and the `updateEvents` that follow a belief change.

use super::cycle::Semantics;
use super::state::{Event, EventTrigger, Origin, State};
use crate::model::atoms::{AtomId, AtomSet};
use crate::syntax::ast::{TriggerKind, TriggerOp};

impl Semantics<'_> {
    /// Whether the order of predicate `p`'s beliefs is kept in [`State::order`].
    pub fn is_ordered(&self, p: crate::model::atoms::PredId) -> bool {
        self.ordered[p.0 as usize]
    }

    /// Whether atom `a` is the environment's (of a PDDL predicate), not a mental note.
    pub fn is_environment_atom(&self, a: AtomId) -> bool {
        self.env_atoms.contains(a)
    }

    /// How many of the environment's atoms hold in `beliefs`.
    pub fn env_count(&self, beliefs: &AtomSet) -> usize {
        let env = self.env_atoms.words();
        beliefs
            .words()
            .iter()
            .zip(env)
            .map(|(b, e)| (b & e).count_ones() as usize)
            .sum()
    }

    /// What of `env_count` an act phase depends on: the size of Jason's percept set
    /// decides the order of perceived effects (`Semantics::java_order`) only through its
    /// number of buckets, which is one value for every count an action can lead to, unless
    /// the count is near a resize (then the count itself).
    pub fn env_class(&self, env: usize) -> u64 {
        env_class(env, self.max_effect)
    }

    /// Sorts percepts as Jason's belief update meets them: `Agent.buf` puts the perceived
    /// literals (given in atom order) in a fresh `HashSet` and goes through it, so the
    /// order is the set's bucket order for a set of `size` elements
    /// (`java.util.HashMap`: 16 buckets, doubled past three quarters full; a bucket keeps
    /// insertion order). Removed percepts are taken in the same bucket order (Jason goes
    /// through its belief base's percept set, whose buckets may hold them in the order
    /// they were first perceived: where two share a bucket, atom order is used).
    pub(super) fn java_order(&self, atoms: &mut [AtomId], size: usize) {
        if atoms.len() < 2 {
            return;
        }
        let cap = java_capacity(size);
        let bucket = |a: &AtomId| {
            let h = self.jhash[a.0 as usize] as u32;
            (h ^ (h >> 16)) & (cap - 1)
        };
        atoms.sort_by_key(|a| (bucket(a), a.0));
    }

    /// Applies to a whole state's `order` what an act phase did to the order of the
    /// beliefs it read: `removed` and `added` leave their places, and `front` (the added
    /// ones whose order is kept, newest first) goes in front of their predicates' beliefs.
    pub(super) fn reorder_front(
        &self,
        order: &mut Vec<AtomId>,
        front: &[AtomId],
        removed: &AtomSet,
        added: &AtomSet,
    ) {
        order.retain(|a| !removed.contains(*a) && !added.contains(*a));
        // Inserting the oldest first in front of its group leaves the newest in front.
        for &a in front.iter().rev() {
            self.put_in_front(order, a);
        }
    }

    /// Puts `a` in front of its predicate's beliefs in `order`.
    fn put_in_front(&self, order: &mut Vec<AtomId>, a: AtomId) {
        let pred = |a: AtomId| self.project.atoms.pred_of(a);
        let p = pred(a);
        let at = order
            .iter()
            .position(|x| pred(*x) >= p)
            .unwrap_or(order.len());
        order.insert(at, a);
    }

    /// Records a belief just added to `s` where the order of its predicate's beliefs is
    /// kept (the newest in front), with no event.
    pub(super) fn note_added(&self, s: &mut State, a: AtomId) {
        self.reorder(s, &[a], &[]);
    }

    /// Keeps [`State::order`] for a belief added (in front of its predicate's beliefs)
    /// or removed.
    pub(super) fn reorder(&self, s: &mut State, added: &[AtomId], removed: &[AtomId]) {
        let pred = |a: AtomId| self.project.atoms.pred_of(a);
        for &a in removed.iter().chain(added) {
            if self.is_ordered(pred(a)) {
                s.order.retain(|x| *x != a);
            }
        }
        for &a in added {
            if self.is_ordered(pred(a)) {
                self.put_in_front(&mut s.order, a);
            }
        }
    }

    /// Records beliefs just added and removed, in the order Jason adds and removes them:
    /// [`State::order`] is updated, and `+p`/`-p` queued for those some plan is relevant
    /// for (deletions first, as `Agent.buf` does).
    pub(super) fn perceive(&self, s: &mut State, added: &[AtomId], removed: &[AtomId]) {
        self.perceive_with_focus(s, added, removed, None);
    }

    /// As [`Semantics::perceive`], for a plan's belief update: the event of `focus` (the
    /// last one) is not queued but returned, for the intention that waits in it; the
    /// waiting intentions are told of it with the others.
    pub(super) fn perceive_with_focus(
        &self,
        s: &mut State,
        added: &[AtomId],
        removed: &[AtomId],
        focus: Option<(TriggerOp, AtomId)>,
    ) -> Option<EventTrigger> {
        self.reorder(s, added, removed);
        let b = self.beliefs(s);
        let mut new_events = Vec::new();
        let mut told = Vec::new();
        let mut focused = None;
        let waits = s.waiting.iter().any(|w| !w.woken);
        for (atoms, op) in [(removed, TriggerOp::Del), (added, TriggerOp::Add)] {
            for a in atoms {
                let trigger = EventTrigger {
                    op,
                    kind: TriggerKind::Belief,
                    literal: b.atom_term(*a),
                };
                if waits {
                    // A `.wait` hears of every event, relevant or not.
                    told.push((trigger.clone(), *a));
                }
                if focus == Some((op, *a)) {
                    focused = Some(trigger);
                } else if !self.relevant_plans(&trigger).is_empty() {
                    new_events.push(Event {
                        trigger,
                        intention: None,
                        origin: Origin::Spawned,
                        posted_at: None,
                    });
                }
            }
        }
        s.events.extend(new_events);
        if waits {
            self.belief_events_added(s, &told);
        }
        focused
    }
}

/// [`Semantics::env_class`] for actions that change at most `max_effect` atoms: the bucket
/// count every reachable count shares, or, near a resize, the count itself (tagged, so that
/// no count is taken for a bucket count).
fn env_class(env: usize, max_effect: usize) -> u64 {
    let lo = java_capacity(env.saturating_sub(max_effect));
    let hi = java_capacity(env + max_effect);
    if lo == hi {
        u64::from(lo)
    } else {
        1 << 40 | env as u64
    }
}

/// The number of buckets of a `java.util.HashSet` after `size` insertions into a new one:
/// 16, doubled whenever it is more than three quarters full (`HashMap.resize`).
fn java_capacity(size: usize) -> u32 {
    let mut cap: u32 = 16;
    while size as u64 > u64::from(cap / 4 * 3) {
        cap *= 2;
    }
    cap
}

#[cfg(test)]
mod tests {
    use super::{env_class, java_capacity};

    #[test]
    fn a_java_hash_set_doubles_its_sixteen_buckets_past_three_quarters() {
        // java.util.HashMap: threshold = capacity * 0.75, resize when size exceeds it.
        let sizes = [(0, 16), (1, 16), (12, 16), (13, 32), (24, 32), (25, 64)];
        for (size, cap) in sizes.into_iter().chain([(48, 64), (49, 128), (97, 256)]) {
            assert_eq!(java_capacity(size), cap, "{size} elements");
        }
    }

    #[test]
    fn counts_of_one_class_see_the_same_bucket_counts_after_any_action() {
        // The compiled act phase is cached by the class: sound only if every count an
        // action can lead to from either of two counts of a class has the same buckets.
        for me in 0..=20 {
            let classes: Vec<u64> = (0..400).map(|env| env_class(env, me)).collect();
            for a in 0..400 {
                for b in a + 1..400 {
                    if classes[a] != classes[b] {
                        continue;
                    }
                    for d in 0..=me {
                        assert_eq!(java_capacity(a + d), java_capacity(b + d), "{a} {b} {me}");
                        let (x, y) = (a.saturating_sub(d), b.saturating_sub(d));
                        assert_eq!(java_capacity(x), java_capacity(y), "{a} {b} {me}");
                    }
                }
            }
        }
    }
}
