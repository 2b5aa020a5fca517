// expect: 3:14 cannot be negated or annotated
// Internal actions cannot be strongly negated.
+!storeCup : ~.desire(tidy) <- pickUp(c1).
