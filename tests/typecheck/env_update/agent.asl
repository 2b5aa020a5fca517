// Belief updates on environment predicates.
+!go(L) : not robotAt(L)
   <- navigateTo(L);
      +robotAt(L);
      -+holding(none).
