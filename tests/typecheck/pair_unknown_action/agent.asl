+!go <- navigateTo(table); pickUp(cup1).
