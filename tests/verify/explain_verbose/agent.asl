// The wipe happens inside a subgoal, which the syntactic test gives no effects: the
// explanation of going to the table runs on to the walk to the cupboard, past the subgoal
// that really changes `dirty(table)` (content-concise).
@wipeAndLeave
+!wipeTable : dirty(table)
   <- navigateTo(table);
      !wipeIt;
      navigateTo(cupboard).

@wipeIt
+!wipeIt : true
   <- wipe(table).
