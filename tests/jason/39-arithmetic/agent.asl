// Case 39 (point 10): arithmetic + - * / div mod ** and unary minus on a belief's number; the
// results are printed and decide which actions run (N mod 2 == 0, M < 0, an if/elif/else on
// K). `/` is real division (7 / 2 = 3.5), `div` integer division, numbers print without
// ".0" when whole. Decided by ArithExpr (ArithmeticOp), RelExpr and NumberTermImpl.toString.

val(7).

+!calc <- ?val(N);
          if (N mod 2 == 0) { act(a) } else { act(b) };
          X = N * 3 - 1; .print("x=", X);
          Y = N div 2; .print("y=", Y);
          Z = N / 2; .print("z=", Z);
          W = 2 ** 3; .print("w=", W);
          M = -N; .print("m=", M);
          if (M < 0 & X \== 0) { act(c) } else { ping };
          if (N - 7 == 0 & Y * 2 + 1 == N) { mark(a) }.

+!calc2 : val(N) & N > 5 <- -+val(N - 4); ?val(K);
          if (K mod 2 == 0) { act(a) } elif (K > 2) { act(b) } else { act(c) }.
+!calc2 <- ping.
