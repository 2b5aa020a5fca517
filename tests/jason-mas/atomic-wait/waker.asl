// A goal for the sleeper, a step it waits to see, then `go`.
!wake.
+!wake
   <- .send(sleeper, achieve, hello);
      step(s2);
      .print("waker stepped");
      .send(sleeper, tell, go);
      .print("waker done").
