// A coin the robot flips: below 0.5 it uses the thing at once, which only works once it
// is ready. `.random` gives each value of `[bounds] random` in some run, so the run with
// 0.1 is found; `.random([a, b], X)` gives each element, and `use(b)` fails when b is
// picked.

+!go <- .random(R); !flip(R).

+!flip(R) : R < 0.5 <- use(a).
+!flip(R) <- prepare(a); use(a).

+!pick <- prepare(a); .random([a, b], X); use(X).
