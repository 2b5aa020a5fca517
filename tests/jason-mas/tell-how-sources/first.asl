// Tells the plan, has it used, takes it back, has it used again.
!start.
+!start
   <- .send(learner, tellHow, "@m1 +!mark_it(T) <- mark(T); .print(\"marked \", T).");
      .wait(marked(t1));
      .send(learner, untellHow, m1);
      .send(second, achieve, go).
