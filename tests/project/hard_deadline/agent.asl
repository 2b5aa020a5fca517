// A goal with a hard deadline fails when it is not achieved in time (JasonER's
// checkHardDeadline, a timer): bdi-check does not model that yet, so it refuses the goal
// where it is posted rather than run it without its deadline.
+!t <- !u[hard_deadline(100)].
+!v <- !!u[hard_deadline(50)].
+!u <- use(a).
