// Case 28 (points 6, 7): one action (markAll) changes several percepts at once; each change is
// an event (+marked(X)), handled one per cycle in the order Jason's perception added them,
// and each reaction is its own intention; -marked(X) reactions after unmarkAll likewise.
// Decided by Agent.buf (the order of the percept list and of the new/removed beliefs) and
// Circumstance's FIFO event queue.

+!go <- markAll.

+!reset <- unmarkAll.

+marked(X) <- act(X).

-marked(X) <- ping.
