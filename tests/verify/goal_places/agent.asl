// Goals that fail with no step to blame are located where they are at fault: +!a at its
// plan (none applies), +!b at the request (no plan at all), +!start at the initial goal.
!start.
+!a : marked(b) <- act(a).
+!c <- act(c); act(c).
+!c <- act(b).
