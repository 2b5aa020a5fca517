// Case 43 (point 11): .abolish of one belief and of a pattern, .count and .findall over mental
// notes, and .count in contexts over percepts (.count(marked(_), M) & M > 1). Decided by
// jason.stdlib.abolish (Agent.abolish), jason.stdlib.count and jason.stdlib.findall.

seen(a).
seen(b).
seen(c).

+!go : .count(seen(_), 3) <- .abolish(seen(b)); .count(seen(_), N); .print("left ", N); !again.
+!go <- ping.

+!again : .count(seen(_), N) & N >= 2 <- .findall(X, seen(X), L); .print(L); .abolish(seen(_)); !again.
+!again <- .count(seen(_), N); .print("none ", N); act(a).

+!percepts : .count(marked(_), M) & M > 1 <- act(b).
+!percepts <- act(c).
