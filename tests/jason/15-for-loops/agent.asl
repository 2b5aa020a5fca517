// Case 15 (point 3): `for` over .member of a list, over .range, and over percepts; one
// iteration per answer, in the order the answers come (the list's order, 1..3, and the
// belief base order of the percepts). Decided by jason.stdlib.foreach, jason.stdlib.member,
// jason.stdlib.range.

+!go <- for (.member(X, [c, a, b])) { act(X) };
        for (.range(I, 1, 3)) { .print("i=", I) };
        for (marked(Y)) { act(Y) };
        ping.
