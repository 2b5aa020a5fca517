// The three plans of one goal, from the most general to the most specific.
@broad      +!tidy(C) : cupAt(C, table) <- navigateTo(table).
@narrower   +!tidy(C) : cupAt(C, table) & used(C) <- navigateTo(table).
@narrowest  +!tidy(C) : cupAt(C, table) & used(C) & robotAt(table) <- navigateTo(table).
@elsewhere  +!tidy(C) : not cupAt(C, table).
