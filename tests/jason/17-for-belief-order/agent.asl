// Case 17 (points 3, 7): `for` over mental notes: initial beliefs keep their source order
// (item(b) before item(a)), beliefs added by +extra(...) come newest first (b, a, c), and a
// conjunction iterates the first literal's answers in that order. Decided by
// Agent.addInitialBelsInBB (adds the initial beliefs in reverse) and DefaultBeliefBase.add
// (a new belief goes first), jason.stdlib.foreach and jason.stdlib.findall.

item(b).
item(a).

+!go <- +extra(c); +extra(a); +extra(b);
        for (item(X)) { act(X) };
        for (extra(Y)) { act(Y) };
        for (item(Z) & extra(Z)) { mark(Z) };
        .findall(W, extra(W), L); .print(L).
