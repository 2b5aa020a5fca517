// Case 82: a belief update whose argument cannot be evaluated (an integer division by
// zero) fails the plan like any step that throws, with the error annotation Jason gives
// it; a constraint with the same division fails too. Decided by
// TransitionSystem.applyExecInt (addBel/delBel: prepareBodyForEvent, capply of ArithExpr)
// and the JasonException error terms.

val(1).

+!d <- X = 0; +val(5 div X); act(a).
-!d[error(E)] <- .print("d: ", E).

+!e <- X = 0; -val(5 mod X); act(a).
-!e[error(E)] <- .print("e: ", E).

+!f <- X = 0; Y = 5 div X; act(a).
-!f[error(E)] <- .print("f: ", E).
