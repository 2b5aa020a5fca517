;; `a` deletes `p` when `q` does not hold; `b` changes nothing.
(define (domain shared)
  (:requirements :strips :negative-preconditions :conditional-effects)
  (:predicates (p) (q) (done))
  (:action a
    :parameters ()
    :precondition (p)
    :effect (when (not (q)) (not (p))))
  (:action b
    :parameters ()
    :precondition ()
    :effect (done)))
