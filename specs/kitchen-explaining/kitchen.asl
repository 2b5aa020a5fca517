// The kitchen robot of specs/kitchen with the paper's explanation mechanism written in the
// agent itself, as the paper's Jason prototype did it: the owner's expected successors are
// beliefs (`expected(Before, After)` over observation tokens), the last observation is a
// belief, and before every environment action the agent checks the pair; when it is novel it
// explains itself with `explain(Action, Context, Steps)` and learns the pair.
//
// The content is written by hand: each plan passes its context down to its subgoals (`Ctx`),
// so an explanation's context is the plan's own literals and everything above it, and the
// steps run up to the one that changes that context (`not p` is written `neg(p)`, since a
// Jason list holds terms). `verify` checks that every explanation the agent gives is the one
// the reference algorithms give, on every run (demand-conformance, content-conformance).

/* Observation tokens: the model's beliefs hold objects, so actions and requests are named. */

navToken(table, nav_table).
navToken(dishwasher, nav_dishwasher).
navToken(cupboard, nav_cupboard).
pickToken(cup1, pick_cup1).
pickToken(cup2, pick_cup2).
putToken(cup1, put_cup1).
putToken(cup2, put_cup2).
storeToken(cup1, req_store_cup1).
storeToken(cup2, req_store_cup2).
putAwayToken(cup1, req_putaway_cup1).
putAwayToken(cup2, req_putaway_cup2).

/* What the owner expects (the pairs of the owner in specs/kitchen, for each cup). */

last(start).
expected(req_store_cup1, nav_table).
expected(req_store_cup2, nav_table).
expected(nav_table, pick_cup1).
expected(nav_table, pick_cup2).
expected(pick_cup1, nav_dishwasher).
expected(pick_cup2, nav_dishwasher).
expected(nav_dishwasher, put_cup1).
expected(nav_dishwasher, put_cup2).
expected(req_putaway_cup1, nav_table).
expected(req_putaway_cup2, nav_table).
expected(pick_cup1, nav_cupboard).
expected(pick_cup2, nav_cupboard).
expected(nav_cupboard, put_cup1).
expected(nav_cupboard, put_cup2).
expected(req_run, nav_dishwasher).
expected(nav_dishwasher, close_dishwasher).
expected(close_dishwasher, nav_dishwasher).
expected(nav_dishwasher, start_dishwasher).
expected(req_wipe, nav_table).
expected(nav_table, wipe_table).

/* Storing a used cup in the dishwasher, then closing the dishwasher. */

@storeCup
+!storeCup(C) : true
   <- ?storeToken(C, R);
      -+last(R);
      !stow(C);
      !closeDishwasherIfNeed([]).

@storeUsedCup
+!stow(C) : used(C) & not cupAt(C, dishwasher)
   <- !openDishwasherIfNeed([used(C), neg(cupAt(C, dishwasher))]);
      !fetch(C, [used(C), neg(cupAt(C, dishwasher))]);
      !deliver(C, dishwasher, [used(C), neg(cupAt(C, dishwasher))]).

@storeNothing
+!stow(C) : not used(C) | cupAt(C, dishwasher).

/* Opening the dishwasher. */

@openDishwasherIfNeed
+!openDishwasherIfNeed(Ctx) : not dishwasherDoor(open) & holding(none)
   <- if (last(P1) & not expected(P1, nav_dishwasher)) {
         explain(navigateTo(dishwasher), [neg(dishwasherDoor(open)), holding(none) | Ctx], [navigateTo(dishwasher), openDoor(dishwasher)]);
         +expected(P1, nav_dishwasher)
      };
      -+last(nav_dishwasher);
      navigateTo(dishwasher);
      if (last(P2) & not expected(P2, open_dishwasher)) {
         explain(openDoor(dishwasher), [neg(dishwasherDoor(open)), holding(none) | Ctx], [openDoor(dishwasher)]);
         +expected(P2, open_dishwasher)
      };
      -+last(open_dishwasher);
      openDoor(dishwasher).

@dishwasherAlreadyOpen
+!openDishwasherIfNeed(Ctx) : dishwasherDoor(open).

/* Fetching a cup from where it stands, and putting the held cup down somewhere. */

@fetch
+!fetch(C, Ctx) : cupAt(C, L)
   <- ?navToken(L, N);
      ?pickToken(C, K);
      if (last(P1) & not expected(P1, N)) {
         explain(navigateTo(L), [cupAt(C, L) | Ctx], [navigateTo(L), pickUp(C)]);
         +expected(P1, N)
      };
      -+last(N);
      navigateTo(L);
      if (last(P2) & not expected(P2, K)) {
         explain(pickUp(C), [cupAt(C, L) | Ctx], [pickUp(C)]);
         +expected(P2, K)
      };
      -+last(K);
      pickUp(C).

