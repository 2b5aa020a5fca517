;; Each step of the worker's job leaves a mark.
(define (domain steps)
  (:requirements :strips :typing)
  (:types stage)
  (:predicates (done ?s - stage))
  (:action step
    :parameters (?s - stage)
    :precondition (and)
    :effect (done ?s)))
