// Less common mistakes: an initial belief about the environment, a mental note used with
// two arities, a goal of the wrong arity in `.desire`, a variable action, an arithmetic
// function as an action (the plan added at run time, a plan term, is no mistake).
robotAt(table).
seen(table).

+!look(L) : seen(L, cup1) & .desire(look(L, L)) <- A = navigateTo(L); A; math.abs(3).
+!learn <- +{ +!g <- navigateTo(table) }.
