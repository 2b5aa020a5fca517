// Case 08 (point 2): the bottom goal's failure plan fails once, and a mental note makes the
// second -!job choose another failure plan, which succeeds. Whether the rest of +!job
// (act(a)) runs afterwards is decided, as in case 07, by TransitionSystem.applyClrInt.
// Decided by Intention.findEventForFailure (-!job posted again for the bottom frame),
// TransitionSystem.applyClrInt and plan selection in source order (Agent.selectOption).

+!job <- use(a); act(a).

-!job : not retried <- +retried; use(b).
-!job : retried <- -retried; act(b).
