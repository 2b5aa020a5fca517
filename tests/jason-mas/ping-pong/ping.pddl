(define (domain ping)
  (:requirements :strips :typing :negative-preconditions)
  (:types agent)
  (:predicates (ponged ?a - agent))
  (:action pong
    :parameters (?a - agent)
    :precondition (not (ponged ?a))
    :effect (ponged ?a)))
