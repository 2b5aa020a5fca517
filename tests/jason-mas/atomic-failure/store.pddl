;; Items free to take, taken once; steps leave marks.
(define (domain store)
  (:requirements :strips :typing)
  (:types item stage)
  (:predicates (free ?i - item) (held ?i - item) (done ?s - stage))
  (:action take
    :parameters (?i - item)
    :precondition (free ?i)
    :effect (and (held ?i) (not (free ?i))))
  (:action step
    :parameters (?s - stage)
    :precondition (and)
    :effect (done ?s)))
