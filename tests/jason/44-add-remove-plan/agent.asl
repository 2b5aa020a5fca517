// Case 44 (point 11): .add_plan with a fixed plan term, the plan used by a subgoal, then
// .remove_plan by its label; the next !extra has no relevant plan and -!go handles the
// failure. Decided by jason.stdlib.add_plan / remove_plan (PlanLibrary.add / remove, label
// extra[source(self)]).

+!go <- .add_plan({ @extra +!extra <- act(c) });
        !extra;
        .remove_plan(extra);
        !extra;
        ping.

-!go <- act(a).
