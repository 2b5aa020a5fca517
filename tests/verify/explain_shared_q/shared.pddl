;; `a` deletes `p` when `q` holds; `b` changes nothing.
(define (domain shared)
  (:requirements :strips :negative-preconditions :conditional-effects)
  (:predicates (p) (q) (done))
  (:action a
    :parameters ()
    :precondition (p)
    :effect (when (q) (not (p))))
  (:action b
    :parameters ()
    :precondition ()
    :effect (done)))
