// expect: 3:1 is never closed
// A `begin` block without `{ end }`.
{ begin namespace(tray, local) }
slots(4).
+!put(C) <- place(C).
