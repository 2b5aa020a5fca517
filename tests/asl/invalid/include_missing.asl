// expect: 3:1 cannot include
// The included file does not exist; the error is at the directive.
{ include("no_such_library.asl") }
+!g <- a.
