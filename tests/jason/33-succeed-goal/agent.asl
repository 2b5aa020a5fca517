// Case 33 (point 8): .succeed_goal(mid) from a deeper plan: mid and the frames above it end
// as if achieved and +!top goes on with act(c). .succeed_goal(bg) from another intention ends
// the spawned intention bg wherever it is (running or waiting for an action's feedback).
// Decided by jason.stdlib.succeed_goal (drop / dropIntention over C's intentions, pending
// actions and events).

+!top <- !mid; act(c).
+!mid <- !low; act(b).
+!low <- act(a); .succeed_goal(mid); act(a).

+!go <- !!bg; act(a); act(a); .succeed_goal(bg); act(c).
+!bg <- act(b); act(b); act(b); act(b); act(b).
