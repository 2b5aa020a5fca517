// Case 25 (point 6): an action's effect (mark(a) adds the percept marked(a)) triggers a +marked
// plan; the reaction is a new intention and runs round-robin with the acting intention, one
// step each per cycle, so its act(a)s come between go's act(b)s. When marked(a) holds from
// the start (second scenario), the first perception already posts +marked(a), before the
// request arrives, and mark(a) changes nothing. Decided by Agent.buf (percept events),
// TransitionSystem (one event and one intention step per reasoning cycle; an intention that
// acts waits for the action's feedback, applyProcAct) and the default selectIntention (queue).

+!go <- mark(a); act(b); act(b); act(b).

+marked(X) <- act(X); act(X).
