// Seeded defect: the cup is picked up without going to where it stands.
+!fetch(C) : cupAt(C, table) <- navigateTo(dishwasher); pickUp(C).
