// Unknown predicates: in contexts (with a near name, and with none), in a rule body, in a
// belief-event trigger (a test goal on an unknown predicate is a lint finding, not bad input).
+!storeCup(C) : usd(C) & cupAt(C, table)
   <- pickUp(C).

+!wipeTable : sparkling(table) | dirty(table)
   <- ?holdin(X);
      wipe(table).

clean(L) :- not drity(L).

+sparkle(L) <- .print(L).
