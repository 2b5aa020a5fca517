// Case 04 (point 2): an action fails inside the subgoal !enter(D), which has no failure plan;
// the failure goes down the stack to the first goal with a relevant -! plan (-!visit(D)),
// the frames above it are dropped after the failure plan ends, and knock(D) after !enter(D)
// does not run. Decided by Intention.findEventForFailure (walks the stack while
// PlanLibrary.hasCandidatePlan is false) and TransitionSystem.applyClrInt (pops the frames of
// the failed goal once the failure plan finishes).

+!visit(D) <- !enter(D); knock(D).

+!enter(D) <- unlock(D); push(D).

-!visit(D) <- fetchKey; knock(D).
