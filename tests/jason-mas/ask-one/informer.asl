// Tells the seller about a discount.
!start.
+!start <- .send(seller, tell, discount(small)).
