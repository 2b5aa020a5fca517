// The fetcher carries a used cup from the table to the counter, then asks the loader to
// put it in the dishwasher. It never goes to the dishwasher itself.

+!clear(C) : cupAt(C, table)
   <- move(fetcher, table);
      pick(fetcher, C);
      move(fetcher, counter);
      put(fetcher, C);
      move(fetcher, table);
      .send(loader, achieve, load(C)).

+!clear(C) : not cupAt(C, table)
   <- true.
