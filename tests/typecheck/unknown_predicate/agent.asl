// Unknown predicates: in contexts (with a near name, and with none), in a rule body, in a
// test goal and in a belief-event trigger.
+!storeCup(C) : usd(C) & cupAt(C, table)
   <- pickUp(C).

+!wipeTable : sparkling(table) | dirty(table)
   <- ?holdin(X);
      wipe(table).

clean(L) :- not drity(L).

+sparkle(L) <- .print(L).
