// expect: 3:34 needs a single literal before `:-`
// A rule in braces has a single literal as its head.
+!learn <- .add_plan({ wipe; dry :- wet }).
