// Case 45 (point 11): .my_name (printed: the name the agent runs under) and .fail in a
// subgoal with a failure plan and in a request's own plan without one (the intention is
// dropped after act(b); act(c) never runs). Decided by jason.stdlib.my_name
// (AgArch.getAgName) and jason.stdlib.fail (returns false -> generateGoalDeletion ia_failed).

+!go <- .my_name(Me); .print("I am ", Me); !check; ping.
+!check <- .fail.
-!check <- act(a).

+!direct <- act(b); .fail; act(c).
