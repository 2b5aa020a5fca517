// Covers body formulas: environment actions, internal actions `.name(...)`,
// `!g`, `!!g`, `?g` (also `?(f & g)`), `+b`, `-b`, `-+b`, `+>b`, `++b`, `--b`,
// `+<b`, constraints `X = expr` and `N > 0`, a variable used as an action,
// a parenthesised group `( a; b )`, and the control statements
// `if (...) {...} elif (...) {...} else {...}`, `while (...) {...}`, `for (...) {...}`.

+!storeCup(C) : cup(C)
   <- navigateTo(table);                 // environment action
      pickUp(C)[hand(left)];             // environment action with an annotation
      .print("picked ", C);              // internal action
      !openDishwasherIfNeed;             // subgoal
      !!logActivity(storeCup(C));        // subgoal in a new intention
      ?at(dishwasher, Where);            // test goal
      ?(holding(C) & not dishwasherDoor(closed));  // test goal on a formula
      +holding(C);                       // add belief
      -holding(none);                    // delete belief
      -+lastCup(C);                      // replace belief
      +>history(C);                      // add at the end of the belief base
      ++carrying(C);                     // add, event in a new intention
      --carrying(none);                  // delete, event in a new intention
      +<seen(C, Where);                  // `+<b` is `+b`
      N = 2 * 3 + 1;                     // constraint (unification)
      N > 0;                             // constraint (test)
      putDown(C).

// A variable as the action: the action is chosen at run time.
+!perform(Action) <- Action; .print("done ", Action).

// A parenthesised group of steps.
+!rinse(C) <- (turnOnTap; wet(C)); turnOffTap.

+!sortCups(Cups)
   <- if (Cups == []) {
         .print("nothing to sort")
      } elif (.length(Cups, 1)) {
         .print("one cup")
      } elif (.length(Cups, N) & N > 10) {
         .print("too many cups");
         !callHuman
      } else {
         .sort(Cups, Sorted);
         +sorted(Sorted)
      }
      .print("sorted").

+!countCups
   <- I = 0;
      while (cup(C) & not counted(C)) {
         +counted(C);
      }
      for (cup(C)) {
         .print("cup ", C);
         if (dirty(C)) { !wash(C) }
      };
      for (.member(X, [1, 2, 3])) {
         .print(X)
      }
      if (true) { .print("done") } else { }
      while (false) { }.
