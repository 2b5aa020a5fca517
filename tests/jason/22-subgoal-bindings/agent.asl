// Case 22: bindings made inside a subgoal flow back to the plan that posted it: by a test goal
// in the subplan (?best(X)), by a plan trigger with a constant (+!choose(a).), by a context
// (+!viaContext(X) : best(X)), and through two levels (!outer(V) -> !inner(V)). Decided by
// TransitionSystem.applyClrInt (joinRenamedVarsIntoIntentionUnifier: the finished subgoal's
// literal is unified with the body step that called it).

best(b).

+!fetch <- !get(X); act(X).
+!get(X) <- ?best(X).

+!pick <- !choose(Y); act(Y); !viaContext(Z); act(Z).
+!choose(a).
+!viaContext(X) : best(X) <- true.

+!deep <- !outer(V); act(V).
+!outer(V) <- !inner(V).
+!inner(c).
