// expect: 3:2 a variable cannot be an initial goal
// A variable cannot be an initial goal.
!Goal.
