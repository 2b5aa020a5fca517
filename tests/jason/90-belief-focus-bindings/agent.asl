// Case 90: more of a belief update's focus. delv: `-n(X)` binds X before the intention
// waits in the -n event, and keeps it after the event's plan. waits: the event's plan
// waits (.wait(10)) on top of the intention while another intention acts. again: `+r(a)`
// of a belief held changes nothing (no event, no wait); `-+r(b)` posts -r(a) on its own.
// Decided by TransitionSystem.applyExecInt (addBel, delBel, delAddBel) and Agent.brf.

n(a).
n(b).
+!delv <- -n(X); act(X); -n(Y); act(Y).
-n(X) <- act(c); act(X).

+!waits <- !!side; +w(a); act(c).
+w(X) <- .wait(10); act(X).
+!side <- act(b); act(b); act(b).

+!again <- +r(a); +r(a); act(c); -+r(b); act(c).
+r(X) <- act(X).
-r(X) <- act(c).
