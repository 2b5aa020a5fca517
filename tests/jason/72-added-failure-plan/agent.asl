// Case 72: plans added at run time take part in failure handling and in test goals: a
// -!attempt plan added by .add_plan handles the next failure of !attempt
// (Intention.findEventForFailure asks the library as it is then), and once a +?where(c) plan
// is added, ?where(c) with no answer posts +?where(c) (TransitionSystem.applyExecInt, test
// goal with a relevant plan).

+!go <- !attempt;
        .add_plan({ -!attempt <- act(b) });
        !attempt;
        .add_plan({ +?where(c) <- act(c) });
        ?where(c);
        ping.

+!attempt <- unmark(a).

-!go <- act(a).
