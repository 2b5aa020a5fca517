// expect: 4:1 unterminated block comment
// A block comment that is never closed.
cup(c1).
/* the robot stops reading here
cup(c2).
