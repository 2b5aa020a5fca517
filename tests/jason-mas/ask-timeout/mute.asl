// Has a plan for the question that never applies: no answer.
+?q(X) : ready <- X = low.
