// Asks the teacher how to give tips, then gives one.
!start.
+!start
   <- .send(teacher, askHow, {+!tip(_)});
      .wait(50);
      !tip(t1);
      !tip(t2).
-!tip(W) <- .print("no tip for ", W).
