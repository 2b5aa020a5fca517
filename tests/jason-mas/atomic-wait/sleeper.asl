// An ordinary intention, and an atomic one that waits.
!chat.
!nap.

+!chat <- .print("chat 1"); .print("chat 2"); .print("chat 3"); .print("chat 4").

@nap[atomic]
+!nap
   <- .print("nap 1");
      .wait(done(s2));
      .print("nap 2");
      .wait({+go});
      .print("nap 3");
      step(s1);
      .wait(20);
      .print("nap 4").

+go[source(A)] <- .print("go from ", A).
+!hello[source(A)] <- .print("hello from ", A).
