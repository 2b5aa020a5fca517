// Case 40 (points 3, 10): a `while` over a numeric counter whose condition binds N afresh each
// iteration (count(N) & N < 4), the parity of N choosing the action, and a `for` over .range
// with a comparison. Decided by jason.stdlib.loop (the condition is evaluated with the
// unifier from before the loop), jason.stdlib.range and jason.stdlib.foreach.

count(0).

+!loop <- while (count(N) & N < 4) {
             if (N mod 2 == 0) { act(a) } else { act(b) };
             -+count(N + 1)
          };
          ?count(F); .print("final ", F).

+!loop2 <- for (.range(I, 1, 3)) { if (I >= 2) { act(c) } else { act(a) } }.
