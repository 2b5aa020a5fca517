// Case 76: a subgoal's answer flows back into the plan that posted it, but the subgoal's
// own variables stay its own: !g(X) binds X to g's unbound Y, which is not the parent's Y,
// so binding the parent's Y later leaves X unbound. Decided by
// TransitionSystem.applyClrInt (the unifier of the finished subgoal is composed into the
// parent's with the subgoal plan's variables renamed apart, Plan.makeVarsAnnon).

+!go <- !g(X); Y = 1; if (X == 1) { act(a) } else { act(b) }; !h(Z, W); Z = 2;
        if (W == 2) { mark(a) } else { mark(b) }.
+!g(A) <- A = Y.
+!h(P, Q) <- Q = P.
