// expect: 3:13 internal action (`.print`) cannot be a goal
// `!` must be followed by a goal, not an internal action.
+!greet <- !.print(hello).
