// expect: 4:34 wrong place for `;`
// Jason: `;` may follow only a plain belief trigger in braces; a goal trigger
// needs `<-` before its body.
+!g <- .add_plan({ +!h(X) : X > 1; a }).
