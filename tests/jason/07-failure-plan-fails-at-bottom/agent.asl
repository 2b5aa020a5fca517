// Case 07 (point 2): the failure plan of the bottom goal fails. Jason then posts -!job again
// for the same intention (the -!job frame is skipped, +!job is the bottom frame, and it still
// has a relevant -! plan), so the failure plan runs once more, on top of the first one; here
// the world makes it succeed the second time (step moves p0 -> p1 -> p2). What is left of
// +!job (cheer) after the second -!job ends is decided by TransitionSystem.applyClrInt (it
// pops the failure frames down to the failed goal); the run shows whether cheer runs.
// Decided by Intention.findEventForFailure and TransitionSystem.applyClrInt.

+!job <- finish; cheer.

-!job <- step; finish.
