// Case 58: a plan added with .add_plan(P, self, begin) goes before the agent's own plan for
// the same goal and is chosen first when applicable; added at the end (the default) it comes
// after it; .remove_plan takes each away again. Decided by jason.stdlib.add_plan (the
// position argument) and PlanLibrary.add(Plan, boolean) (plans.add(0, p) and the trigger's
// list codesList.add(0, p)).

+!go <- .add_plan({ @late +!work <- act(c) });
        !work;
        .add_plan({ @quick +!work : marked(b) <- act(b) }, self, begin);
        !work;
        .remove_plan(quick);
        !work;
        .remove_plan(late);
        !work.

+!work : marked(a) <- act(a).

-!go <- ping.
