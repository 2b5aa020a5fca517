// expect: 3:17 unknown escape `\q`
// One bad escape is one error: the string still ends at its closing quote.
greeting("hello \q world").
ok.
