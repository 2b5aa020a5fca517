// Covers comments: line comments `// ...` and block comments `/* ... */`,
// including block comments spanning lines, comments between tokens, and
// comment markers inside strings (which are not comments).

/* A block comment
   over several lines,
   with * stars ** and / slashes inside. */

cup(c1). // a trailing line comment
cup(/* between tokens */ c2).
/**/ cup(c3).
url("http://kitchen.local/cups // not a comment /* nor this */").

+!g /* before the arrow */ <- // after the arrow
   a; /* between steps */ b.
// last line without a newline at the end of file