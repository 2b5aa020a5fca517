// An atom that is no object, a number, and a string as arguments.
+!go <- navigateTo(tabel).
+!wait : dirty(3) <- wipe("table").
