// big/4 over the numbers 0..20 has 194,481 ground atoms: more than lint encodes.
+!go : big(1, 2, 3, 4) <- act(a).
+!go <- +big(1, 2, 3, 4); act(b).
