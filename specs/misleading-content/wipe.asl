// Where the paper's syntactic content test misleads (SPEC §4, `content-covers`).
//
// The robot always goes to the table before wiping it, even when it is there already:
// navigating is idempotent, so this is a common and harmless habit. But navigateTo(table)
// may add robotAt(table), an atom of the context, so the paper's test (Eff± ∩ Γ ≠ ∅) takes
// it for the step that changes the context, and the explanation of going to the table ends
// there: "I go to the table because I am at the table and the table is dirty." The step
// that really changes the context is wipe(table). With `modifies = "semantic"` the content
// runs on to it: "... I want to wipe the table."

@wipeTable
+!wipeTable : robotAt(table) & dirty(table)
   <- navigateTo(table);
      wipe(table).

@tableAlreadyClean
+!wipeTable : not dirty(table).
