// Case 87: an external event with relevant plans but none applicable is discarded and the
// next event is handled in the same cycle (TransitionSystem.applyRelApplPlRule2: an
// external, irrelevant or inapplicable event goes back to SelEv), so the reaction to the
// second percept of `two` comes one cycle earlier than if each event took a cycle.

+!go <- two(a, b); act(c); act(c); act(c); act(c).
+!other <- two(b, c); act(c); act(c); act(c); act(c).
+p(a) : false <- act(a).
+p(b) : false <- act(a).
+p(c) <- act(b).
+p(b) <- act(b).
