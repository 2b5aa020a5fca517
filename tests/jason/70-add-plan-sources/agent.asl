// Case 70: the sources of added plans. A plan added with source bob stays after
// .remove_plan(b1) (source self) and goes with .remove_plan(b1, bob); a plan equal to one in
// the library (Plan.equals: trigger, context and body, not the label) is not added again,
// the one there gets the new source (PlanLibrary.add(Plan, Term, boolean), plans.indexOf);
// a different plan with a label in use makes .add_plan throw (PlanLibrary.add(Plan,
// boolean)): the step fails with error(internal_action), the plans before it in the list
// being in.

+!go <- .add_plan({ @b1 +!t <- act(a) }, bob);
        !t;
        .remove_plan(b1);
        !t;
        .add_plan({ @other +!t <- act(a) });
        .remove_plan(b1, bob);
        !t;
        .remove_plan(other);
        !t;
        .remove_plan(b1);
        .add_plan([{ @b2 +!t <- act(b) }, { @b2 +!t <- act(c) }]);
        ping.

-!go[error(E)] <- .print(E); !t.
