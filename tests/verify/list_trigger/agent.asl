// `+!state([])` runs at the end of the recursion: it is not a dead plan, though its
// trigger argument is not an object.
+!go <- !state([a, b]).
+!state([]) <- ping.
+!state([H|T]) <- act(H); !state(T).
