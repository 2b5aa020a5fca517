// A long job of four steps, and a plan for a goal nobody asks it to pursue.
+!clean[source(A)]
   <- step(s1);
      .print("cleaning for ", A);
      step(s2);
      step(s3);
      step(s4);
      .print("clean done").

+!rest <- step(s9); .print("resting").
