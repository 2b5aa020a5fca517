// The loader takes cups from the counter into the dishwasher, one at a time: what the
// fetcher asks for is queued as `toStow(C)`, and one intention works through the queue.
//
// Two first versions failed verify: `.wait({-busy})` in the plan for a second request
// waited forever in the run where the `-busy` event came before the wait began, and a
// `not busy` context let two intentions both pass the test before either set `busy`.

!work.

+!load(C)[source(fetcher)]
   <- +toStow(C).

+!work : toStow(C) & cupAt(C, counter)
   <- -toStow(C);
      move(loader, dishwasher);
      openDoor(loader);
      move(loader, counter);
      pick(loader, C);
      move(loader, dishwasher);
      put(loader, C);
      closeDoor(loader);
      move(loader, counter);
      !!work.

// Nothing to do: wait for a request, or look again after a while (a `+toStow` event
// that came before the wait began would otherwise be missed). A wait for an event that
// times out fails, and the failure plan looks again (`!!`: in a new intention, so
// the stack does not grow).
+!work : not toStow(_)
   <- .wait({+toStow(_)}, 500);
      !!work.

-!work
   <- !!work.
