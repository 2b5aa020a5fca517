;; The asker marks that it has listed the shelf.
(define (domain mark)
  (:requirements :strips :typing)
  (:types thing item)
  (:predicates (marked ?x - thing))
  (:action mark
    :parameters (?x - thing)
    :precondition (and)
    :effect (marked ?x)))
