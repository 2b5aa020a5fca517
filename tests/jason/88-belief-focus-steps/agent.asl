// Case 88: an intention waiting in its belief update's event, or running the event's plan
// on top of its own (Jason's default sameFocus), meets the other constructs: .succeed_goal
// of its goal drops the note's plan with it; `for` and `if` go on after each note's plan;
// .drop_intention drops it; a failure in the note's plan is handled by the goal's -!.
// Decided by TransitionSystem.applyExecInt (addBel), succeed_goal/drop_intention
// (Circumstance events and intentions) and findEventForFailure.

+!sg <- !!w; +n(a); act(c); act(c).
+!w <- act(b); .succeed_goal(sg); act(b).
+n(X) <- act(X); act(X); act(X).

+!loop <- for (.member(X, [a, b])) { +m(X) }; act(c).
+m(X) <- act(X).

+!branch <- if (true) { act(a); +k(b) }; act(c).
+k(X) <- act(X); act(X).

+!dropi <- !!d; +n(b); act(c).
+!d <- act(a); .drop_intention(dropi); act(a).

+!fails2 <- +q(a); act(c).
+q(X) <- bad(X).
-!fails2 <- act(b).
