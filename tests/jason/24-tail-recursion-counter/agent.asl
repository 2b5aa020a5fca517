// Case 24 (point 10): tail recursion on a number (+!count(N) : N > 0 <- act(a);
// !count(N - 1).), started by an initial goal !count(3) and by a request; N - 1 is evaluated
// when the subgoal is posted and +!count(0) matches the number 0. Decided by ArithExpr.capply
// (ground expressions are evaluated) and Agent.addInitialGoalsInTS for !count(3).

!count(3).

+!count(N) : N > 0 <- act(a); !count(N - 1).
+!count(0) <- ping.

+!go <- !count(2); act(b).
