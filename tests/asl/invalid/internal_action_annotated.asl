// expect: 3:12 cannot be negated or annotated
// Internal actions cannot have annotations.
+!greet <- .print("hi")[source(self)].
