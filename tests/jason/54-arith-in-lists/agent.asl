// Case 54 (point 14): arithmetic inside lists and nested terms is evaluated when the term
// is used (`L = [N + 1, N * 2]` holds [8, 14]), so .member, .nth and .length see numbers;
// a function result takes part in arithmetic. Decided by ListTermImpl.capply (each element
// applied), ArithExpr.capply and RelExpr (unify applies both sides first).

val(7).

+!go <- ?val(N);
        L = [N + 1, N * 2];
        .print(L);
        .nth(1, L, X); .print("x=", X);
        if (.member(8, L)) { act(a) } else { act(b) };
        .length([N - 7, N], K); .print("k=", K);
        M = [[N mod 3], N div 2]; .print(M);
        Y = math.max(N, 3) + 1; .print("y=", Y);
        if (X > 10) { act(c) } else { ping }.
