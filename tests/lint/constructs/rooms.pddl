;; A robot that carries items between rooms and switches lights: small enough to enumerate
;; every state, used to compare lint with brute force on every construct the encoding has.
(define (domain rooms)
  (:requirements :strips :typing :negative-preconditions :equality :conditional-effects)
  (:types room item)
  (:constants hall - room)
  (:predicates (at ?r - room) (light ?r - room) (in ?i - item ?r - room)
               (carrying ?i - item) (empty))
  (:action go
    :parameters (?from ?to - room)
    :precondition (and (at ?from) (not (= ?from ?to)))
    :effect (and (at ?to) (not (at ?from))))
  (:action switch
    :parameters (?r - room)
    :precondition (at ?r)
    :effect (and (when (light ?r) (not (light ?r)))
                 (when (not (light ?r)) (light ?r))))
  (:action take
    :parameters (?i - item ?r - room)
    :precondition (and (at ?r) (in ?i ?r) (light ?r) (empty))
    :effect (and (carrying ?i) (not (in ?i ?r)) (not (empty))))
  (:action drop
    :parameters (?i - item ?r - room)
    :precondition (and (at ?r) (carrying ?i))
    :effect (and (in ?i ?r) (not (carrying ?i)) (empty))))
