+!go <- navigateTo(dishwasher); navigateTo(table).
