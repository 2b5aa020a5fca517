// Covers namespace directives: `{ begin namespace(n, local) } ... { end }`,
// `{ begin namespace(n) } ... { end }` (a global namespace), the current
// namespace prefix `::p` inside a block, a directive with annotations,
// and references to a namespace's beliefs and goals from outside.

{ begin namespace(tray, local) }
    slots(4).
    ::used(0).
    +!put(C) : ::used(N) & slots(S) & N < S <- place(C); -+::used(N + 1).
    +!put(_) <- .print("tray full").
{ end }

{ begin namespace(shelf) }
    capacity(top, 5).
    // A nested plan library for the shelf.
    +!stack(C) : capacity(top, K) & K > 0 <- putOn(C, top).
{ end }

{ begin namespace(noArgs)[note(empty)] }
{ end }

!shelf::stack(c1).

+!carry(C) <- !tray::put(C); ?shelf::capacity(top, K); .print(K).
