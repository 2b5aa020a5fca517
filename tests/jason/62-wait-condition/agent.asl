// Case 62 (point 11): `.wait(marked(X) & ready(X))` is tested at every event the agent
// adds, on the beliefs of that moment: marked(b) alone does not satisfy it, marked(a)
// after ready(a) does, and X is bound to a. When the condition holds already (second
// scenario), the intention goes on at once. Decided by stdlib wait.execute
// (`ts.getAg().believes(f, un)`) and WaitEvent.testResumeCondition.

+!go <- !!prep; .wait(marked(X) & ready(X)); act(X).

+!prep <- mark(b); act(c); prepare(a); act(c); mark(a); act(c).
