// The fetcher of specs/two-robots, which asks the loader whether it is free before it
// hands a cup over (and hands it over whatever the answer).

+!clear(C) : cupAt(C, table)
   <- move(fetcher, table);
      pick(fetcher, C);
      move(fetcher, counter);
      put(fetcher, C);
      move(fetcher, table);
      .send(loader, askOne, free(A), free(A));
      .send(loader, achieve, load(C)).

+!clear(C) : not cupAt(C, table)
   <- true.
