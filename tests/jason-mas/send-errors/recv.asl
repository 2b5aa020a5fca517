+!g[source(A)] : .my_name(Me) <- greet(Me, A).
