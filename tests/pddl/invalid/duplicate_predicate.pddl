; expect: 5:6 predicate `holding` is declared twice
(define (domain d)
  (:predicates
    (holding ?x)
    (holding ?x ?y)))
