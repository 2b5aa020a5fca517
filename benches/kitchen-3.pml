/* The kitchen robot of specs/kitchen with 3 cups, for SPIN (benches/spin.rs writes it;
 * this text is that bench's `promela` function, do not edit it by hand).
 *
 * What is modelled, at the level of actions:
 * - the state: every atom of kitchen.pddl over its objects, one bit each, as bdi-check
 *   has them (robotAt per location, holding per item with holding[0] = holding(none),
 *   cupAt per cup and location, used per cup, dishwasherDoor open/closed, dirty per
 *   location), so that the invariants are the manifest's, counts of atoms included;
 * - the initial states: every assignment of the manifest's `vary` atoms that satisfies its
 *   constraints and invariants (each cup on the table, in the dishwasher or in the
 *   cupboard, used or not but never used in the cupboard; the door open or closed; the
 *   table dirty or not; robotAt(table) and holding(none)), chosen nondeterministically;
 * - the requests: at most MAXREQ per run, each ground goal of [requests] at most once,
 *   arriving only when the robot is idle (arrival = "idle"); the run may stop at any idle
 *   point (the end label);
 * - the plan library kitchen.asl: each goal is an inline whose `if` takes the first
 *   applicable plan in source order (plan_selection = "first"; no applicable plan is a
 *   goal failure, an assertion), each body step in order, the plan's variables C and L
 *   in the locals c and l; `for` snapshots its answers and runs in cup order;
 * - the actions of kitchen.pddl: one d_step each, whose assert is the precondition (an
 *   action attempted when it does not hold is a failure, as bdi-check's action-failure
 *   check) followed by the effects;
 * - the [invariants] and the `always` property: a monitor process's assertions, checked
 *   in every state once the initial state is set up;
 * - stuck states (bdi-check's deadlock check): pan's invalid end states.
 *
 * What is abstracted: Jason's reasoning cycle. bdi-check's states hold the event queue, the
 * intention stack with its frames and the belief base in Jason's order, and one transition
 * is one reasoning cycle (an event selected and a plan adopted, or one body step); here one
 * transition is one Promela statement, mostly an action or a plan's choice, the intention
 * stack is the program counter, and the order of `for`'s answers is the cups' (Jason's is
 * its belief base's). The state counts of the two searches differ for that reason. The
 * `reachable` property is not checked here: pan's safety search finds violations, and a
 * witness is one only as the failure of an assertion that it is unreachable. */

#define CUPS 3
#define MAXREQ 2
#define TABLE 0
#define DISHWASHER 1
#define CUPBOARD 2

bit robotAt[3];
bit holding[CUPS + 1];   /* holding[0]: holding(none); holding[c + 1]: the cup c */
typedef Places { bit at[3] };
Places cupAt[CUPS];
bit used[CUPS];
bit doorOpen;            /* dishwasherDoor(open) */
bit doorClosed;          /* dishwasherDoor(closed) */
bit dirty[3];
bit requested[2 * CUPS + 3];   /* storeCup(c), putAway(c), runDishwasher, unloadDishwasher, wipeTable */
byte nreq;               /* requests made */
bit ready;               /* the initial state is set up */

/* [invariants] and the property no_used_cup_in_cupboard */
#define one_location (robotAt[TABLE] + robotAt[DISHWASHER] + robotAt[CUPBOARD] == 1)
#define one_item_in_hand (holding[0] + holding[1] + holding[2] + holding[3] == 1)
#define placed(c) (cupAt[c].at[TABLE] + cupAt[c].at[DISHWASHER] + cupAt[c].at[CUPBOARD])
#define held_or_placed(c) ((holding[c + 1] && placed(c) == 0) || (!holding[c + 1] && placed(c) == 1))
#define cup_held_or_in_one_place (held_or_placed(0) && held_or_placed(1) && held_or_placed(2))
#define door_open_or_closed (doorOpen + doorClosed == 1)
#define no_used_cup_in_cupboard (!(used[0] && cupAt[0].at[CUPBOARD]) && !(used[1] && cupAt[1].at[CUPBOARD]) && !(used[2] && cupAt[2].at[CUPBOARD]))
#define INVARIANTS (one_location && one_item_in_hand && cup_held_or_in_one_place && door_open_or_closed && no_used_cup_in_cupboard)

/* The monitor: blocked while the invariants hold, so that it adds no states (its end label
 * makes that a valid end state), and enabled in any stored state where they fail, so that
 * the assertion of the first that fails fails there. Unlike a never claim, it leaves
 * pan's check of invalid end states on: a state where the robot is stuck outside its idle
 * point is an error. */
active proctype monitor() {
end:
  ready && !INVARIANTS ->
  assert(one_location);
  assert(one_item_in_hand);
  assert(cup_held_or_in_one_place);
  assert(door_open_or_closed);
  assert(no_used_cup_in_cupboard)
}

/* The actions of kitchen.pddl: the precondition, then the effects. Each call is a d_step
 * of its own: one transition. */

