!start.
+!start <- .send(keeper, tell, ready(t1)); .send(keeper, tell, ready(t1)); .send(keeper, tell, ready(t2)); .send(keeper, achieve, check).
