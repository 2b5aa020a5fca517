;; Each asker marks that it started; nothing makes ready or done true.
(define (domain mark)
  (:requirements :strips :typing)
  (:types thing num)
  (:predicates (marked ?x - thing) (ready ?n - num) (done))
  (:action mark
    :parameters (?x - thing)
    :precondition (and)
    :effect (marked ?x)))
