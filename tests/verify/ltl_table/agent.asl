// Wiping is only done when asked; resting walks to the cupboard.
+!wipeTable : dirty(table) <- navigateTo(table); wipe(table).
+!wipeTable : not dirty(table).
+!rest <- navigateTo(cupboard).
