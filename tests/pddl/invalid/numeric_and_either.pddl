; expect: 5:29 numeric comparisons are not supported
; expect: 6:32 `either` types are not supported
; expect: 7:34 numeric effect `increase` is not supported
(define (domain d) (:predicates (p ?x))
  (:action a :precondition (> (fuel) 3))
  (:action b :parameters (?x - (either cup plate)))
  (:action c :effect (and (p c) (increase (total-cost) 1))))
