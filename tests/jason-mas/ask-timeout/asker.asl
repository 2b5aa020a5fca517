// Asks three agents, each with a timeout of 100 ms, and prints what it got.
!start.
+!start
   <- mark(asked);
      .send(quick, askOne, q(X), C, 100);
      .print("quick: ", C);
      .send(slow, askOne, q(Y), A, 100);
      .print("slow: ", A);
      .send(mute, askOne, q(high), B, 100);
      .print("mute: ", B);
      mark(done).
