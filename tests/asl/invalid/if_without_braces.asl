// expect: 3:25 expected `{` to open the `if` body
// The branches of `if` need braces.
+!tidy <- if (used(c1)) !storeCup(c1).
