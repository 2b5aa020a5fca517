+!tidy : .length([a, b], N) & N > 1
   <- navigateTo(dishwasher).
