// expect: 3:2 expected a plan label name or `[`
// A plan label outside a plan term is an atom, not a variable.
@Label +!storeCup(C) <- pickUp(C).
