;; A greeting marks the tag with who asked for it.
(define (domain mark)
  (:requirements :strips :typing)
  (:types tag agent)
  (:constants learner teacher asker - agent)
  (:predicates (marked ?t - tag ?a - agent))
  (:action mark
    :parameters (?t - tag ?a - agent)
    :precondition (and)
    :effect (marked ?t ?a)))
