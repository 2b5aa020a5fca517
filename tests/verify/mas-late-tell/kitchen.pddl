;; The shared kitchen of two robots. Each action names the robot that does it (an agent
;; writes its own name, as a constant of type robot).
(define (domain two-robots)
  (:requirements :strips :typing :negative-preconditions :equality
                 :existential-preconditions :conditional-effects)
  (:types location cup robot doorstate - object)
  (:constants table counter dishwasher - location
              fetcher loader - robot
              open closed - doorstate)
  (:predicates
    (at ?r - robot ?l - location)        ; where each robot is
    (handsFree ?r - robot)
    (holding ?r - robot ?c - cup)
    (cupAt ?c - cup ?l - location)       ; nowhere while held
    (door ?s - doorstate))               ; the dishwasher's door

  (:action move
    :parameters (?r - robot ?to - location)
    :precondition (exists (?from - location) (at ?r ?from))
    :effect (and (at ?r ?to)
                 (forall (?l - location) (when (not (= ?l ?to)) (not (at ?r ?l))))))

  ;; Cups in the dishwasher are reached through an open door.
  (:action pick
    :parameters (?r - robot ?c - cup)
    :precondition (and (handsFree ?r)
                       (exists (?l - location) (and (at ?r ?l) (cupAt ?c ?l)))
                       (imply (cupAt ?c dishwasher) (door open)))
    :effect (and (holding ?r ?c) (not (handsFree ?r))
                 (forall (?l - location) (not (cupAt ?c ?l)))))

  (:action put
    :parameters (?r - robot ?c - cup)
    :precondition (and (holding ?r ?c)
                       (imply (at ?r dishwasher) (door open)))
    :effect (and (not (holding ?r ?c)) (handsFree ?r)
                 (forall (?l - location) (when (at ?r ?l) (cupAt ?c ?l)))))

  (:action openDoor
    :parameters (?r - robot)
    :precondition (and (at ?r dishwasher) (handsFree ?r) (door closed))
    :effect (and (door open) (not (door closed))))

  (:action closeDoor
    :parameters (?r - robot)
    :precondition (and (at ?r dishwasher) (handsFree ?r) (door open))
    :effect (and (door closed) (not (door open)))))
