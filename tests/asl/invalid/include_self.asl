// expect: 3:1 includes itself
// A file that includes itself.
{ include("include_self.asl") }
cup(c1).
