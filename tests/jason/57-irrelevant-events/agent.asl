// Case 57: events no plan is relevant for take no turn of their own. Two noise
// intentions add mental notes (`-+n(X)` posts -n and +n) faster than one event per cycle
// is taken; Jason queues those events (TransitionSystem.updateEvents) but its
// deliberation discards each one without a relevant plan and selects the next event in
// the same cycle (applyRelApplPlRule2 -> SelEv), so the +marked(a) percept event behind
// them is handled at once: the reaction's act(a) comes right after mark(a).

+!go <- !!noise(a); !!noise(b); act(c); act(c); mark(a); act(c); act(c); act(c); act(c).

+!noise(X) <- -+n(X); -+n(X); -+n(X); -+n(X).

+marked(X) <- act(X); act(X).
