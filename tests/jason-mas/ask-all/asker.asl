// Asks the shelf for all its items and all its tools.
!start.
+!start
   <- .send(shelf, askAll, item(X), L);
      .print("items: ", L);
      .send(shelf, askAll, tool(T), N);
      .print("tools: ", N);
      mark(listed).
