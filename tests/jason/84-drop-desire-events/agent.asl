// Case 84: .drop_desire(g) on the events queued when it runs (jason.stdlib.drop_desire:
// C.removeEvents of +!g, and events whose intention pursues g): one action's two percepts
// queue two belief events; a goal event and belief events of the same literal meet the
// drop while still queued.

+!go <- !!g(a); two(a, b); .drop_desire(p(_)); act(c).
+!keep <- !!g(b); two(a, b); .drop_desire(g(_)); act(c).
+!sub <- two(a, b); !h; act(c).
+!h <- .drop_desire(p(b)); act(b).

+p(X) <- act(X).
+!p(X) <- act(X).
+!g(X) <- act(X); act(X).
