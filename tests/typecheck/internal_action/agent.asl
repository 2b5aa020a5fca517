// Internal actions bdi-check does not model (messages), next to ones it does.
+!go <- .print("going"); .send(bob, tell, going); navigateTo(table).
+!rest : .count(cupAt(_, table), N) & N > 0 <- .wait(100); .broadcast(tell, resting); X = math.abs(N); .drop_desire(go).
