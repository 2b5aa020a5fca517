// expect: 4:7 unterminated quoted atom
// expect: 6:1 expected a term, found end of file
// A quoted atom may span lines, so an unclosed one swallows the rest of the file.
label('blue cup).
cup(c1).
