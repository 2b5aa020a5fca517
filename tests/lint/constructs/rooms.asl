// Every construct lint encodes: rules (with an output argument), `not` over local
// variables, a disjunction whose binding is read later, `.count`, `\==`, `==`, `=`, test
// goals, `if`, `while`, `!!`, mental notes (`+`, `-`, `-+`), a failure plan and a belief
// trigger.

lit(R) :- light(R).
dark(R) :- not light(R).
somewhere(I, R) :- in(I, R).
somewhere(I, R) :- carrying(I) & at(R).

@fetchHere
+!fetch(I, R) : somewhere(I, R).

@fetchCarried
+!fetch(I, R) : carrying(I) & at(From) & From \== R
   <- go(From, R);
      drop(I, R).

@fetchFar
+!fetch(I, R) : in(I, Where) & at(From) & not (Where == R)
   <- !goto(Where);
      if (dark(Where)) {
         switch(Where)
      };
      take(I, Where);
      !goto(R);
      drop(I, R);
      +visited(Where).

@gotoHere
+!goto(R) : at(R).

@gotoThere
+!goto(R) : at(From) & not at(R)
   <- go(From, R).

@lightsOut
+!lightsOut : .count(light(_), N) & N > 0 & at(R)
   <- while (lit(X) & at(Y)) {
         !goto(X);
         switch(X)
      };
      -+visited(R).

@lightsAlreadyOut
+!lightsOut : not light(_).

@tidy
+!tidy : (in(I, hall) | carrying(I)) & not in(I, lab) & at(R)
   <- ?at(Here);
      X = hall;
      !!lightsOut;
      !fetch(I, lab);
      -visited(X).

@tidyNothing
+!tidy : not somewhere(_, hall) & not carrying(_).

// Defects for lint to find: a dead plan, a shadowed plan, a goal with a coverage gap and
// two overlapping plans.
@tidyOdd
+!tidy : carrying(I) & in(I, _).

@lightsAlsoOut
+!lightsOut : not lit(_) & at(R).

@inspectLit
+!inspect(R) : lit(R) & at(R)
   <- switch(R).

@inspectItem
+!inspect(R) : somewhere(I, R) & .count(in(_, R), N) & N >= 1 & not carrying(I)
   <- !goto(R);
      take(I, R).

-!fetch(I, R) <- .print("could not fetch ", I).

+light(R) : visited(R) <- -visited(R).
