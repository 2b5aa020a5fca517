// Case 55 (point 14): .desire and .intend in contexts while other goals are pending: a goal
// posted with !! is desired (an event) before it is intended (a plan for it on a stack);
// the running goals are intended; a goal nobody pursues is neither. Decided by
// jason.stdlib.desire (events and intentions) and jason.stdlib.intend (intentions only).

+!go <- !!bg; !probe(bg); !probe(go); !probe(nothing); !inner; !probe(bg); !!fresh; !sub.

+!bg <- act(b); act(b).

+!probe(G) : .intend(G) <- .print("intend ", G).
+!probe(G) : .desire(G) <- .print("desire ", G).
+!probe(G) <- .print("none ", G).

+!inner : .intend(inner) | .intend(go) & .desire(go) <- act(a).
+!inner <- ping.

// While its own event is being deliberated, a goal posted with !! is desired, not intended;
// a subgoal's event belongs to the intention that posted it, so it is intended too.
+!fresh : .desire(fresh) & not .intend(fresh) <- .print("fresh desired").
+!fresh <- .print("fresh other").
+!sub : .intend(sub) <- .print("sub intended").
+!sub <- .print("sub other").
