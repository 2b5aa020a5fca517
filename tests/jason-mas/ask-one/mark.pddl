;; The asker marks what it has done.
(define (domain mark)
  (:requirements :strips :typing)
  (:types thing fruit cost)
  (:predicates (marked ?x - thing))
  (:action mark
    :parameters (?x - thing)
    :precondition (and)
    :effect (marked ?x)))
