// `.wait(1000)` is meant to give !prepare the time to finish, but nothing makes it so: the
// timer may end the wait before `ready(a)` holds, and `use(a)` then fails. The model has no
// clock, so it finds that run; Jason, on a fast machine, would not show it in a test.

+!go <- !!prepare; .wait(1000); use(a).

+!prepare <- act(b); prepare(a).

// Waiting for the event itself is right: `use(a)` runs only once `ready(a)` holds.
+!go2 <- !!prepare; .wait({+ready(a)}); use(a).
