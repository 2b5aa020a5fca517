// Case 91: .drop_desire(p(_)) among the percepts of p and the intentions reacting to them:
// belief events and belief plans are not the goal p, so they stay and run
// (jason.stdlib.drop_desire drops the events +!p(_) and the intentions pursuing p(_)).

+!go <- !!b; act(c); .drop_desire(p(_)); act(c).
+!b <- two(a, b); act(b).
+p(X) <- act(X).
+!p(X) <- act(X).
