// a send to nobody, no failure plan: the intention is dropped
!start.
+!start <- .send(ghost, achieve, g); .print("not reached").
