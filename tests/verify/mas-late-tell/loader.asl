// The loader of specs/two-robots, which waits at the dishwasher and tells the fetcher
// while it is at the counter (`atCounter`). Seeded defect: the tell is a message, and the
// fetcher may have looked, and moved, before it arrives.

!work.

+!load(C)[source(fetcher)]
   <- +toStow(C).

+!work : toStow(C) & cupAt(C, counter)
   <- -toStow(C);
      openDoor(loader);
      .send(fetcher, tell, atCounter);
      move(loader, counter);
      pick(loader, C);
      move(loader, dishwasher);
      .send(fetcher, untell, atCounter);
      put(loader, C);
      closeDoor(loader);
      !!work.

+!work : not toStow(_)
   <- .wait({+toStow(_)}, 500);
      !!work.

-!work
   <- !!work.
