// a send to nobody, with a failure plan that shows the error annotations
!start.
+!start <- .send(nobody, achieve, g).
-!start[error(E), agent_not_found(A)] <- .print("send failed: ", E, " agent_not_found(", A, ")").
