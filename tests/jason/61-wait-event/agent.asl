// Case 61 (point 11): `.wait({+marked(X)})` is woken by the percept event even though no
// plan is relevant for it, binds X, and the intention resumes in the next cycle. The
// second wait has a timeout and nothing it waits for comes: it fails with `wait_timeout`,
// and `-!go` handles that. Decided by stdlib wait (WaitEvent.eventAdded, resume(true) ->
// generateGoalDeletion) and Circumstance.addEvent (listeners hear every event).

+!go <- !!mk; .wait({+marked(X)}); act(X); .wait({+ready(a)}, 20); act(c).

+!mk <- act(b); mark(a); act(b).

-!go[error(E)] <- .print(E); act(c); act(c).
