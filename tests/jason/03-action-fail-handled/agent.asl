// Case 03 (point 2): an environment action fails (its precondition does not hold), the plan
// fails and the failure plan -!enter(D) runs instead of the rest of the body. Decided by
// TransitionSystem.applyProcAct (action feedback false -> generateGoalDeletion) and
// Intention.findEventForFailure (the top goal has a -! plan).

+!enter(D) <- unlock(D); push(D); knock(D).

-!enter(D) <- knock(D); knock(D).
