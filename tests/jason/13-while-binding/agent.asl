// Case 13 (point 3): a `while` whose body binds a variable with a test goal (?cur(X)); the
// loop condition is a mental note and the body walks a chain of initial beliefs with -+.
// Every iteration starts from the unifier the loop had before it (X is free again), and the
// bindings made in the body are dropped when the loop ends. Decided by jason.stdlib.loop
// (the `while` internal action: backup unifier, one iteration inserted per check).

next(a, b).
next(b, c).
cur(a).

+!walk <- while (not finished) {
             ?cur(X);
             act(X);
             if (next(X, Y)) { -+cur(Y) } else { +finished }
          };
          ping.
