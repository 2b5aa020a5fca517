// Case 49: two initial goals become two intentions that run round-robin; a request arrives
// when the agent is idle, after both. Decided by Agent.addInitialGoalsInTS (one event per
// initial goal, in source order) and the round-robin of the running intentions.

!init.
!init2.

+!init <- act(a); act(a).
+!init2 <- act(b).

+!go <- act(c).
