// expect: 3:21 `,` or `)`
// An argument list that is never closed.
+!wash(C) <- rinse(C; dry(C).
