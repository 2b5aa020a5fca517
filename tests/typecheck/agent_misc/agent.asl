// Less common mistakes: an initial belief about the environment, a mental note used with
// two arities, a goal of the wrong arity in `.desire`, a variable action, an arithmetic
// function as an action, and plans added at run time.
robotAt(table).
seen(table).

+!look(L) : seen(L, cup1) & .desire(look(L, L)) <- A = navigateTo(L); A; math.abs(3).
+!learn <- +{ +!g <- navigateTo(table) }.
