// Case 92: `.intend` asked by a step of the intention itself: Jason's intend goes through
// Circumstance.getAllIntentions, which includes the selected intention (C.SI), so a plan
// intends its own goal and the goals below it; a belief plan on the same intention (the
// focus of `+q(c)`) is not the goal q(c).

+!go <- if (.intend(go)) { act(a) } else { act(b) }; !g.
+!g <- if (.intend(go)) { act(a) } else { act(b) }; +q(c).
+q(X) <- if (.intend(q(X))) { act(a) } else { act(b) }; if (.intend(g)) { act(a) } else { act(b) }.
+!q(X) <- act(c).
