;; The asker marks its progress; nothing makes ready true.
(define (domain mark)
  (:requirements :strips :typing)
  (:types thing level)
  (:predicates (marked ?x - thing) (ready))
  (:action mark
    :parameters (?x - thing)
    :precondition (and)
    :effect (marked ?x)))
