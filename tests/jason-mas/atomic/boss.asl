// Three goals for the worker, one message per cycle.
!start.
+!start
   <- .send(worker, achieve, hello);
      .send(worker, achieve, outer);
      .send(worker, achieve, hello).
