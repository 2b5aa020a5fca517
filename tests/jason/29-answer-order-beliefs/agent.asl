// Case 29 (point 7): several beliefs of one predicate, added in an order different from the
// atoms' order: the first answer of a test goal, a context and .findall follows Jason's
// belief base order (initial beliefs in source order: at(b) first; added beliefs newest
// first: spot(b), spot(a), spot(c)). Decided by Agent.addInitialBelsInBB and
// DefaultBeliefBase.add (addFirst) / getCandidateBeliefs.

at(b).
at(a).

+!go <- ?at(X); act(X);
        !pick;
        +spot(c); +spot(a); +spot(b);
        ?spot(Y); act(Y);
        .findall(Z, spot(Z), L); .print(L);
        !pick2.

+!pick : at(P) <- act(P).

+!pick2 : spot(S) & S \== b <- act(S).
