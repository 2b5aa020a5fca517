// The loader of specs/two-robots, which also answers whether it is free. Seeded defect:
// it answers only while the dishwasher's door is closed (no `+?free(no)` plan), so a
// question that comes while it loads a cup finds no applicable plan in Jason's plans for
// messages, and no answer is sent.

+?free(yes) : door(closed).

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
