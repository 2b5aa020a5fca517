// Case 79: .wait({+marked(a)}) wakes on that event only: not on -marked(a), nor on the
// goal event +!marked(a) of the same literal; and when one action's percepts wake two
// waiting intentions, each wakes on its own event. Decided by stdlib wait (WaitEvent:
// the trigger must unify, operator and type included, Trigger.equals / unifies) and
// Agent.brf's events, one per changed belief.

+!go <- !!w; !!marked(a); unmark(a); ping; mark(a); ping.
+!w <- .wait({+marked(a)}); act(b).
+!marked(X) <- act(c).

+!two <- !!w1; !!w2; ping; markAll; ping.
+!w1 <- .wait({+marked(b)}); act(b).
+!w2 <- .wait({+marked(c)}); act(c).
