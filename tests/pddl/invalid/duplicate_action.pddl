; expect: 6:12 action `wait` is declared twice
(define (domain d)
  (:predicates (idle))
  (:action wait
    :effect (idle))
  (:action wait
    :effect (not (idle))))
