// Case 35 (point 9): plans chosen by the source annotation of the goal: the initial goal
// !start posts !clean(c) with source(self); a request is an achievement goal whose source is
// the requester, owner ([requests] from = "owner"). The first relevant plan whose trigger annotations are a subset of the event's is chosen
// ([source(owner)], then [source(self)], then [source(A)] for any other sender). Decided by
// PlanLibrary.getCandidatePlans / Trigger unification with annotations (Literal.subsumes for
// annotation subsets) and, for requests, the source the message or the external goal carries
// (Circumstance.addAchvGoal, or TransitionSystem's handling of an `achieve` message:
// source(Sender)).

!start.

+!start <- !clean(c).

+!clean(R)[source(owner)] <- act(R).
+!clean(R)[source(self)] <- mark(R).
+!clean(R)[source(A)] <- .print("clean from ", A); ping.

+!who(R)[source(A)] <- .print("asked by ", A); act(R).

+!plain(R) <- .print("plain ", R); act(R).
