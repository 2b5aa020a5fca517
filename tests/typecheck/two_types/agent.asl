// A variable used as a cup and as a location, directly and through a subgoal.
+!storeCup(C) : used(C)
   <- navigateTo(C).

+!fetch(X) <- pickUp(X).
+!go(L) : robotAt(L) <- !fetch(L).
