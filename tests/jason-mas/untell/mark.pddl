;; The keeper marks each belief it is untold, with who untold it.
(define (domain mark)
  (:requirements :strips :typing)
  (:types tag agent)
  (:constants keeper teller stranger - agent)
  (:predicates (marked ?t - tag ?a - agent))
  (:action mark
    :parameters (?t - tag ?a - agent)
    :precondition (and)
    :effect (marked ?t ?a)))
