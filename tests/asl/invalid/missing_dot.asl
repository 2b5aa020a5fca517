// expect: 4:1 expected `.` to end the belief
// A belief without its final dot: the error is at the next item.
cup(c1)
cup(c2).
