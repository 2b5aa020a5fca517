// Subgoal summaries (an add-only summary keeps what was true), variables bound in an `if`
// condition (gone after it), a rule with a repeated head variable, a disjunction whose
// binding is read later, a trigger with a constant, `!!`, and mental notes with unbound
// arguments (a deletion with an unbound argument removes only what matches the rest).

same(X, X) :- true.

@reachHere
+!reach(R) : at(A) & same(A, R).

@reachThere
+!reach(R) : at(A) & not same(A, R)
   <- go(A, R).

@prepare
+!prepare(R) : at(R) & unlocked(R) & light(R) & in(I, R) & free
   <- !ensureUnlocked(R);
      take(I, R);
      +seen(I);
      +marked(I, R).

@ensureHere
+!ensureUnlocked(R) : at(R)
   <- unlock(R).

@ensureElsewhere
+!ensureUnlocked(R) : not at(R).

@inspect
+!inspect : free
   <- if (at(X)) {
         .print(X)
      };
      if (light(X)) {
         switch(X)
      }.

@stow
+!stow : (holding(I) | in(I, hall)) & not in(I, lab) & at(R).

// Only the left branch binds I: after `free`, `not in(I, lab)` asks about every item.
@check
+!check : (holding(I) | free) & not in(I, lab).

@checkSplit
+!check : free & in(box, hall) & in(ball, lab).

@checkLab
+!check : free & in(_, lab).

@lightHall
+!lightUp(hall) : not light(hall)
   <- !reach(hall);
      switch(hall).

@alreadyLit
+!lightUp(R) : light(R).

// `-marked(I, _)` removes only I's marks: the `else` branch is unreachable.
@unmark
+!unmark(I) : marked(ball, hall) & I \== ball
   <- -marked(I, _);
      if (marked(ball, hall)) {
         .print(kept)
      } else {
         go(lab, hall)
      }.

@busy
+!busy : at(hall) & seen(I) & in(I, _)
   <- !!inspect;
      -seen(_);
      unlock(hall);
      -+seen(I).
