// Asks a question no plan of the oracle's applies to, and waits for ever.
!start.
+!start <- mark(asker); .send(oracle, askOne, q(one), A); .print("answer: ", A).
