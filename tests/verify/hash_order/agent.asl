// Jason perceives the effects of one action in the order of its percept set's buckets
// (Agent.buf), which depends on the objects' names: after markAll, the newest marked
// thing is not the same for every renaming of the things, so symmetry over them is not
// exact, and verify says so.
+!go(X) <- markAll; !pick(X).

+!pick(X) : marked(Y) & Y \== X <- act(Y).
+!pick(X) : not (marked(Y) & Y \== X) <- ping.
