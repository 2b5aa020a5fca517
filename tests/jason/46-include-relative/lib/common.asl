// Included by ../agent.asl with include("lib/common.asl").
+!helper(X) <- act(X); mark(X).
