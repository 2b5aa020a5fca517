// Case 18 (point 4): rules `head :- body.` in plan contexts, a rule calling another rule, and
// a rule over a closed-world negation of a percept. Decided by Rule /
// Literal.logicalConsequence (a rule's body is proved with the belief base at that moment).

clean(X) :- not marked(X).
both_clean :- clean(a) & clean(b).

+!check(X) : clean(X) <- act(X).
+!check(X) : not clean(X) <- unmark(X).

+!all : both_clean <- ping.
+!all <- mark(c).
