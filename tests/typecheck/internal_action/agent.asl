// Internal actions bdi-check does not model, next to ones it does.
+!go <- .print("going"); .df_register(going); navigateTo(table).
+!rest : .count(cupAt(_, table), N) & N > 0 <- .wait(100); .all_names(L); X = math.abs(N); .drop_desire(go).
