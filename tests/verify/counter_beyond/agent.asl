// A counter that Jason would count on for ever: past `[bounds] numbers` the run leaves the
// finite model. That is a limit of the model, not a failure of the agent: the search is
// incomplete (exit 3), with no goal failure.
count(0).
!tick.
+!tick : count(N) <- -+count(N + 1); !tick.
