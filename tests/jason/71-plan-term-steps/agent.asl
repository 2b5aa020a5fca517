// Case 71: the plan-term steps. +{P} adds P at the beginning, +>{P} at the end and -{P}
// removes the plan with P's label (the parser writes them as .add_plan(P, self, begin),
// .add_plan(P, self, end) and .remove_plan(P): AS2JavaParser.jj, body_formula); a plan for
// a belief event added at run time handles the events that come after it; an added plan
// adds another when it runs. A plan term with a label in use fails the step, and since the
// parser builds the call with no place, the failure says code_line(no_code)
// (Literal.addSourceInfoAsAnnots).

+!go <- mark(a);
        +>{ @late +!w <- act(c) };
        +{ @early +!w <- act(b) };
        !w;
        -{ @early +!w };
        !w;
        +{ +marked(X) <- .print("marked ", X) };
        mark(b);
        +{ @maker +!make <- .add_plan({ @made +!made <- act(a) }) };
        !make;
        !made;
        +{ @late +!w <- act(a) }.

-!go[error(E), code_line(L)] <- .print(E, " ", L).
