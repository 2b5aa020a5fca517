// expect: 3:16 expected a variable or a list after `|`
// The tail of a list must be a variable or a list.
cups([c1, c2 | c3]).
