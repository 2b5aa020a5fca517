// expect: 3:16 `+` must be followed by a literal
// `+` adds a belief; an arithmetic expression is not one.
+!countCup <- +(Count + 1).
