; expect: 5:23 `or` is not allowed in an effect
; expect: 6:23 an equality cannot be an effect
; expect: 7:29 `when` is an effect, not a goal description
(define (domain d) (:predicates (p) (q))
  (:action a :effect (or (p) (q)))
  (:action b :effect (= a b))
  (:action c :precondition (when (p) (q))))
