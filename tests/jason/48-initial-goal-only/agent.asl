// Case 48: an initial goal (!start.) and an initial belief, with no requests: the agent works
// from its own goal and then stays idle. Decided by Agent.addInitialGoalsInTS (the initial
// goal is an external event with source(self)) and Agent.addInitialBelsInBB.

ready_to_go.

!start.

+!start : ready_to_go <- act(a); !next.
+!start <- ping.

+!next <- mark(b); act(c).
