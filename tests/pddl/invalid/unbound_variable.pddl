; expect: 6:56 undefined variable `?l`
; expect: 8:35 undefined variable `?z`
(define (domain d)
  (:predicates (at ?x ?l) (holding ?x))
  (:action pickUp :parameters (?x)
    :precondition (and (exists (?l) (at ?x ?l)) (at ?x ?l))
    :effect (and (holding ?x)
                 (forall (?y) (at ?z ?y)))))
