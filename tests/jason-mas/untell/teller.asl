// Tells two beliefs, then takes them back.
!start.
+!start
   <- .send(keeper, tell, ready(t1));
      .send(keeper, tell, ready(t2));
      .send(keeper, untell, ready(t1));
      .send(keeper, untell, ready(t2));
      .send(keeper, achieve, check).
