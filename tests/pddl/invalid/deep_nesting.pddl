; expect: 4:311 nesting deeper than 64 levels
(define (domain d) (:predicates (p))
  (:action a :precondition
(not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (not (p)))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))
