// Wiping is only done when asked; nothing else cleans the table.
+!wipeTable : dirty(table) <- navigateTo(table); wipe(table).
+!wipeTable : not dirty(table).
+!rest <- navigateTo(cupboard).
