; expect: 5:25 undefined predicate `robotat`
(define (domain d)
  (:predicates (robotAt ?l))
  (:action go :parameters (?l)
    :precondition (not (robotat ?l))
    :effect (robotAt ?l)))
