// Internal actions bdi-check does not model, next to ones it does.
+!go <- .print("going"); .send(bob, tell, going); navigateTo(table).
+!rest : .count(cupAt(_, table), N) & N > 0 <- .wait(100); X = math.abs(N); .drop_desire(go).
