// expect: 3:21 expected a term
// `<-` must be followed by a body.
+!openDishwasher <- .
