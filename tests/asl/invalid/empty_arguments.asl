// expect: 3:5 expected a term
// `p()` is not Jason: write `p`.
cup().
