// expect: 7:1 expected `.` to end the belief
// expect: 8:21 `,` or `)`
// expect: 9:2 a variable cannot be an initial goal
// Three independent errors: the parser recovers after each one and
// reports all of them in one run.
cup(c1)
dishwasher(d1).
+!wash(C) <- rinse(C; dry(C).
!G.
+!ok <- fine.
