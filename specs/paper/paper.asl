// The running example of Wang, Calandra and Klös, "Effective Explanations for
// Belief-Desire-Intention Robots", exactly as the paper prints its two plans (the paper
// writes the door both as dishwasherDoor(open) and dishwasher(open); this project uses
// dishwasherDoor throughout, and writes the subgoal step +!openDishwasherIfNeed of the
// paper's body as Jason's !openDishwasherIfNeed).
//
// The example has a gap: when the dishwasher door is already open, no plan for
// +!openDishwasherIfNeed is applicable, so the request fails.

// pi_1: storeUsedCup
+!storeCup(C) : used(C)
   <- !openDishwasherIfNeed;
      navigateTo(table);
      pickUp(C);
      navigateTo(dishwasher);
      putDown(C).

// pi_2: openDishwasherIfNeed
+!openDishwasherIfNeed : not dishwasherDoor(open) & holding(none)
   <- navigateTo(dishwasher);
      openDoor(dishwasher).
