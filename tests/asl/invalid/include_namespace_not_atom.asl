// expect: 3:31 the namespace of an `include` must be an atom
// The namespace of an include is an atom, not a string.
{ include("lib/cupboard.asl", "cupboard") }
