// A new user's robot (issue 14's trial): rules, a counter, `<- true`, `.fail`, a
// `[source(A)]` plan and `.wait`; it verifies with no false error.
count(0).
clean(R) :- not dirty(R).
+!tidy(R)[source(A)] : dirty(R) <- goTo(R); wipe(R); ?count(N); -+count(N + 1); !report(A).
+!tidy(R) : clean(R) <- true.
+!report(A) : count(N) & N > 2 <- .print("tired"); .fail.
+!report(A) <- .wait(10); .print("done for ", A).
-!report(A) <- .print("giving up").
