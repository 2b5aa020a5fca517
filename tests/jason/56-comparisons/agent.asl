// Case 56 (point 14): every relational operator on numbers and on other terms, each result
// printed: <= and >= at equality, < and > between 9 and 10 (numbers by value), between
// atoms and strings (Jason's term order), == and \== on structures. Decided by RelExpr
// (compareTo of NumberTermImpl, Atom and StringTermImpl).

lim(9).

+!go <- ?lim(N);
        if (N <= 9) { .print("le9") } else { .print("not le9") };
        if (N <= 8) { .print("le8") } else { .print("not le8") };
        if (N >= 9) { .print("ge9") } else { .print("not ge9") };
        if (N >= 10) { .print("ge10") } else { .print("not ge10") };
        if (N < 10) { .print("lt10") } else { .print("not lt10") };
        if (10 > N) { act(a) } else { act(b) };
        if (N + 0.5 > 9) { .print("gt") } else { .print("not gt") };
        if (a < b) { .print("a<b") } else { .print("not a<b") };
        if ("abc" < "abd") { .print("s<") } else { .print("not s<") };
        if (f(1) == f(1)) { .print("eq") } else { .print("not eq") };
        if (f(1) \== f(2)) { act(c) } else { ping };
        if (N \== 9) { ping } else { act(a) }.
