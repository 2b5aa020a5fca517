; expect: 5:32 undefined type `cups`
(define (domain d)
  (:requirements :typing)
  (:types cup location)
  (:action a :parameters (?c - cups ?l - location)))
