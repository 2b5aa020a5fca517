// Case 42 (point 11): strings and terms: .concat of strings, .length of a string, .substring
// (with a position), .string, .number, .atom, .structure, .ground, .term2string both ways, and
// .print/.println of strings, numbers, atoms, lists and a term whose variable was bound
// later. Decided by jason.stdlib.{concat,length,substring,string,number,atom,structure,
// ground,term2string,print,println} (println.argsToString: strings without quotes).

+!go <- .concat("ab", "cd", S); .print(S);
        .length(S, N); .print(N);
        .substring("bc", S);
        .substring("c", S, P); .print("pos ", P);
        .string(S); .number(N); .atom(a); .structure(f(a)); .ground(f(a, b));
        T = f(a, V); V = b; .print(T);
        .term2string(g(a, b), Str); .print(Str);
        .term2string(Term, "h(c)"); .print(Term);
        .print("text", 42, a, [1, "x", b], g(c));
        .println("done ", N);
        if (.atom(S)) { ping } else { act(a) };
        if (.ground(g(W))) { ping } else { act(b) }.
