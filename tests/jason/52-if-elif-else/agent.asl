// Case 52: if / elif / else with `&`, `|` and `not` over percepts, and a context with `|`,
// `&` and `not`. Decided by jason.stdlib.if_then_else (the first branch whose condition has
// an answer) and LogExpr (and, or, not).

+!classify(X) <-
    if (marked(X) & ready(X)) { act(a) }
    elif (marked(X) | ready(X)) { act(b) }
    elif (not marked(c)) { act(c) }
    else { ping }.

+!pick : (marked(a) | marked(b)) & not ready(c) <- act(a).
+!pick : ready(c) & not (marked(a) & marked(b)) <- act(b).
+!pick <- ping.
