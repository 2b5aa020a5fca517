// Case 23: tail recursion over a chain of beliefs (+!walk(X) : next(X,Y) <- act(X); !walk(Y).),
// and a recursive walk whose last step fails (use(c) without ready(c)) with a failure plan.
// Jason's tail-recursion optimisation replaces the frame of the recursive goal. Decided by
// TransitionSystem.applySelAppl / IntendedMeans (TRO, Settings.isTROon) and
// Intention.findEventForFailure.

next(a, b).
next(b, c).

+!walk(X) : next(X, Y) <- act(X); !walk(Y).
+!walk(X) <- act(X); ping.

+!walk2(X) : next(X, Y) <- act(X); !walk2(Y).
+!walk2(X) <- use(X).
-!walk2(X) <- mark(X).
