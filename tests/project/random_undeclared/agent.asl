// `.random(X)` needs the values to check (`[bounds] random`); the list form does not.
// (`.random` in a context is refused in tests/project/wait_refused.)
+!t <- .random([a, b], X); act(X); .random(R); act(a).
