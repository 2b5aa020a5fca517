;; Two rooms, two items, a door to unlock: the smallest domain on which lint's subgoal
;; summaries, `if` scoping, rules and disjunctions make a difference (compared with brute
;; force in tests/suite/lint.rs).
(define (domain depot)
  (:requirements :strips :typing :negative-preconditions :equality :conditional-effects)
  (:types room item)
  (:constants hall - room)
  (:predicates (at ?r - room) (light ?r - room) (unlocked ?r - room)
               (in ?i - item ?r - room) (holding ?i - item) (free))
  (:action go
    :parameters (?from ?to - room)
    :precondition (and (at ?from) (not (= ?from ?to)))
    :effect (and (at ?to) (not (at ?from))))
  (:action unlock
    :parameters (?r - room)
    :precondition (at ?r)
    :effect (unlocked ?r))
  (:action switch
    :parameters (?r - room)
    :precondition (at ?r)
    :effect (and (when (light ?r) (not (light ?r)))
                 (when (not (light ?r)) (light ?r))))
  (:action take
    :parameters (?i - item ?r - room)
    :precondition (and (at ?r) (in ?i ?r) (light ?r) (free) (unlocked ?r))
    :effect (and (holding ?i) (not (in ?i ?r)) (not (free))))
  (:action drop
    :parameters (?i - item ?r - room)
    :precondition (and (at ?r) (holding ?i))
    :effect (and (in ?i ?r) (not (holding ?i)) (free))))
