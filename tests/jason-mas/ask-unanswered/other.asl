// Asks a question the oracle has a plan for another instance of, and waits for ever.
!start.
+!start <- mark(other); .send(oracle, askOne, p(two), A); .print("answer: ", A).
