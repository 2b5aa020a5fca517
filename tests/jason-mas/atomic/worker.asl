// An ordinary intention and an atomic one from the start.
!plain.
!grab.

+!plain
   <- .print("plain 1");
      step(p1);
      .print("plain 2");
      step(p2);
      .print("plain 3").

// Once chosen, nothing else runs and no event is handled until it ends: its subgoal and
// its belief update come first, its `!!later` waits.
@grab[atomic]
+!grab
   <- .print("grab 1");
      step(g1);
      !sub;
      +noted;
      .print("grab 2");
      !!later;
      step(g2);
      .print("grab 3").

+!sub <- .print("sub 1"); step(g3); .print("sub 2").
+noted <- .print("noted").
+!later <- .print("later").
+done(g1) <- .print("saw g1").

// An atomic plan above an ordinary one: the intention stays atomic (Jason's AI) one
// cycle after it ends, so `outer after inner` runs before any event is handled.
+!outer[source(A)] <- !inner; .print("outer after inner"); .print("outer end").
@inner[atomic]
+!inner <- .print("inner 1"); .print("inner 2").

+!hello[source(A)] <- .print("hello from ", A).
