// The fetcher of specs/two-robots, written to be explained: each context states what stays
// true while its plan runs (a cup being cleared is not on the counter until the fetcher puts
// it there), and each subgoal's actions end with the one that changes its context. It stays
// at the counter, and the loader takes the cup from there.

@clearFromTable
+!clear(C) : not cupAt(C, counter)
   <- !fetch(C);
      !bring(C);
      .send(loader, achieve, load(C)).

@clearNothing
+!clear(C) : cupAt(C, counter)
   <- true.

@fetch
+!fetch(C) : cupAt(C, table)
   <- move(fetcher, table);
      pick(fetcher, C).

@bring
+!bring(C) : holding(fetcher, C)
   <- move(fetcher, counter);
      put(fetcher, C).
