; expect: 5:4 a second `(:predicates` section
; expect: 6:36 undefined predicate `r`
; Both sections are still read, so `q` is declared and only `r` is undefined.
(define (domain d) (:predicates (p))
  (:predicates (q))
  (:action a :effect (and (p) (q) (r))))
