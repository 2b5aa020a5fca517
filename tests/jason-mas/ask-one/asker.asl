// Asks the seller, synchronously, then asynchronously, and prints what it learns.
!start.

+!start
   <- .send(seller, askOne, price(apple, P1), price(apple, P1));   // from a belief
      .print("apple costs ", P1);
      .send(seller, askOne, price(pear, P2), A2);                 // from a +? plan
      .print("pear: ", A2);
      .send(seller, askOne, stock(plum), A3);                     // nothing answers
      .print("plum: ", A3);
      .send(seller, askOne, discount(D), A4);                     // told by the informer
      .print("discount: ", A4);
      mark(asked);
      !mismatch.

+!mismatch
   <- .send(seller, askOne, price(apple, _), price(apple, free));
      .print("not reached").
-!mismatch[error(E)]
   <- .print("mismatch: ", E);
      .send(seller, askOne, price(apple, _)).                    // the answer comes as a belief

+price(F, P)[source(seller)] <- .print("async: ", F, " costs ", P); mark(async).
