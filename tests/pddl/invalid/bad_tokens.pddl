; expect: 4:43 invalid variable `?`
; expect: 5:17 invalid name `1st`
; expect: 6:25 expected a variable or a constant, found number `3`
(define (domain d) (:predicates (p ?x) (q ? x))
  (:constants a 1st)
  (:action a :effect (p 3)))
