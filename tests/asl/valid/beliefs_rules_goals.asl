// Covers: initial beliefs, rules (`head :- body.`), initial goals (`!g.`),
// strong negation `~`, annotations (`p(a)[source(percept), x(1)]`),
// namespaces `ns::p` and `V::p` (`::p` is in directives_namespace.asl),
// and the constants `true` / `false` in rule bodies.

// Initial beliefs: what the kitchen robot knows when it starts.
cup(c1).
cup(c2).
cup(c3).
at(c1, table)[source(percept), x(1)].
at(c2, table)[source(percept)].
at(c3, cupboard)[source(self), confidence(0.9)].
holding(none).
dishwasherDoor(closed).

// Strong negation: c3 is known NOT to be dirty; the cupboard is not full.
~dirty(c3).
~full(cupboard)[source(percept)].

// Beliefs qualified by a namespace.
kitchen::location(table).
kitchen::location(dishwasher).
kitchen::location(cupboard).
stock::count(cups, 3).

// Rules.
used(C) :- cup(C) & at(C, table) & not ~dirty(C).
clean(C) :- ~dirty(C).
reachable(L) :- kitchen::location(L).
// `V::p`: a namespace given by a variable.
known(NS, C) :- NS::cup(C).
alwaysReady :- true.
neverBroken(C) :- cup(C) & not false.
~needsWash(C) :- clean(C).

// Initial goals.
!tidyKitchen.
!storeCup(c1)[priority(high)].
!kitchen::inspect(table).
