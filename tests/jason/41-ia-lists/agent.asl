// Case 41 (point 11): list internal actions and functions as Jason's examples use them:
// .length, .nth (0-based), .concat, .reverse, .sort, .min, .max, .member, .empty, .list and
// math.sum (Jason 3 has no .sum; math.sum is the arithmetic function). Results are printed or
// choose the action. Decided by jason.stdlib.{length,nth,concat,reverse,sort,min,max,member,
// empty,list} and jason.functions.Sum.

+!go <- L = [c, a, b];
        .length(L, N); .print("length ", N);
        .nth(0, L, First); act(First);
        .concat(L, [c], L2); .print(L2);
        .reverse(L, R); .print(R);
        .sort(L, S); .print(S);
        .min(L, Min); act(Min);
        .max(L, Max); act(Max);
        .member(b, L);
        .empty([]);
        .list(L);
        Total = math.sum([1, 2, 3]); .print("sum ", Total);
        .min([4, 2, 8], Low); .print("min ", Low);
        if (.member(a, [b, c])) { ping } else { act(b) };
        if (.empty(L)) { ping } else { act(c) }.
