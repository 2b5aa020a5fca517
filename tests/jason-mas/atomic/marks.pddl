;; Each step leaves a mark.
(define (domain marks)
  (:requirements :strips :typing)
  (:types stage)
  (:predicates (done ?s - stage))
  (:action step
    :parameters (?s - stage)
    :precondition (and)
    :effect (done ?s)))
