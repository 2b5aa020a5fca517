// Case 53: .count in plan contexts, with a comparison on the count and with a fixed count,
// and in a `while` condition whose body changes the counted percepts. Decided by
// jason.stdlib.count (counts the answers of the query in the belief base at that moment).

+!go : .count(marked(_), N) & N >= 2 <- act(a).
+!go : .count(marked(_), 1) <- act(b).
+!go <- act(c).

+!fill <- while (.count(marked(_), N) & N < 2) { markAll; ping }; act(a).
