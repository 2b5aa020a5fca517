// Case 12 (point 2): failure plans selected by the error annotation of the failure event:
// error(action_failed) for a failed action, test_goal_failed for a test goal nothing answers,
// ia_failed for .fail. Decided by TransitionSystem.generateGoalDeletion /
// setDefaultFailureAnnots and the `error` terms of JasonException.createBasicErrorAnnots;
// plan relevance compares trigger annotations as a subset (Trigger/Literal.subsumes).

+!t(X) <- use(X); act(X).
-!t(X)[error(action_failed)] <- .print("action failed for ", X); mark(X).
-!t(X) <- .print("other failure for ", X).

+!q <- act(a); ?ghost(Y); act(Y).
-!q[error(E)] <- .print("q: ", E).

+!f <- act(b); .fail.
-!f[error(E)] <- .print("f: ", E).
