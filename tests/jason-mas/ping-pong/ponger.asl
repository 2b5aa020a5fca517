+!ping[source(A)] <- pong(A).
