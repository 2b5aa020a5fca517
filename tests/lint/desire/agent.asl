// `.desire` and `.intend` read the agent's goals, not the state: lint treats each as an
// unconstrained Boolean, the same one wherever the same goal is asked about.
@whenWanted
+!a : .desire(b)
   <- navigateTo(table).

@whenNotWanted
+!a : not .desire(b).

@onlyWhileA
+!b : .intend(a) & .desire(b).
