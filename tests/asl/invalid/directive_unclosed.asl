// expect: 4:1 expected `}` to close the directive
// A directive without its closing brace.
{ include("lib/cupboard.asl")
cup(c1).
