// Case 20 (point 5): test goals answered by a belief (a +?home plan exists but the belief
// answers first), by a rule, by a percept, and by a +?spot plan when no belief answers (the
// plan's binding X = c flows back to ?spot(S)); ?marked(M) with nothing marked and no +? plan
// fails the request. Decided by TransitionSystem.applyExecInt (case test: logicalConsequence
// first, then a +? event if a relevant plan exists) and applyClrInt (the test goal's bindings).

home(b).
near(X) :- home(X).
spare(c).

+?spot(X) : spare(X) <- true.
+?home(X) <- X = a.

+!t1 <- ?home(H); act(H).
+!t2 <- ?near(N); act(N).
+!t3 <- ?marked(M); unmark(M).
+!t4 <- ?spot(S); act(S).
