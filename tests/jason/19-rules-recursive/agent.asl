// Case 19 (point 4): a recursive rule over a small chain of initial beliefs (reach/2), used in
// a context, in a `for` (its answers in Jason's order: the first clause's before the
// second's) and in a test goal. Decided by Literal.logicalConsequence (rules are tried in
// belief base order, clause by clause, depth first).

link(a, b).
link(b, c).

reach(X, Y) :- link(X, Y).
reach(X, Z) :- link(X, Y) & reach(Y, Z).

+!go(X) : reach(a, X) <- act(X).
+!go(X) <- mark(X).

+!list <- for (reach(a, Y)) { act(Y) }; ?reach(b, W); act(W).
