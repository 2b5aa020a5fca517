// Case 83: Jason's tail-recursion optimisation counts test goals as goals: when the last
// step of a `+!g` or `+?g` plan posts `!g` or `?g` (same functor and arity, both additions),
// the new plan replaces the finished one's frame. So `?find(X)`, last in `+!find(X)` and
// handled by `+?find(X)`, binds X in `+!go`; and a failure inside the replacing plan is
// handled below the replaced one (here by `-!go2`, not `-!f2`; by `-!go3`, not `-?h`).
// Decided by TransitionSystem.applyAddIM (its TRO block: `isGoal()`
// on both triggers, Trigger.isGoal = achieve or test) and Intention.findEventForFailure.

+!go <- !find(X); act(X).
+!find(X) <- ping; ?find(X).
+?find(a) <- ping.

+!go2 <- !f2(b); act(a).
+!f2(X) <- ping; ?f2(X).
+?f2(X) <- .fail.
-!f2(X) <- act(b).
-!go2 <- act(c).

+!go3 <- ?h; act(a).
+?h <- ping; !h.
+!h <- .fail.
-?h <- act(b).
-!go3 <- act(c).

// Not the same arity: no TRO, so `-!f4` handles the failure and `+!go4` goes on.
+!go4 <- !f4; act(a).
+!f4 <- ping; ?f4(b).
+?f4(X) <- .fail.
-!f4 <- act(b).
-!go4 <- act(c).
