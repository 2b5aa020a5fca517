// Tells the same plan, as a plan term; once the first has taken it back, uses it, then
// takes it back too and asks again.
!start.
+!start
   <- .send(learner, tellHow, {@m1 +!mark_it(T) <- mark(T); .print("marked ", T)});
      .send(learner, achieve, mark_it(t1)).
+!go
   <- .send(learner, achieve, mark_it(t2));
      .wait(marked(t2));
      .send(learner, untellHow, "@m1");
      .send(learner, achieve, mark_it(t3)).
