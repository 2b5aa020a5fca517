// Covers forks `|&|` (wait for all branches) and `|||` (wait for the first)
// with parenthesised branches, plan terms as body formulas `+{ ... }`,
// `+>{ ... }` and `-{ ... }`, and `{ ... }` plan terms as arguments:
// a plan (`.add_plan({ +b : c <- d })`), a trigger (`.relevant_plans({ +!g }, L)`),
// a body (`{ a; b }`), a rule (`{ p :- q }`), and plan terms with labels
// (`@l`, `@[annots]`, and a variable label inside a term).

// Forks.
+!clearTable
   <- (!storeCup(c1); !storeCup(c2)) |&| (!wipe(table)) |&| !fetchTray;
      !goDishwasher ||| !goCupboard;
      (navigateTo(table) |&| openDoor(dishwasher)) ||| (.wait(5000); timeout).

// Adding and removing plans at run time.
+!learnRinse
   <- +{ +!rinse(C) <- wet(C); scrub(C) };
      +>{ @rinseLast +!rinse(C) : dry(C) <- wet(C) };
      -{ +!rinse(C) <- wet(C); scrub(C) };
      +{ clean(C) :- washed(C) & dried(C) };
      .add_plan({ +cupDropped(C) : holding(none) <- pickUp(C) });
      .add_plan({ @[source(self)] -!storeCup(C) <- .print(C) });
      .relevant_plans({ +!storeCup(_) }, Plans);
      .relevant_plans({ -!storeCup(_) }, _FailPlans);
      .relevant_plans({ ^!storeCup(_) }, _StatePlans);
      .plan_label(P, storeUsed);
      .add_plan({ @L +!cool(C) <- wait(C) }, self, begin);
      Steps = { pickUp(c1); putDown(c1) };
      Empty = {};
      .wait({ +dishwasherDoor(open) });
      .send(helper, tellHow, { +?where(C, shelf) : onShelf(C) });
      .print(Plans, P, Steps, Empty, L).