inline navigateTo(to) {
  assert(robotAt[TABLE] || robotAt[DISHWASHER] || robotAt[CUPBOARD]);
  robotAt[TABLE] = (to == TABLE);
  robotAt[DISHWASHER] = (to == DISHWASHER);
  robotAt[CUPBOARD] = (to == CUPBOARD)
}

/* Cups in the dishwasher can only be reached through an open door. */
inline pickUp(cup) {
  assert(holding[0]
         && ((robotAt[TABLE] && cupAt[cup].at[TABLE]) || (robotAt[DISHWASHER] && cupAt[cup].at[DISHWASHER])
             || (robotAt[CUPBOARD] && cupAt[cup].at[CUPBOARD]))
         && (!cupAt[cup].at[DISHWASHER] || doorOpen));
  holding[cup + 1] = 1;
  holding[0] = 0;
  cupAt[cup].at[TABLE] = 0;
  cupAt[cup].at[DISHWASHER] = 0;
  cupAt[cup].at[CUPBOARD] = 0
}

/* A cup goes where the robot stands; never a used cup into the cupboard. */
inline putDown(cup) {
  assert(holding[cup + 1] && (!robotAt[DISHWASHER] || doorOpen) && (!robotAt[CUPBOARD] || !used[cup]));
  holding[cup + 1] = 0;
  holding[0] = 1;
  cupAt[cup].at[TABLE] = cupAt[cup].at[TABLE] || robotAt[TABLE];
  cupAt[cup].at[DISHWASHER] = cupAt[cup].at[DISHWASHER] || robotAt[DISHWASHER];
  cupAt[cup].at[CUPBOARD] = cupAt[cup].at[CUPBOARD] || robotAt[CUPBOARD]
}

inline openDoor(a) {
  assert(a == DISHWASHER && robotAt[DISHWASHER] && holding[0] && doorClosed);
  doorOpen = 1;
  doorClosed = 0
}

inline closeDoor(a) {
  assert(a == DISHWASHER && robotAt[DISHWASHER] && holding[0] && doorOpen);
  doorClosed = 1;
  doorOpen = 0
}

/* A wash cycle cleans every cup inside. */
inline startDishwasher(a) {
  assert(a == DISHWASHER && robotAt[DISHWASHER] && doorClosed);
  used[0] = used[0] && !cupAt[0].at[DISHWASHER];
  used[1] = used[1] && !cupAt[1].at[DISHWASHER];
  used[2] = used[2] && !cupAt[2].at[DISHWASHER]
}

inline wipe(loc) {
  assert(robotAt[loc] && holding[0]);
  dirty[loc] = 0
}

/* The plans of kitchen.asl, one inline per goal: the first applicable plan in source
 * order, else the goal fails. */

inline openDishwasherIfNeed() {
  if
  :: !doorOpen && holding[0] ->            /* @openDishwasherIfNeed */
     d_step { navigateTo(DISHWASHER) };
     d_step { openDoor(DISHWASHER) }
  :: else ->
     if
     :: doorOpen                            /* @dishwasherAlreadyOpen */
     :: else -> assert(false)               /* no applicable plan */
     fi
  fi
}

/* @fetch: cupAt(C, L), the first answer (the invariants leave one). */
inline fetch() {
  d_step {
    assert(placed(c) > 0);                  /* no applicable plan otherwise */
    l = (cupAt[c].at[TABLE] -> TABLE : (cupAt[c].at[DISHWASHER] -> DISHWASHER : CUPBOARD))
  };
  d_step { navigateTo(l) };
  d_step { pickUp(c); l = 0 }   /* @fetch ends with its last step, as in Jason: L goes */
}

inline deliver(dest) {
  if
  :: holding[c + 1] ->                      /* @deliver */
     d_step { navigateTo(dest) };
     d_step { putDown(c) }
  :: else -> assert(false)
  fi
}

inline storeCup() {
  if
  :: used[c] && !cupAt[c].at[DISHWASHER] -> /* @storeUsedCup */
     openDishwasherIfNeed();
     fetch();
     deliver(DISHWASHER)
  :: else                                   /* @storeNothing */
  fi
}

inline putAway() {
  if
  :: !used[c] && !cupAt[c].at[CUPBOARD] ->  /* @putAwayCup */
     if                                     /* !reach(C) */
     :: cupAt[c].at[DISHWASHER] ->          /* @reachIntoDishwasher */
        openDishwasherIfNeed()
     :: else                                /* @reachDirectly */
     fi;
     fetch();
     deliver(CUPBOARD)
  :: else                                   /* @putAwayNothing */
  fi
}

