// Case 02 (point 1): plans without a body (`+!check(X) : marked(X).`) and percept reactions
// with an empty body (`<- true`): the goal is achieved without acting, the percept events are
// handled and nothing else happens. Decided by as2j.plan (the body is optional) and
// TransitionSystem.applyClrInt; the percept events come from Agent.buf.

+!check(X) : marked(X).
+!check(X) : not marked(X) <- mark(X).

+!flip(X) <- !check(X); unmark(X); !check(X); act(X).

+marked(X) : true <- true.
-marked(X) <- true.
