; expect: 6:4 `(:durative-action ...)` is not supported
; expect: 10:4 `(:functions ...)` is not supported
(define (domain d)
  (:requirements :strips)
  (:predicates (clean))
  (:durative-action wash
    :parameters ()
    :duration (= ?duration 10)
    :effect (at end (clean)))
  (:functions (water-used)))
