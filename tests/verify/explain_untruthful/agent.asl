// The context says where the robot stands, and the plan's first action moves it: when the
// wipe is explained, `robotAt(cupboard)` is no longer believed (content-truthful).
@wipeFromCupboard
+!wipeTable : robotAt(cupboard) & dirty(table)
   <- navigateTo(table);
      wipe(table).
