ready(t2).
+ready(T)[source(A)] : A \== self <- mark(T, A).
+!check : ready(t1)[source(teller1)] & ready(t1)[source(teller2)] <- .print("both told t1").
+!check <- .print("not both").
