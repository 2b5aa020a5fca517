// Case 60 (point 11): `.wait(N)` suspends its intention; the other intention runs all its
// steps meanwhile, and the wait ends when nothing else is left (the waits here are far
// longer than the cycles, and the agent sleeps until its timer fires). Decided by stdlib
// wait.execute / WaitEvent.resume and TransitionSystem.runAtBeginOfNextCycle.

+!go <- !!other; .wait(30); act(c); .wait(20); act(c).

+!other <- act(a); act(a); act(b).
