+!storeCup(C) : used(C) <- pickUp(C).
