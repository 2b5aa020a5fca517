(define (domain mark)
  (:requirements :strips :typing)
  (:types tag agent)
  (:constants keeper teller1 teller2 - agent)
  (:predicates (marked ?t - tag ?a - agent))
  (:action mark
    :parameters (?t - tag ?a - agent)
    :precondition (not (marked ?t ?a))
    :effect (marked ?t ?a)))
