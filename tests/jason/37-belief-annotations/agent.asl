// Case 37 (point 9): annotations of beliefs in contexts and triggers: a percept is
// marked(a)[source(percept)], a mental note is flag(a)[source(self)]; `marked(X)[source(self)]`
// matches no percept. +marked(X)[source(percept)] reacts to the percept mark(b) adds.
// Decided by Agent.buf (percepts get source(percept)), TransitionSystem.prepareBodyForEvent
// (+flag gets source(self)) and Literal.logicalConsequence (annotations of the query must be
// a subset of the belief's).

+!go : marked(X)[source(percept)] <- act(X); +flag(X); !check(X).
+!go <- ping.

+!check(X) : flag(X)[source(self)] <- mark(b).
+!check(X) <- ping.

+!self_marked : marked(X)[source(self)] <- act(X).
+!self_marked <- ping.

+marked(X)[source(percept)] <- act(c).
