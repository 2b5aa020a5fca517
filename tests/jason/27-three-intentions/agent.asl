// Case 27 (point 6): three intentions started with !! act three times each; the order of the
// actions shows Jason's round-robin (one step of each intention in turn; an intention that
// acted goes to the back of the queue when its feedback arrives). +!mixed interleaves two
// spawned intentions with its own pings. Decided by TransitionSystem.applySelInt /
// Agent.selectIntention (the queue's head) and applyProcAct (feedback re-queues).

+!go <- !!w(a); !!w(b); !!w(c).

+!w(X) <- act(X); act(X); act(X).

+!mixed <- !!w(a); !!w(b); ping; ping; ping.
