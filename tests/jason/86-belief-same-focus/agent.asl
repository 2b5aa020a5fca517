// Case 86: a plan's belief update keeps its focus (Jason's default `sameFocus`,
// TransitionSystem.applyExecInt addBel/delBel): the intention waits in the update's event,
// relevant or not, and the event's plan runs on top of it, in the same intention.
// quiet: a mental note no plan is relevant for still costs its intention a turn of the
// event queue, while another intention acts. fails: a failure in the note's plan is
// handled by the goal below it. last: a note as the last step of a subgoal; the subgoal
// ends after the note's plan. del: `-n` with a relevant plan.

+!quiet <- !!side; act(a); +n(a); act(a); act(a).
+!side <- act(b); act(b); act(b); act(b).

+!fails <- !g; act(c).
+!g <- +m(a); act(a).
-!g <- act(b).
+m(X) <- bad(X); act(X).

+!last <- !h; act(c).
+!h <- act(a); +k(b).
+k(X) <- act(X); act(X).

+!del <- +n(b); act(a); -n(b); act(a).
-n(X) <- act(X); act(c).
