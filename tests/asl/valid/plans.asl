// Covers plans: optional labels `@name[annots]` and `@[annots]`, triggers
// `+`/`-`/`^` combined with `!` (achieve), `?` (test) or a belief,
// optional context, optional body, a plan with no body, Jason 3's goal
// condition `<:`, and Jason 3 sub-plans `{ ... }` written after a plan.

holding(none).

// A bare trigger with a body and no context.
+!tidyKitchen <- !storeCup(c1).

// Labelled plan with annotations on the label.
@storeUsed[atomic, priority(2)]
+!storeCup(C) : used(C) <- pickUp(C); putDown(C).

// A label made only of annotations.
@[breakpoint]
+!storeCup(C) : not used(C) <- .print("cup ", C, " is clean already").

// A plan with no body: reaching a place we already are at succeeds at once.
+!at(L) : at(L).

// A plan with a body but no context.
+!at(L) <- navigateTo(L); -+at(L).

// Goal deletion (failure handling) plans.
-!storeCup(C) <- .print("could not store ", C).
-!at(_) : true.

// Test-goal triggers.
+?where(C, L) : at(C, L).
+?where(C, unknown) <- .print("no idea where ", C, " is").
-?where(_, _) <- true.

// Belief triggers: addition and deletion.
+cupDropped(C)[source(percept)] : holding(C) <- -+holding(none); !storeCup(C).
-dishwasherDoor(open) <- .print("door closed").
+~full(cupboard) <- !storeAll.

// Goal-state triggers (`^`), Jason 3.
^!storeCup(C)[state(S)] : S == suspended <- .print(C, " suspended").
^!tidyKitchen[state(finished)].

// Jason 3 goal condition: the goal is achieved as soon as `stored(C)` holds.
@washLoop
+!wash(C) : cup(C) <: stored(C) <- rinse(C); dry(C).

// Goal condition with no context.
+!dryAll <: not wet(_) <- dry(c1).

// Jason 3 sub-plans: plans that exist only while the enclosing goal runs.
+!emptyDishwasher : dishwasherDoor(open) <- !unloadNext.
{
    +!unloadNext : inDishwasher(C) <- pickUp(C); !putAway(C); !unloadNext.
    +!unloadNext.
    @putAwayPlan[atomic]
    +!putAway(C) <- navigateTo(cupboard); putDown(C).
}

// Sub-plans after a plan with a goal condition and no body.
+!serve(C) : ready(C) <: served(C).
{
    -!serve(C) <- .print("serving ", C, " failed").
}
