// A failure plan that fails itself: Jason drops the intention (it does not retry -!load).
+!load(C) : cupAt(C, table) <- navigateTo(table); pickUp(C); !open; navigateTo(dishwasher); putDown(C).
+!open : holding(none) <- navigateTo(dishwasher); openDoor(dishwasher).
-!load(C) : holding(C) <- navigateTo(dishwasher); putDown(C).
