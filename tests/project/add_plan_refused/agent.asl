// .add_plan and .remove_plan are modelled when the plans and labels are written in the step:
// what is known only at run time is refused, each where it is written.
@twice +!go <- .add_plan({ @y +!u <- act(a) }).
@twice +!go <- .remove_plan(y).
+!go : marked(X) <- .add_plan({ @y +!u <- act(X) }).
+!go <- .add_plan(P).
+!go <- .add_plan("+!g <- act(a).").
+!go <- .remove_plan(L).
+!go <- .add_plan({ +!u }, self).
+!go <- .remove_plan(p__3).
+!go <- .add_plan({ @L +!u <- act(a) }).
+!go <- .add_plan([{ @l +!u <- act(a) } | T]).
+!go <- .add_plan({ ^!u <- act(a) }).
+!go <- .add_plan({ @l +!u <- act(a) }, self, B).
+!go <- .add_plan({ @l +!u <- act(a) }, S).
{ include("helper.asl", helpers) }
