// Storing cups, written apart from specs/kitchen (the libraries bench's store-cup library),
// for three interchangeable cups. The first plan opens the door before it fetches the cup:
// when its later actions are explained, `dishwasherDoor(closed)` (and, once the cup is
// picked up, its place and the free hand) is no longer believed (content-truthful).
+!storeCup(C) : cupAt(C, P) & P \== dishwasher & holding(none) & dishwasherDoor(closed)
   <- navigateTo(dishwasher);
      openDoor(dishwasher);
      navigateTo(P);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C);
      closeDoor(dishwasher).
+!storeCup(C) : cupAt(C, P) & P \== dishwasher & holding(none) & not dishwasherDoor(closed)
   <- navigateTo(P);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C).
+!storeCup(C) : cupAt(C, dishwasher).
