// Case 14 (points 3, 7): `while` loops whose condition reads percepts that the body's actions
// change: the condition is evaluated again, on the beliefs of that cycle, before each
// iteration; the first answer of marked(X) decides which thing is unmarked first. Decided by
// jason.stdlib.loop and the belief base order (DefaultBeliefBase, percepts added by
// Agent.buf).

+!clear <- while (marked(X)) { unmark(X); act(X) }; ping.

+!fill <- while (not marked(b)) { mark(a); mark(b) }; ping.
