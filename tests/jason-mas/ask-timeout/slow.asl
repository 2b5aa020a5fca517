// Works the answer out, slowly.
+?q(X) <- .wait(300); X = high.
