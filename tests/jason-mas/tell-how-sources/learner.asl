// Marks a tag when it knows how; says so when it does not.
-!mark_it(T) <- .print("cannot mark ", T).
