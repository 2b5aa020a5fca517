// Plans for the questions, whose contexts never hold here.
+?q(X) : ready(X) <- true.
+?q(X) : done <- true.
+?p(one) <- true.