inline runDishwasher() {
  if
  :: cupAt[0].at[DISHWASHER] || cupAt[1].at[DISHWASHER] || cupAt[2].at[DISHWASHER] ->   /* @runDishwasher */
     if                                     /* !closeDishwasherIfNeed */
     :: doorOpen ->                         /* @closeOpenDishwasher */
        d_step { navigateTo(DISHWASHER) };
        d_step { closeDoor(DISHWASHER) }
     :: else                                /* @dishwasherAlreadyClosed */
     fi;
     if                                     /* !startWash */
     :: doorClosed ->                       /* @startWash */
        d_step { navigateTo(DISHWASHER) };
        d_step { startDishwasher(DISHWASHER) }
     :: else -> assert(false)
     fi
  :: else                                   /* @runEmptyDishwasher */
  fi
}

/* @unloadDishwasher: for (cupAt(C, dishwasher) & not used(C)) { !putAway(C) } */
inline unloadDishwasher() {
  d_step {
    todo[0] = cupAt[0].at[DISHWASHER] && !used[0];
    todo[1] = cupAt[1].at[DISHWASHER] && !used[1];
    todo[2] = cupAt[2].at[DISHWASHER] && !used[2]
  };
  do
  :: d_step {                               /* the next answer, or CUPS when none is left */
       c = (todo[0] -> 0 : (todo[1] -> 1 : (todo[2] -> 2 : CUPS)));
       if
       :: c < CUPS -> todo[c] = 0
       :: else
       fi
     };
     if
     :: c == CUPS -> break
     :: else -> putAway()
     fi
  od
}

inline wipeTable() {
  if
  :: dirty[TABLE] ->                        /* @wipeDirtyTable */
     d_step { navigateTo(TABLE) };
     d_step { wipe(TABLE) }
  :: else                                   /* @tableAlreadyClean */
  fi
}

active proctype robot() {
  byte c;          /* the running plans' variable C */
  byte l;          /* @fetch's variable L */
  bit todo[CUPS];  /* the answers @unloadDishwasher's for has left */

  /* [initial]: robotAt(table), holding(none), and every assignment of the vary atoms
   * that satisfies the constraints and the invariants. */
  atomic {
    robotAt[TABLE] = 1;
    holding[0] = 1;
    if
    :: cupAt[0].at[TABLE] = 1
    :: cupAt[0].at[TABLE] = 1; used[0] = 1
    :: cupAt[0].at[DISHWASHER] = 1
    :: cupAt[0].at[DISHWASHER] = 1; used[0] = 1
    :: cupAt[0].at[CUPBOARD] = 1
    fi;
    if
    :: cupAt[1].at[TABLE] = 1
    :: cupAt[1].at[TABLE] = 1; used[1] = 1
    :: cupAt[1].at[DISHWASHER] = 1
    :: cupAt[1].at[DISHWASHER] = 1; used[1] = 1
    :: cupAt[1].at[CUPBOARD] = 1
    fi;
    if
    :: cupAt[2].at[TABLE] = 1
    :: cupAt[2].at[TABLE] = 1; used[2] = 1
    :: cupAt[2].at[DISHWASHER] = 1
    :: cupAt[2].at[DISHWASHER] = 1; used[2] = 1
    :: cupAt[2].at[CUPBOARD] = 1
    fi;
    if
    :: doorOpen = 1
    :: doorClosed = 1
    fi;
    if
    :: dirty[TABLE] = 1
    :: skip
    fi;
    ready = 1
  };

  /* Idle: the next request, or none (the run stops here). */
end_idle:
  if
  :: d_step { nreq < MAXREQ && !requested[0] -> requested[0] = 1; nreq++; c = 0 };   /* !storeCup(cup1) */
     storeCup()
  :: d_step { nreq < MAXREQ && !requested[1] -> requested[1] = 1; nreq++; c = 1 };   /* !storeCup(cup2) */
     storeCup()
  :: d_step { nreq < MAXREQ && !requested[2] -> requested[2] = 1; nreq++; c = 2 };   /* !storeCup(cup3) */
     storeCup()
  :: d_step { nreq < MAXREQ && !requested[3] -> requested[3] = 1; nreq++; c = 0 };   /* !putAway(cup1) */
     putAway()
  :: d_step { nreq < MAXREQ && !requested[4] -> requested[4] = 1; nreq++; c = 1 };   /* !putAway(cup2) */
     putAway()
  :: d_step { nreq < MAXREQ && !requested[5] -> requested[5] = 1; nreq++; c = 2 };   /* !putAway(cup3) */
     putAway()
  :: d_step { nreq < MAXREQ && !requested[6] -> requested[6] = 1; nreq++; c = 0 };   /* !runDishwasher */
     runDishwasher()
  :: d_step { nreq < MAXREQ && !requested[7] -> requested[7] = 1; nreq++; c = 0 };   /* !unloadDishwasher */
     unloadDishwasher()
  :: d_step { nreq < MAXREQ && !requested[8] -> requested[8] = 1; nreq++; c = 0 };   /* !wipeTable */
     wipeTable()
  fi;
  atomic { c = 0; l = 0 };   /* the intention is done: its variables go */
  goto end_idle
}
