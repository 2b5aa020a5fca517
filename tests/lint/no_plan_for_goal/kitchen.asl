// The kitchen robot's plan library: the paper's running example (storeUsedCup and
// openDishwasherIfNeed) completed so that every request can be served, and the other
// cleaning tasks of the paper's survey.

/* Storing a used cup in the dishwasher (the paper's plan pi_1). */

@storeUsedCup
+!storeCup(C) : used(C) & cupAt(C, table)
   <- !openDishwasher;
      navigateTo(table);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C).

// Nothing to store: the cup is clean, or not on the table.
@storeNothing
+!storeCup(C) : not used(C) | not cupAt(C, table).

/* Opening the dishwasher (the paper's plan pi_2). */

@openDishwasherIfNeed
+!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)
   <- navigateTo(dishwasher);
      openDoor(dishwasher).

// The paper's gap, closed: when the door is already open there is nothing to do.
@dishwasherAlreadyOpen
+!openDishwasherIfNeed : dishwasherDoor(open).

/* Putting a clean cup away in the cupboard. */

@putAwayFromDishwasher
+!putAway(C) : not used(C) & cupAt(C, dishwasher)
   <- !openDishwasherIfNeed;
      navigateTo(dishwasher);
      pickUp(C);
      navigateTo(cupboard);
      putDown(C).

@putAwayFromTable
+!putAway(C) : not used(C) & cupAt(C, table)
   <- navigateTo(table);
      pickUp(C);
      navigateTo(cupboard);
      putDown(C).

// A used cup is not put away, and a cup in the cupboard is away already.
@putAwayNothing
+!putAway(C) : used(C) | cupAt(C, cupboard).

/* Running the dishwasher when it holds cups. */

@runOpenDishwasher
+!runDishwasher : cupAt(_, dishwasher) & dishwasherDoor(open)
   <- navigateTo(dishwasher);
      closeDoor(dishwasher);
      startDishwasher(dishwasher).

@runClosedDishwasher
+!runDishwasher : cupAt(_, dishwasher) & dishwasherDoor(closed)
   <- navigateTo(dishwasher);
      startDishwasher(dishwasher).

@runEmptyDishwasher
+!runDishwasher : not cupAt(_, dishwasher).

/* Unloading: every clean cup in the dishwasher goes to the cupboard, one at a time. */

@unloadOneCup
+!unloadDishwasher : cupAt(C, dishwasher) & not used(C)
   <- !putAway(C);
      !unloadDishwasher.

@unloadDone
+!unloadDishwasher : not (cupAt(C, dishwasher) & not used(C)).

/* Wiping the table. */

@wipeDirtyTable
+!wipeTable : dirty(table)
   <- navigateTo(table);
      wipe(table).

@tableAlreadyClean
+!wipeTable : not dirty(table).
