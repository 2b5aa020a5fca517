;; The learner marks the tags it is asked to.
(define (domain mark)
  (:requirements :strips :typing)
  (:types tag)
  (:predicates (marked ?t - tag))
  (:action mark
    :parameters (?t - tag)
    :precondition (and)
    :effect (marked ?t)))
