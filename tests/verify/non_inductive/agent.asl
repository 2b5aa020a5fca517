// A correct library whose invariant is true but not inductive: putDown would break
// `cup_placed` from a state where the cup is both held and on the table, which no run
// reaches (pickUp takes the cup off the table).
+!move(C) : cupAt(C, table) & holding(none) <- pickUp(C); putDown(C).
