// included-only: loaded by main.asl into namespace `dryer`.

wet(c1).
+!dryAll : wet(C) <- dry(C); -wet(C); !dryAll.
+!dryAll.
