// Covers terms: atoms, quoted atoms ('Hello world'), variables, the anonymous
// variable `_` and named anonymous variables `_Named`, integers, floats,
// scientific notation (1.5e3, 2E-2, 3.0e+2), strings with escapes,
// lists `[a, b | T]`, lists whose tail is a list, nested lists, empty lists,
// variables with annotations, and empty annotations (`p[]`).

greeting('Hello world').
label(c1, 'Cup #1 (blue)').
weight(c1, 250).
weight(c2, 0.25).
temperature(dishwasher, 1.5e3).
tolerance(2E-2).
offset(3.0e+2, .5).
motto("keep \"every\" cup\tclean\n").
path([table, dishwasher, cupboard]).
shelves([[c1, c2], [c3], []]).
mixed([1, 2.5, "three", four, 'Five', [6 | [7, 8]]]).
empty([]).
plain[].

first([H | _], H).
second([_, S | _Rest], S).
headTail(L, H, T) :- L = [H | T].
joined(A, B, [A, B | []]).
annotated(X) :- X = cup(_Id)[source(_Src)] & Y[source(self)] = X & Y == X.

+!describe(C)
   <- ?weight(C, W);
      .concat("cup ", C, " weighs ", W, " g", Text);
      .print(Text, " \\ done");
      .print('Hello world', [C, W | [extra]]).
