// Covers logical expressions in contexts and rules: `&`, `|`, `not`,
// parentheses; relational operators `<`, `<=`, `>`, `>=`, `==`, `\==`, `=`, `=..`;
// arithmetic `+ - * / div mod **` with unary minus and unary plus, Jason's
// precedence (`**` binds tighter than `* / div mod`, which bind tighter than
// `+ -`; the sign belongs to the number, so `-2 ** 2` is `(-2) ** 2`);
// arithmetic functions (`math.abs(X)`) and internal actions in contexts (`.desire(g)`).

capacity(dishwasher, 12).
loaded(dishwasher, 5).
shelf(top, 3).
shelf(bottom, 0).

// `&`, `|`, `not` and parentheses.
canLoad :- dishwasherDoor(open) & (holding(none) | holding(tray)) & not full(dishwasher).
spaceLeft(N) :- capacity(dishwasher, Cap) & loaded(dishwasher, L) & N = Cap - L.
// Every relational operator.
almostFull :- spaceLeft(N) & N < 3.
nearlyEmpty :- spaceLeft(N) & N >= 10.
overloaded :- loaded(dishwasher, L) & capacity(dishwasher, C) & L > C.
halfway :- loaded(dishwasher, L) & L <= 6.
sameShelf(A, B) :- shelf(A, _) & shelf(B, _) & A == B.
otherShelf(A, B) :- shelf(A, _) & shelf(B, _) & A \== B.
functorOf(T, F) :- T =.. [F, _, _].
// Arithmetic with precedence.
score(S) :- S = 1 + 2 * 3 - 4 / 2.               // 1 + (2*3) - (4/2) = 5
slots(S) :- S = 17 div 5 mod 2 + 2 ** 3 ** 2.   // ((17 div 5) mod 2) + 2 ** (3 ** 2)
signs(X) :- X = -2 ** 2 + +3 - -(1 + 1).        // (-2)**2 + 3 + 2
distance(A, B, D) :- D = math.abs(A - B) * 1.5.
rounded(X, Y) :- Y = math.round(X * 100) / 100.

// Internal actions and arithmetic in plan contexts.
+!storeCup(C) : .desire(tidyKitchen) & not .intend(storeCup(_)) <- !doStore(C).
+!loadCups(N) : N > 0 & spaceLeft(S) & (S >= N | N - S < 2) <- load(N).
+!balance(A, B) : math.abs(A - B) <= 1 & not (A == 0 & B == 0) <- .print("balanced").
+!pickShelf : shelf(top, T) & shelf(bottom, B) & T * 2 > B + 1 | .count(cup(_), 0)
   <- .print("top").
