// Messages: what bdi-check does not model yet is refused where written; a
// performative Jason does not know is an error.
+!go <- .send(bob, tellHow, P); .send(bob, achieve, rest); .send(bob, inform, going).
+!rest <- .broadcast(askHow, going); .send([bob, ann], achieve, go); .send(bob, achieve, rest, A).
+going <- .send(bob, tell, going, mid1); .send(bob, askOne, going, A, soon); .send(bob, signal, going).
