(define (domain greet)
  (:requirements :strips :typing)
  (:types agent)
  (:predicates (greeted ?a - agent ?b - agent))
  (:action greet
    :parameters (?a - agent ?b - agent)
    :precondition (and)
    :effect (greeted ?a ?b)))
