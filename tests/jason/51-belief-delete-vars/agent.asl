// Case 51: -b with a variable deletes only the first belief that unifies (belief base order),
// -+b deletes the first belief of the predicate and adds the new one (one, not all of them),
// and -b of a bound variable. The beliefs left are printed and iterated. Decided by
// Agent.brf (delete: the first candidate belief that unifies) and TransitionSystem.applyExecInt
// (case delAddBel: makeTermsAnnon, brf delete, then add).

seen(a).
seen(b).
seen(c).
pos(a).
pos(b).

+!go <- -seen(_);
        .findall(X, seen(X), L1); .print(L1);
        -+pos(c);
        .findall(P, pos(P), L2); .print(L2);
        ?seen(Y); -seen(Y);
        .findall(Z, seen(Z), L3); .print(L3);
        for (pos(Q)) { act(Q) }.
