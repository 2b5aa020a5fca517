// Tells the shelf of a new item, and of one it already has.
!start.
+!start <- .send(shelf, tell, item(c)); .send(shelf, tell, item(a)).