@deliver
+!deliver(C, L, Ctx) : holding(C)
   <- ?navToken(L, N);
      ?putToken(C, K);
      if (last(P1) & not expected(P1, N)) {
         explain(navigateTo(L), [holding(C) | Ctx], [navigateTo(L), putDown(C)]);
         +expected(P1, N)
      };
      -+last(N);
      navigateTo(L);
      if (last(P2) & not expected(P2, K)) {
         explain(putDown(C), [holding(C) | Ctx], [putDown(C)]);
         +expected(P2, K)
      };
      -+last(K);
      putDown(C).

/* Putting a clean cup away in the cupboard, then closing the dishwasher it may have opened. */

@putAway
+!putAway(C) : true
   <- ?putAwayToken(C, R);
      -+last(R);
      !shelve(C);
      !closeDishwasherIfNeed([]).

@putAwayCup
+!shelve(C) : not used(C) & not cupAt(C, cupboard)
   <- !reach(C, [neg(used(C)), neg(cupAt(C, cupboard))]);
      !fetch(C, [neg(used(C)), neg(cupAt(C, cupboard))]);
      !deliver(C, cupboard, [neg(used(C)), neg(cupAt(C, cupboard))]).

@putAwayNothing
+!shelve(C) : used(C) | cupAt(C, cupboard).

@reachIntoDishwasher
+!reach(C, Ctx) : cupAt(C, dishwasher)
   <- !openDishwasherIfNeed([cupAt(C, dishwasher) | Ctx]).

@reachDirectly
+!reach(C, Ctx) : not cupAt(C, dishwasher).

/* Running the dishwasher when it holds cups. */

@runDishwasher
+!runDishwasher : cupAt(C, dishwasher)
   <- -+last(req_run);
      !closeDishwasherIfNeed([cupAt(C, dishwasher)]);
      !startWash([cupAt(C, dishwasher)]).

@runEmptyDishwasher
+!runDishwasher : not cupAt(_, dishwasher)
   <- -+last(req_run).

@closeOpenDishwasher
+!closeDishwasherIfNeed(Ctx) : dishwasherDoor(open)
   <- if (last(P1) & not expected(P1, nav_dishwasher)) {
         explain(navigateTo(dishwasher), [dishwasherDoor(open) | Ctx], [navigateTo(dishwasher), closeDoor(dishwasher)]);
         +expected(P1, nav_dishwasher)
      };
      -+last(nav_dishwasher);
      navigateTo(dishwasher);
      if (last(P2) & not expected(P2, close_dishwasher)) {
         explain(closeDoor(dishwasher), [dishwasherDoor(open) | Ctx], [closeDoor(dishwasher)]);
         +expected(P2, close_dishwasher)
      };
      -+last(close_dishwasher);
      closeDoor(dishwasher).

@dishwasherAlreadyClosed
+!closeDishwasherIfNeed(Ctx) : not dishwasherDoor(open).

@startWash
+!startWash(Ctx) : dishwasherDoor(closed)
   <- if (last(P1) & not expected(P1, nav_dishwasher)) {
         explain(navigateTo(dishwasher), [dishwasherDoor(closed) | Ctx], [navigateTo(dishwasher), startDishwasher(dishwasher)]);
         +expected(P1, nav_dishwasher)
      };
      -+last(nav_dishwasher);
      navigateTo(dishwasher);
      if (last(P2) & not expected(P2, start_dishwasher)) {
         explain(startDishwasher(dishwasher), [dishwasherDoor(closed) | Ctx], [startDishwasher(dishwasher)]);
         +expected(P2, start_dishwasher)
      };
      -+last(start_dishwasher);
      startDishwasher(dishwasher).

/* Unloading: every clean cup in the dishwasher goes to the cupboard. */

@unloadDishwasher
+!unloadDishwasher : true
   <- -+last(req_unload);
      for (cupAt(C, dishwasher) & not used(C)) {
         !shelve(C);
      };
      !closeDishwasherIfNeed([]).

/* Wiping the table. */

@wipeDirtyTable
+!wipeTable : dirty(table)
   <- -+last(req_wipe);
      if (last(P1) & not expected(P1, nav_table)) {
         explain(navigateTo(table), [dirty(table)], [navigateTo(table), wipe(table)]);
         +expected(P1, nav_table)
      };
      -+last(nav_table);
      navigateTo(table);
      if (last(P2) & not expected(P2, wipe_table)) {
         explain(wipe(table), [dirty(table)], [wipe(table)]);
         +expected(P2, wipe_table)
      };
      -+last(wipe_table);
      wipe(table).

@tableAlreadyClean
+!wipeTable : not dirty(table)
   <- -+last(req_wipe).
