// Knows no greeting of its own: it greets with the plans it is told.
+!bye(W) <- .print("bye of my own to ", W).
