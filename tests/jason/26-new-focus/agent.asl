// Case 26 (point 6): `!!side(X)` starts a new intention; the posting plan goes on at once, and
// the two intentions interleave round-robin. `!side(b)` after `!!side(c)` is an ordinary
// subgoal of +!both. Decided by TransitionSystem.applyExecInt (case achieveNF: an event
// without intention) and the round-robin of C.getRunningIntentions.

+!go <- !!side(b); act(a); act(a); act(a).

+!side(X) <- act(X); act(X).

+!both <- !!side(c); !side(b); act(a).
