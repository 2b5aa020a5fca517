// Case 80: a plan's sources one by one. A plan added twice (equal plans, two sources)
// stays until its last source is removed, in either order; a plan whose label already
// names the source it is added with holds that source once, so removing it removes the
// plan. Decided by PlanLibrary.add(Plan, Term, boolean) (Pred.addSource on the label) and
// PlanLibrary.remove(Literal, Term) (delSource, then the plan goes when no source is left).

+!go <- .add_plan({ @p1 +!t <- act(a) }, boss);
        .add_plan({ @p1 +!t <- act(a) }, bob);
        .remove_plan(p1, boss); !t;
        .remove_plan(p1, bob); !t.
+!go2 <- .add_plan({ @p2 +!t <- act(b) }, bob);
         .add_plan({ @p2 +!t <- act(b) }, boss);
         .remove_plan(p2, boss); !t;
         .remove_plan(p2, bob); !t.
+!go3 <- .add_plan({ @p3[source(boss)] +!u <- act(b) }, boss);
         !u; .remove_plan(p3, boss); !u.
-!t <- act(c).
-!u <- act(c).
