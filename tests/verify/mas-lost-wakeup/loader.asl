// Seeded communication defect: a request that comes while the loader is busy waits for
// `-busy`, which may have come already.
+!load(C)[source(fetcher)] <- !stow(C).

+!stow(C) : not busy & cupAt(C, counter)
   <- +busy;
      move(loader, dishwasher);
      openDoor(loader);
      move(loader, counter);
      pick(loader, C);
      move(loader, dishwasher);
      put(loader, C);
      closeDoor(loader);
      move(loader, counter);
      -busy.

+!stow(C) : busy
   <- .wait({-busy});
      !stow(C).
