// A countdown over `[bounds] numbers`: `+!start(0)` is reached through `!start(X - 1)`, so
// it is not dead.
!start(3).
+!start(0) <- .print("done").
+!start(X) : X > 0 <- .print(X); !start(X - 1).
