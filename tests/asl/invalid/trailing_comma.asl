// expect: 3:19 expected a term, found `)`
// A comma must be followed by another argument.
at(c1, dishwasher,).
