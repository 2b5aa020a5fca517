// Included by ../agent.asl with include("common.asl"), found through source_path = ["lib"].
target(c).

+!helper(X) : target(T) <- act(X); act(T).
