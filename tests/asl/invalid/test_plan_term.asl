// expect: 3:9 `?` must be followed by a logical formula
// A test goal on a plan term.
+!g <- ?{ +!h <- a }.
