// Case 73: tail recursion deeper than bdi-check's stack bound (64 plans) runs as in Jason:
// the recursive subgoal that is the last step of its plan replaces its frame (TRO), so
// !count(70) never holds more than two plans. Goals of other names are not replaced:
// !a and !b call each other, and when !a(0) fails, the -!b plan of the nearest b frame
// handles it and the stack unwinds through the frames TRO kept. Decided by
// TransitionSystem.applySelAppl / IntendedMeans (TRO, Settings.isTROon: the same functor
// and arity) and Intention.findEventForFailure.

start(70).

+!go <- ?start(N); !count(N); act(b).
+!count(N) : N > 0 <- !count(N - 1).
+!count(0) <- act(a).

+!go2 <- !a(2); act(c).
+!a(N) : N > 0 <- !b(N).
+!b(N) <- !a(N - 1).
+!a(0) <- use(c).
-!b(N) <- .print("b failed ", N).
