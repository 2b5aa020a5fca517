(define (domain d) (:requirements :strips :typing) (:types thing)
  (:predicates (rel ?a - thing ?b - thing ?c - thing))
  (:action ping :parameters () :precondition (and) :effect (and)))
