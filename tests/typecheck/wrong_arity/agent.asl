// A predicate and an action used with the wrong number of arguments.
+!storeCup(C) : cupAt(C)
   <- navigateTo(table, C);
      pickUp(C).
