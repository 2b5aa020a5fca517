// Seeded defect: patrolling never ends (the recursive call is the last step, so Jason's
// tail-recursion optimisation keeps the intention from growing and the states repeat).
+!patrol <- navigateTo(dishwasher); navigateTo(table); !patrol.
