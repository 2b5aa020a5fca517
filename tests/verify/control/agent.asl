// Every body statement and internal action the model checker models, each observable
// through a mental note that the manifest's properties check.

// for: once per answer, with the answer's bindings.
+!clean <- for (dirty(L)) { navigateTo(L); wipe(L); +wiped(L) }.

// if / elif / else with a relation on .count's answer.
+!assess : .count(dirty(_), N) <- if (N > 1) { +busy } elif (N == 1) { +light } else { +quiet }.

// while, then a test goal binding P.
+!walk <- while (not robotAt(cupboard)) { navigateTo(cupboard) }; ?robotAt(P); +visited(P).

// -+ keeps one belief of the predicate.
+!mark <- -+last(table); -+last(dishwasher).

// .succeed_goal ends the subgoal; the plan that posted it goes on.
+!skip <- !sub; +after.
+!sub <- .succeed_goal(sub); +never.

// .fail_goal fails the goal; the failure plan of the goal below handles it.
+!abort <- !doomed; +never.
+!doomed <- .fail_goal(doomed); +never.
-!abort <- +aborted.

// .findall, .member, .length and a constraint.
+!lists <- .findall(L, dirty(L), Ls); .length(Ls, N); N >= 1; .member(X, Ls); +first(X).
-!lists <- +nothing.

// .intend sees the goals of the intention; .drop_desire drops it.
+!outer <- !inner.
+!inner : .intend(outer) <- +intended.
+!drop <- .drop_desire(drop); +never.

// !! starts a new intention; the old one goes on.
+!spawn <- !!side; +spawned.
+!side <- +sided.
