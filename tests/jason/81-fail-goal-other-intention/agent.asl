// Case 81: .fail_goal(g) on a goal another intention pursues above its bottom goal, with no
// failure plan for g nor below it: that intention is dropped, and the one that ran
// .fail_goal goes on. With a -!b plan below, the failure event goes there instead. Decided
// by stdlib fail_goal.dropIntention (findEventForFailure finds nothing: Intention.fail,
// return 3, and succeed_goal.drop drops the running intention) and Intention.dropGoal.

+!go <- !!b; ping; ping; .fail_goal(g); act(c).
+!b <- !g; act(b).
+!g <- ping; ping; ping; act(a).

+!go2 <- !!b2; ping; ping; .fail_goal(g2); act(c).
+!b2 <- !g2; act(b).
+!g2 <- ping; ping; ping; act(a).
-!b2 <- mark(b).
