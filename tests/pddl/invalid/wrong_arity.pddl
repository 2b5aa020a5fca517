; expect: 5:48 predicate `cupAt` takes 2 arguments, found 1
; expect: 6:23 predicate `cupAt` takes 2 arguments, found 3
(define (domain d)
  (:predicates (cupAt ?c ?l))
  (:action a :parameters (?c ?l) :precondition (cupAt ?c)
    :effect (and (not (cupAt ?c ?l ?l)))))
