// expect: 3:17 `?` must be followed by a logical formula
// A test goal on a number.
+!checkCups <- ?3.
