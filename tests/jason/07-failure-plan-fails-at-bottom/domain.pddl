;; A job that needs two steps of preparation (phase p0 -> p1 -> p2) before it can finish.
(define (domain phases)
  (:requirements :strips :typing :negative-preconditions :conditional-effects)
  (:types phase)
  (:constants p0 p1 p2 - phase)
  (:predicates
    (phase ?p - phase)
    (done))

  ;; Conditions are read in the state before the action: one step at a time.
  (:action step :parameters () :precondition (and)
    :effect (and (when (phase p0) (and (phase p1) (not (phase p0))))
                 (when (phase p1) (and (phase p2) (not (phase p1))))))
  (:action finish :parameters () :precondition (phase p2) :effect (done))
  ;; always possible, changes nothing
  (:action cheer :parameters () :precondition (and) :effect (and)))
