// Case 59: .remove_plan removes plans of the agent's own library, whose labels Jason gives
// source(self) when the agent loads (PlanLibrary.add(Plan, boolean)): once @first is gone
// !step falls to @second, and once both are, !step has no relevant plan (error no_relevant).
// A removal with a source the plan does not have, or of a label no plan has, changes nothing
// (PlanLibrary.remove(Literal, Term): delSource, then remove when no source is left).

@first +!step : true <- act(a).
@second +!step <- act(b).

+!go <- !step;
        .remove_plan(first, bob);
        !step;
        .remove_plan(first);
        !step;
        .remove_plan([second, nothing]);
        !step.

-!go[error(E)] <- .print(E); ping.
