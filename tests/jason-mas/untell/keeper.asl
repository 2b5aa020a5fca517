// Keeps what others tell it; ready(t2) is also its own belief.
ready(t2).

+ready(T)[source(A)] : A \== self <- .print("told ", T, " by ", A).
-ready(T)[source(A)] <- .print("untold ", T, " by ", A); mark(T, A).

+!check[source(A)] : ready(t2)[source(self)] & not ready(t2)[source(teller)] & not ready(t1)
   <- .print(A, " checks: t1 gone, t2 mine only").
+!check[source(A)] <- .print(A, " checks: not yet").
