// Mental notes, rules and goal parameters, all inferred.
visited(table).

near(L) :- robotAt(L).
near(L) :- visited(L).

+!tidy(C) : cupAt(C, L) & not marked(C)
   <- !fetch(C);
      +marked(C);
      +visited(L);
      !report(C);
      explain("tidied").

+!fetch(X) <- pickUp(X).
+!report(Y) : visited(Z) <- .print(Y, Z).

// a -> b -> c: the type of c's parameter flows back to a.
+!a(X) <- !b(X).
+!b(Y) <- !c(Y).
+!c(Z) <- wipe(Z).

// A mental note added with unrelated types is an `object` note.
+!both <- +thing(cup1); +thing(table).

+marked(C) : near(L) <- .print(C, L).
