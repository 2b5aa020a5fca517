// Case 06 (point 2): as case 05 with a goal below: after -!r(d1) handles the failure of the
// failure plan -!g(d1), +!top goes on with knock(d2). With +!top2, the failing -!g2 is skipped
// together with g2's frame and -!top2 handles it; knock(d2) of +!top2 never runs. Decided by
// Intention.findEventForFailure and TransitionSystem.applyClrInt.

+!top <- !r(d1); knock(d2).
+!r(D) <- !g(D); knock(D).
+!g(D) <- unlock(D).
-!g(D) <- push(D).
-!r(D) <- fetchKey.

+!top2 <- !g2(d1); knock(d2).
+!g2(D) <- unlock(D).
-!g2(D) <- push(D).
-!top2 <- knock(d1).
