// expect: 3:31 expected `;` or `.` to end the plan
// The goal condition `<:` comes before `<-`, not after the body.
+!wash(C) <- rinse(C); dry(C) <: clean(C).
