// Case 38 (point 10): a numeric counter in a belief: count(0), -+count(N + 1), comparisons
// N < 3, N >= 3 and N \== 0 in contexts decide which plan (and so which action) runs; the
// final count is printed. Decided by TransitionSystem.applyExecInt (case delAddBel: remove
// count(_), add count(N+1)), RelExpr and ArithExpr.

count(0).

+!tick : count(N) & N < 3 <- -+count(N + 1); act(a).
+!tick : count(N) & N >= 3 <- act(b).

+!run <- !tick; !tick; !tick; !tick; ?count(C); .print("count=", C).

+!down : count(N) & N \== 0 <- -+count(N - 1); act(c); !down.
+!down <- ping.
