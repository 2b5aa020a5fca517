// included-only: loaded by lib.asl (path relative to lib.asl's folder).

+!wash(C) <- navigateTo(dishwasher); putIn(C); start(dishwasher).
