// Case 21 (point 12): a test goal on a predicate nothing defines (no belief, no rule, no +?
// plan): the test goal fails, the plan fails; +!go's intention is dropped, +!go2's failure
// plan runs. Decided by TransitionSystem.applyExecInt (case test -> generateGoalDeletion with
// test_goal_failed).

+!go <- act(a); ?nowhere(P); act(P).

+!go2 <- act(a); ?nowhere(P); act(P).
-!go2 <- act(b).
