// Seeded race: two requests both pass `not busy` before either sets it.
+!load(C)[source(fetcher)]
   <- +toStow(C);
      !stowAll.

+!stowAll : busy
   <- true.

+!stowAll : not busy & toStow(C) & cupAt(C, counter)
   <- +busy;
      -toStow(C);
      move(loader, dishwasher);
      openDoor(loader);
      move(loader, counter);
      pick(loader, C);
      move(loader, dishwasher);
      put(loader, C);
      closeDoor(loader);
      move(loader, counter);
      -busy;
      !stowAll.

+!stowAll : not busy & not toStow(_)
   <- true.
