// Case 10 (point 2): a subgoal with a relevant plan whose context does not hold. Jason posts
// -! for the first goal with a failure plan (-!go(X)), or drops the intention (+!bare).
// Decided by TransitionSystem.applyRelApplPlRule2 -> generateGoalDeletionFromEvent and
// Intention.findEventForFailure.

+!go(X) <- act(X); !sub(X); act(c).

+!sub(X) : marked(X) <- unmark(X).

-!go(X) <- mark(X).

+!bare(X) <- act(X); !sub(X); act(c).
