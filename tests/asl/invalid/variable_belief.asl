// expect: 3:1 a variable cannot be a belief
// A variable cannot be an initial belief.
Cup[source(self)].
