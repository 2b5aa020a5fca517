+!go <- navigateTo(table).
