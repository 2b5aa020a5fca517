// Case 30 (point 7): several percepts of one predicate; which comes first (context, test goal,
// .findall) is decided by the order in which perception added them, and a percept added later
// by an action (mark(b)) comes before the older ones. Decided by Agent.buf (percepts added
// with BeliefBase.add, newest first) and DefaultBeliefBase.getCandidateBeliefs.

+!go : marked(X) <- act(X); .findall(Y, marked(Y), L); .print(L).
+!go <- ping.

+!late <- mark(b); act(c); ?marked(Z); act(Z).
