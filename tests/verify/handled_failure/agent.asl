// The failure of !open (no plan applies with full hands) is handled by -!load: the robot
// puts the cup back down, and the request ends without a goal failure.
+!load(C) : cupAt(C, table) <- navigateTo(table); pickUp(C); !open; navigateTo(dishwasher); putDown(C).
+!open : holding(none) <- navigateTo(dishwasher); openDoor(dishwasher).
-!load(C) : holding(C) <- putDown(C).
