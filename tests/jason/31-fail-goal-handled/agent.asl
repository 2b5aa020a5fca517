// Case 31 (point 8): .fail_goal(mid) from a plan two levels above mid: mid and the frames
// above it are dropped (Intention.dropGoal), -!mid is posted and handled (ping). Whether +!top
// then goes on with act(c) depends on what Jason does with the step of the running intention
// after the internal action returns (TransitionSystem.applyExecInt removes the current step of
// the frame now on top, +!top's !mid) and on applyClrInt after -!mid. Decided by
// jason.stdlib.fail_goal / succeed_goal.drop (dropIntention, then
// TransitionSystem.findEventForFailure for the dropped goal) and applyClrInt.

+!top <- !mid; act(c).
+!mid <- !low; act(b).
+!low <- act(a); .fail_goal(mid); act(a).
-!mid <- ping.
