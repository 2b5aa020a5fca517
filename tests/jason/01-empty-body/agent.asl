// Case 01 (point 1): `<- true` and `: true <- true` are empty bodies. A subgoal whose plan
// body is `true` is achieved at once and the plan that posted it goes on; a request whose plan
// body is `true` just ends. Decided by Jason's parser (as2j.plan_body: the formula `true`
// gives an empty PlanBodyImpl) and TransitionSystem.applyClrInt (the finished intended means
// is popped and the step `!nothing` of the plan below is removed).

+!go <- !nothing; act(a); !also_nothing; act(b).

+!nothing <- true.

+!also_nothing : true <- true.

+!quiet : true <- true.
