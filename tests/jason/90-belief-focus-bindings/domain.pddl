;; Things the agent can act on; `bad` always fails (its precondition never holds).
(define (domain things)
  (:requirements :strips :typing)
  (:types thing)
  (:predicates (never ?x - thing))
  (:action act :parameters (?x - thing) :precondition (and) :effect (and))
  (:action bad :parameters (?x - thing) :precondition (never ?x) :effect (and)))
