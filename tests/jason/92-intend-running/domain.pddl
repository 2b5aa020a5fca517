;; Things the agent can act on; `two` marks two of them at once (two percepts).
(define (domain things)
  (:requirements :strips :typing)
  (:types thing)
  (:predicates (p ?x - thing))
  (:action act :parameters (?x - thing) :precondition (and) :effect (and))
  (:action two :parameters (?x ?y - thing) :precondition (and) :effect (and (p ?x) (p ?y))))
