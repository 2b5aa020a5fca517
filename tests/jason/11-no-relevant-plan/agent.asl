// Case 11 (points 2, 12): a subgoal no plan is relevant for (!nowhere). The goal fails with
// error(no_relevant); -!go[error(E)] handles it and prints E, +!go2 has no failure plan and
// its intention is dropped. Decided by TransitionSystem.applyRelApplPlRule2("relevant") ->
// generateGoalDeletionFromEvent (annotations from JasonException.createBasicErrorAnnots).

+!go <- act(a); !nowhere; act(b).

-!go[error(E)] <- .print("go failed: ", E); act(c).

+!go2 <- act(a); !nowhere; act(b).
