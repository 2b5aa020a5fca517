// Case 63 (point 11): an intention waiting in `.wait` is dropped by `.drop_intention`
// (stdlib drop_intention.dropInt goes through the pending intentions too), and another is
// ended by `.succeed_goal` of its goal while it waits (succeed_goal.drop, the pending
// intentions last): its plan below goes on. Neither wait ever ends on its own.

+!go <- !!guard; !!sub; .wait({+ready(a)}); act(a).

+!sub <- !inner; act(b).
+!inner <- .wait({+ready(b)}); act(a).

+!guard <- act(c); act(c); .drop_intention(go); .succeed_goal(inner); act(c).
