// The kitchen robot's plan library: the paper's running example (storeUsedCup and
// openDishwasherIfNeed) completed so that every request can be served, and the other
// cleaning tasks of the paper's survey.
//
// Written so that its explanations hold up (SPEC §4, checked by `verify`):
// * a plan's context only states what stays true while the plan runs (what made the robot
//   choose it), never what the plan itself changes: every literal of an explanation's
//   context is still believed when the explanation is given (content-truthful);
// * a body's actions never follow a subgoal that acts: what the user sees is then the
//   body's own sequence, so the paper's Algorithm 1, which marks a body's actions when the
//   plan is adopted, flags the same actions as the observed sequence (demand-adoption).
// * a task that may open the dishwasher closes it again when it is done, from a plan whose
//   context is `true` (`+!storeCup`, `+!putAway`, `+!unloadDishwasher`): the context of the
//   plan that moved the cup no longer holds by then, and an explanation must not give it
//   (the manifest's `door_closed_after_the_last_request`).

/* Storing a used cup in the dishwasher (the paper's plan pi_1, with its moves in subgoals),
   then closing the dishwasher. */

@storeCup
+!storeCup(C) : true
   <- !stow(C);
      !closeDishwasherIfNeed.

@storeUsedCup
+!stow(C) : used(C) & not cupAt(C, dishwasher)
   <- !openDishwasherIfNeed;
      !fetch(C);
      !deliver(C, dishwasher).

// Nothing to store: the cup is clean, or in the dishwasher already.
@storeNothing
+!stow(C) : not used(C) | cupAt(C, dishwasher).

/* Opening the dishwasher (the paper's plan pi_2). */

@openDishwasherIfNeed
+!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)
   <- navigateTo(dishwasher);
      openDoor(dishwasher).

// The paper's gap, closed: when the door is already open there is nothing to do.
@dishwasherAlreadyOpen
+!openDishwasherIfNeed : dishwasherDoor(open).

/* Fetching a cup from where it stands, and putting the held cup down somewhere. */

@fetch
+!fetch(C) : cupAt(C, L)
   <- navigateTo(L);
      pickUp(C).

@deliver
+!deliver(C, L) : holding(C)
   <- navigateTo(L);
      putDown(C).

/* Putting a clean cup away in the cupboard, then closing the dishwasher it may have opened. */

@putAway
+!putAway(C) : true
   <- !shelve(C);
      !closeDishwasherIfNeed.

@putAwayCup
+!shelve(C) : not used(C) & not cupAt(C, cupboard)
   <- !reach(C);
      !fetch(C);
      !deliver(C, cupboard).

// A used cup is not put away, and a cup in the cupboard is away already.
@putAwayNothing
+!shelve(C) : used(C) | cupAt(C, cupboard).

// Cups in the dishwasher can only be reached through its open door.
@reachIntoDishwasher
+!reach(C) : cupAt(C, dishwasher)
   <- !openDishwasherIfNeed.

@reachDirectly
+!reach(C) : not cupAt(C, dishwasher).

/* Running the dishwasher when it holds cups. */

@runDishwasher
+!runDishwasher : cupAt(_, dishwasher)
   <- !closeDishwasherIfNeed;
      !startWash.

@runEmptyDishwasher
+!runDishwasher : not cupAt(_, dishwasher).

@closeOpenDishwasher
+!closeDishwasherIfNeed : dishwasherDoor(open)
   <- navigateTo(dishwasher);
      closeDoor(dishwasher).

@dishwasherAlreadyClosed
+!closeDishwasherIfNeed : not dishwasherDoor(open).

@startWash
+!startWash : dishwasherDoor(closed)
   <- navigateTo(dishwasher);
      startDishwasher(dishwasher).

/* Unloading: every clean cup in the dishwasher goes to the cupboard, one at a time. */

@unloadDishwasher
+!unloadDishwasher : true
   <- for (cupAt(C, dishwasher) & not used(C)) {
         !shelve(C);
      };
      !closeDishwasherIfNeed.

/* Wiping the table. */

@wipeDirtyTable
+!wipeTable : dirty(table)
   <- navigateTo(table);
      wipe(table).

@tableAlreadyClean
+!wipeTable : not dirty(table).
