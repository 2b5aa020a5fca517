// Case 34 (point 8): .drop_desire(bg(_)) ends another intention (no failure event), and the
// plan that called it goes on; .drop_intention(quit) drops the caller's own intention (act(b)
// never runs); .drop_intention(bg(c)) drops a freshly spawned intention. Decided by
// jason.stdlib.drop_desire / drop_intention (Circumstance: running, pending and
// feedback intentions, and events for .drop_desire).

+!go <- !!bg(b); act(a); act(a); .drop_desire(bg(_)); act(c).
+!bg(X) <- act(X); act(X); act(X); act(X).

+!quit <- act(a); .drop_intention(quit); act(b).

+!other <- !!bg(c); act(a); .drop_intention(bg(c)); act(a).
