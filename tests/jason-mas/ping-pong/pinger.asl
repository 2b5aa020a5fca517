!start.
+!start <- .send(ponger, achieve, ping).
