// Case 75: a subgoal posted with annotations of its own still gets source(self), so a
// plan for +!g[source(self)] applies to !g[urgent]; a subgoal that names its source keeps
// it (!h[source(boss)] is not source(self)). Plans' annotations must be a subset of the
// event's. Decided by TransitionSystem.prepareBodyForEvent (addAnnot source(self) unless
// hasSource) and Trigger/Literal.subsumes in relevance.

+!go <- !g[urgent]; !h[source(boss)]; !k[urgent].
+!g[source(self)] <- act(a).
+!g <- act(b).
+!h[source(self)] <- act(a).
+!h[source(boss)] <- act(c).
+!k[urgent, source(self)] <- mark(a).
+!k <- mark(b).
