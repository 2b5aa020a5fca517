// Tells the learner how to greet, has it greet, then takes the greeting back.
!start.
+!start
   <- .send(learner, tellHow, "@greet1 +!hello(W)[source(A)] <- .print(\"hello \", W, \" from \", A); mark(W, A).");
      .send(learner, achieve, hello(t1));
      .send(learner, tellHow, {@bye2 +!bye(W) <- .print("told bye to ", W)});
      .send(learner, achieve, bye(t2));
      .send(learner, untellHow, greet1);
      .send(learner, achieve, hello(t2)).

@tip1 +!tip(W) : W == t1 <- .print("tip one for ", W); mark(W, asker).
@tip2 +!tip(W) <- .print("tip for ", W); mark(W, asker).
