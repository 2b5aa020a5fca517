// What `.wait` forms the model refuses: the time waited (no clock), an event given as a
// string, and `.wait` in a context (Jason: `canBeUsedInContext` is false).
+!t <- .wait({+ready(a)}, 100, T); use(a).
+!u <- .wait("+ready(a)", 100); use(a).
+!v : .wait(10) <- use(a).
