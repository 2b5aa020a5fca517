// Case 74: the error annotation of a failure event for each kind of failing step: a
// constraint that does not hold (constraint_failed), a test goal with no answer
// (test_goal_failed), an arithmetic error in a belief update and in a constraint, and a
// failed action (action_failed). Decided by TransitionSystem.applyExecInt (the
// `constraint` case, generateGoalDeletion) and JasonException.createBasicErrorAnnots.

+!c <- X = 2; X > 3; act(a).
-!c[error(E)] <- .print("c: ", E).

+!t <- ?nothing(X); act(a).
-!t[error(E)] <- .print("t: ", E).

+!u <- use(b); act(a).
-!u[error(E)] <- .print("u: ", E); act(c).

+!k <- X = 1; Y = X - 1; X < 0; act(a).
-!k[error(constraint_failed)] <- .print("k: constraint").
-!k[error(E)] <- .print("k: other ", E).
