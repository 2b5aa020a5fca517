// Jason gives failure events error_msg, code and code_src too; bdi-check gives error and
// code_line only, so a plan that asks for the others is refused, not left silently dead.
+!t <- use(a).
-!t[error(action_failed), code_line(L)] <- .print(L).
-!t[error(E), error_msg(M)] <- .print(M).
+!q <- ?nowhere(X).
-!q[code_src(S)] <- ping.
