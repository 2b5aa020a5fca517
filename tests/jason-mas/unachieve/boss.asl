// Asks for a long job, then calls it off; also calls off a job never asked for.
!start.
+!start
   <- .send(worker, achieve, clean);
      .send(worker, unachieve, clean);
      .send(worker, unachieve, rest).
