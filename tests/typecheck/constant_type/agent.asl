// A constant of the wrong type for an action and for a predicate.
+!clear : holding(none)
   <- pickUp(table);
      navigateTo(cup1).

+!check : cupAt(table, cup1).
