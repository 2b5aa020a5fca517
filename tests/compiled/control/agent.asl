// Body statements in the combinations whose belief reads are subtle, for the test that
// the compiled reasoning cycle agrees with the reference one (tests/suite/compiled.rs).

// A `for` ends inside a `while` whose condition mentions the loop's variable: the
// condition is tested again without the variable bound.
+!sweep <- while (not done(X)) { for (dirty(X)) { if (X == table) { +done(X) } } }.

// -+ and - with a variable; the binding is used after.
+!mark <- -+last(table); -+last(dishwasher); -last(L); +was(L).

// A subgoal's bindings flow back into the plan that posted it.
+!where <- !locate(P); +at(P).
+!locate(P) <- ?robotAt(P).

// Recursion with Jason's tail-recursion optimisation, acting on the environment.
+!clean : dirty(L) <- navigateTo(L); wipe(L); !clean.
+!clean <- .print(clean).

// A belief event from the environment.
-dirty(L) <- +noticed(L).

// A failing test goal, handled by the failure plan.
+!fail <- ?done(cupboard); +never.
-!fail <- +recovered.

// A new intention next to the one that posted it.
+!spawn <- !!side; +spawned.
+!side <- +sided.

// if / elif / else.
+!choose <- if (dirty(table)) { +a } elif (dirty(dishwasher)) { +b } else { +c }.

// A `while` whose condition binds a variable, with an empty-bodied `for` inside.
+!walk <- while (dirty(L) & not visited(L)) { for (robotAt(R)) { }; +visited(L) }.
