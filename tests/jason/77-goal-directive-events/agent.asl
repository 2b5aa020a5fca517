// Case 77: .fail_goal and .succeed_goal on goals whose events are still in the queue, and
// on a goal at the bottom of an intention. markAll makes six percepts, each with a plan, so
// the events of !!a and of a's subgoal !g wait behind them; go<N> waits N pings before it
// fails g. .fail_goal(g) turns a queued +!g into -!g in its place (dropInEvent) and fails
// a g the intention of a already runs; .succeed_goal(k) removes a queued +!k. When g is at
// the bottom of an intention (!!h), Jason 3 throws a NullPointerException inside
// .fail_goal: dropGoal empties the intention and findEventForFailure peeks at it
// (TransitionSystem.findEventForFailure, getPLForIM). bdi-check refuses that run. Decided
// by stdlib fail_goal/succeed_goal (drop, dropIntention, dropInEvent) and
// TransitionSystem.applySelEv (one event per cycle).

+!go0 <- markAll; !!a; .fail_goal(g); .succeed_goal(k); act(f).
+!go1 <- markAll; !!a; ping; .fail_goal(g); .succeed_goal(k); act(f).
+!go2 <- markAll; !!a; ping; ping; .fail_goal(g); .succeed_goal(k); act(f).
+!go3 <- markAll; !!a; ping; ping; ping; .fail_goal(g); .succeed_goal(k); act(f).
+!bottom <- !!h; ping; .fail_goal(h); act(f).

+marked(X) <- act(X).
+!a <- !g; !k; act(e).
+!g <- mark(a).
-!g <- .print("g failed").
+!k <- mark(b).
-!a <- .print("a failed").
+!h <- mark(c); ping; ping; ping.
-!h <- .print("h failed").
