// Seeded defect: tidying walks into the cupboard, which the invariant forbids.
+!tidy <- navigateTo(dishwasher); navigateTo(cupboard); navigateTo(table).
