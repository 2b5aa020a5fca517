// Untells what it never told.
!start.
+!start
   <- .send(keeper, untell, ready(t1));
      .send(keeper, untell, ready(t2));
      .send(keeper, achieve, check).
