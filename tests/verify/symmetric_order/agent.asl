// Which cup the robot takes is the one Jason's query answers first, and queries answer in
// belief order, which names decide: three interchangeable cups whose runs are not
// renamings of each other's (tests/suite/ltl.rs).
+!grab : cupAt(C, table) & holding(none) <- pickUp(C).
// Takes each cup but the last one taken, for ever: two cups take turns.
+!rotate : cupAt(C, table) & not last(C) <- pickUp(C); putDown(C); -+last(C); !rotate.
