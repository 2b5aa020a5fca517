// Case 89: arithmetic and comparison details as Java runs them: `**`, `mod` and `div` of
// negative numbers, `/` of integers, math functions, 1 == 1.0, string, atom and structure
// order (ArithExpr, NumberTermImpl.toString, Term.compareTo).

+!go <- X = 2 ** 3; Y = -7 mod 3; Z = -7 div 2; W = 10 / 4; V = 10 / 5;
        .print(X, " ", Y, " ", Z, " ", W, " ", V);
        A = math.abs(-3); B = math.round(2.5); C = math.floor(-1.5); D = math.max(3, 4.0);
        .print(A, " ", B, " ", C, " ", D);
        if (1 == 1.0) { .print("eq") } else { .print("ne") };
        if (2 < 10) { .print("lt") };
        if ("b" > "a") { .print("sgt") };
        if (b > a) { .print("agt") };
        if (f(2) > f(10)) { .print("fgt") } else { .print("fle") };
        E = 3 + 4 * 2 - 1; .print(E).
