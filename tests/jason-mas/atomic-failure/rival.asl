// Takes the box, then the cup.
!grab.
+!grab <- take(box); .print("rival has the box"); take(cup); .print("rival has the cup").
