;; Doors that may be locked; one key opens them all.
(define (domain doors)
  (:requirements :strips :typing :negative-preconditions)
  (:types door)
  (:predicates
    (locked ?d - door)
    (open ?d - door)
    (haveKey))

  (:action unlock :parameters (?d - door)
    :precondition (and (locked ?d) (haveKey))
    :effect (not (locked ?d)))
  (:action push :parameters (?d - door)
    :precondition (and (not (locked ?d)) (not (open ?d)))
    :effect (open ?d))
  (:action close :parameters (?d - door)
    :precondition (open ?d)
    :effect (not (open ?d)))
  (:action fetchKey :parameters ()
    :precondition (not (haveKey))
    :effect (haveKey))
  ;; always possible, changes nothing
  (:action knock :parameters (?d - door) :precondition (and) :effect (and)))
