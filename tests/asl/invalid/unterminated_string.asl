// expect: 4:19 unterminated string
// expect: 5:8 expected `,` or `)`
// A string that runs to the end of the line.
+!greet <- .print("hello, kitchen).
cup(c1).
