// Case 32 (point 8): .fail_goal(mid) with no -!mid plan and no failure plan below: the whole
// intention is dropped (bottom goal top). With +!top2, .fail_goal(mid2) of the running goal
// itself finds -!top2 below and that handles it. Decided by jason.stdlib.fail_goal
// (findEventForFailure finds no relevant plan -> Intention.fail) and
// Intention.findEventForFailure.

+!top <- !mid; act(c).
+!mid <- !low; act(b).
+!low <- act(a); .fail_goal(mid); act(a).

+!top2 <- !mid2; act(c).
+!mid2 <- act(a); .fail_goal(mid2); act(b).
-!top2 <- ping.
