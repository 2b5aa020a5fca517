;; A few things the agent can act on, mark and prepare.
(define (domain things)
  (:requirements :strips :typing :negative-preconditions :conditional-effects
                 :universal-preconditions)
  (:types thing)
  (:predicates
    (marked ?x - thing)    ; a visible mark on the thing
    (ready ?x - thing))    ; the thing can be used

  ;; Always possible; change nothing (they only show up in the run).
  (:action act :parameters (?x - thing) :precondition (and) :effect (and))
  (:action ping :parameters () :precondition (and) :effect (and))

  ;; Marking is always possible; unmarking needs a mark.
  (:action mark :parameters (?x - thing) :precondition (and) :effect (marked ?x))
  (:action unmark :parameters (?x - thing) :precondition (marked ?x) :effect (not (marked ?x)))
  (:action markAll :parameters () :precondition (and)
    :effect (forall (?x - thing) (marked ?x)))
  (:action unmarkAll :parameters () :precondition (and)
    :effect (forall (?x - thing) (not (marked ?x))))

  ;; Using a thing needs it ready; preparing makes it ready.
  (:action use :parameters (?x - thing) :precondition (ready ?x) :effect (and))
  (:action prepare :parameters (?x - thing) :precondition (not (ready ?x)) :effect (ready ?x)))
