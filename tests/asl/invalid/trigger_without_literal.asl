// expect: 3:4 expected the trigger's literal
// A trigger needs a literal after `+!`.
+! <- navigateTo(table).
