// Case 05 (point 2): the failure plan -!g(D) fails itself (push(D) fails on a locked door).
// Jason then skips the -!g frame and the frames of g and posts -! for the goal beneath:
// -!r(D) handles it, and knock(D) of +!r(D) never runs. Decided by
// Intention.findEventForFailure (the `tevent.isGoal() && !tevent.isAddition()` branch) and
// TransitionSystem.applyClrInt (after -!r ends, pops every frame down to +!r).

+!r(D) <- !g(D); knock(D).

+!g(D) <- unlock(D).

-!g(D) <- push(D).

-!r(D) <- fetchKey; knock(d2).
