// Case 85: `-+q(X)` when q(X) already holds, and when another q holds. Jason's delAddBel
// (TransitionSystem.applyExecInt) removes the old belief with its event, then falls
// through to addBel, which adds the new one with its event: both events, even when the
// belief is the same.

+!go <- +q(a); act(c); -+q(a); act(c).
+!other <- +q(a); act(c); -+q(b); act(c).

+q(X) <- act(X).
-q(X) <- act(b).
