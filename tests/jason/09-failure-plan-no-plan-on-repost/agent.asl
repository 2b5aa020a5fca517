// Case 09 (point 2): the bottom goal's failure plan fails and Jason posts -!job again, but no
// -!job plan is applicable any more (the note `retried` is believed): the intention is dropped
// with -!job as its unhandled failure. Decided by Intention.findEventForFailure (a relevant
// plan is enough to post the event) and TransitionSystem.applyRelApplPlRule2 /
// generateGoalDeletionFromEvent (no applicable plan for a goal deletion: the intention ends).

+!job <- use(a).

-!job : not retried <- +retried; use(b).
