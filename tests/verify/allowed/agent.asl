// Seeded defect: nothing opens the dishwasher when the robot holds something.
+!load(C) : cupAt(C, table) <- navigateTo(table); pickUp(C); !open; navigateTo(dishwasher); putDown(C).
+!open : holding(none) <- navigateTo(dishwasher); openDoor(dishwasher).
