// What `.wait` forms the model refuses: the time waited (no clock), an event given as a
// string, and `.wait` in a context (Jason: `canBeUsedInContext` is false); `.random` in a
// context (its answers would be choices of the deliberation) is refused too.
+!t <- .wait({+ready(a)}, 100, T); use(a).
+!u <- .wait("+ready(a)", 100); use(a).
+!v : .wait(10) <- use(a).
+!w : .random([a, b], X) <- use(X).
