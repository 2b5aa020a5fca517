// Case 16 (point 3): `for (marked(X))` whose body removes the percepts it iterates over, as
// the kitchen's unloadDishwasher does with cupAt. Jason's `for` takes the answers lazily from
// the belief base while the body runs (jason.stdlib.foreach keeps the iterator of
// LogicalFormula.logicalConsequence; the comment there says the list of all solutions is no
// longer computed first), so what the loop sees depends on DefaultBeliefBase's iteration.

+!clear <- for (marked(X)) { unmark(X) }; ping.

+!clearAll <- for (marked(X)) { !drop(X) }; act(a).

+!drop(X) <- unmark(X); act(X).
