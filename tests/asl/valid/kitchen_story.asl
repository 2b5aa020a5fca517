// A realistic kitchen robot, in the style of the paper's running example:
// after breakfast the robot puts every used cup from the table into the
// dishwasher, opening the dishwasher door first if it is closed, and puts
// clean cups back into the cupboard.

/* Initial beliefs */
cup(c1).
cup(c2).
cup(c3).
on(c1, table).
on(c2, table).
on(c3, dishwasher).
used(c1).
used(c2).
holding(none).
dishwasherDoor(closed).
robotAt(charger).

/* Rules */
usedCupOnTable(C) :- cup(C) & on(C, table) & used(C).
cleanCupInDishwasher(C) :- cup(C) & on(C, dishwasher) & not used(C).
handsFree :- holding(none).

/* Initial goal */
!tidyUp.

/* Plans */
@tidy
+!tidyUp : usedCupOnTable(C) <- !storeCup(C); !tidyUp.
+!tidyUp : cleanCupInDishwasher(C) <- !putAway(C); !tidyUp.
+!tidyUp <- !closeDishwasher; navigateTo(charger); .print("kitchen is tidy").

@store
+!storeCup(C) : used(C)
   <- !openDishwasherIfNeed;
      navigateTo(table);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C).

@openDoor
+!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)
   <- navigateTo(dishwasher);
      openDoor(dishwasher).
+!openDishwasherIfNeed : dishwasherDoor(open).

@putAway
+!putAway(C) : handsFree
   <- navigateTo(dishwasher);
      pickUp(C);
      navigateTo(cupboard);
      putDown(C).

+!closeDishwasher : dishwasherDoor(open) & handsFree
   <- navigateTo(dishwasher);
      closeDoor(dishwasher).
+!closeDishwasher.

/* Percepts from the robot's sensors */
+holding(X)[source(percept)] : X \== none <- .print("holding ", X).
+on(C, L)[source(percept)] <- -on(C, _); +on(C, L).
+dishwasherDoor(S)[source(percept)] <- -+dishwasherDoor(S).

/* Failure handling */
-!storeCup(C) : holding(C)
   <- putDown(C);
      .print("could not store ", C, ", put it down");
      .fail.
-!storeCup(C) <- .print("could not store ", C).
