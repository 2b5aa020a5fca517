// The fetcher of specs/two-robots, which keeps off the counter while the loader says it
// is there (`atCounter`, told by the loader).

+!clear(C) : cupAt(C, table)
   <- move(fetcher, table);
      pick(fetcher, C);
      !toCounter;
      put(fetcher, C);
      move(fetcher, table);
      .send(loader, achieve, load(C)).

+!clear(C) : not cupAt(C, table)
   <- true.

+!toCounter : not atCounter[source(loader)]
   <- move(fetcher, counter).

+!toCounter : atCounter[source(loader)]
   <- .wait({-atCounter[source(loader)]});
      !toCounter.
