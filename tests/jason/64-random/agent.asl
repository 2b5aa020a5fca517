// Case 64 (point 11): `.random`. Jason's values are random, so this case only records
// what holds for every value: `.random(R)` gives a number in [0, 1), `.random(L, X)` an
// element of L (here one), an empty list has no answer and fails the plan, and the
// second argument of `.random(X, N)` (how many answers to backtrack over) changes nothing
// in a body. Decided by stdlib random.execute. Which value comes is a choice of the
// model's (`[bounds] random`), checked by `tests/verify/random`.

+!go <- .random(R); R >= 0; R < 1; .random([b], X); act(X);
        .random(S, 5); S < 1; act(c); .random([], Y); act(a).

-!go <- act(c); act(c).
