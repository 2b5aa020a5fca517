!go.
+!go <- .broadcast(achieve, g).
+!g[source(A)] <- .print("caster got g from ", A).
