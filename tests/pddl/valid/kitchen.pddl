; A kitchen robot that stores used cups in the dishwasher.
; Uses every construct bdi-check supports: typing with inheritance, constants,
; negative preconditions, equality, or, exists, forall, imply, and conditional
; effects with `when` and `forall`.
(define (domain kitchen)
  (:requirements :strips :typing :negative-preconditions :equality
                 :disjunctive-preconditions :existential-preconditions
                 :universal-preconditions :conditional-effects)

  (:types
    location item - object
    container dish - item
    cup plate - dish
    appliance - location
    doorState)

  (:constants
    table floor sink - location
    dishwasher - appliance
    none - item
    open closed - doorState)

  (:predicates
    (robotAt ?l - location)
    (holding ?i - item)
    (cupAt ?c - cup ?l - location)
    (used ?d - dish)
    (clean ?d - dish)
    (dishwasherDoor ?s - doorState)
    (running)
    (reachable ?from ?to - location))

  ; Move between two different, reachable places.
  (:action navigateTo
    :parameters (?to - location)
    :precondition (and (not (robotAt ?to))
                       (exists (?from - location)
                         (and (robotAt ?from) (reachable ?from ?to))))
    :effect (and (robotAt ?to)
                 (forall (?l - location)
                   (when (and (robotAt ?l) (not (= ?l ?to)))
                     (not (robotAt ?l))))))

  (:action pickUp
    :parameters (?c - cup ?l - location)
    :precondition (and (robotAt ?l) (cupAt ?c ?l) (holding none)
                       (or (= ?l table) (= ?l sink)))
    :effect (and (holding ?c) (not (holding none)) (not (cupAt ?c ?l))))

  (:action openDoor
    :parameters (?a - appliance)
    :precondition (and (robotAt ?a) (dishwasherDoor closed) (not (running)))
    :effect (and (dishwasherDoor open) (not (dishwasherDoor closed))))

  (:action closeDoor
    :effect (and (dishwasherDoor closed) (not (dishwasherDoor open)))
    :precondition (and (robotAt dishwasher) (dishwasherDoor open)))

  (:action putInDishwasher
    :parameters (?c - cup)
    :precondition (and (robotAt dishwasher) (holding ?c) (dishwasherDoor open)
                       (imply (used ?c) (not (clean ?c))))
    :effect (and (cupAt ?c dishwasher) (holding none) (not (holding ?c))))

  ; Washing cleans every used dish inside, whatever it is.
  (:action startDishwasher
    :parameters ()
    :precondition (and (dishwasherDoor closed)
                       (forall (?c - cup) (imply (cupAt ?c dishwasher) (used ?c))))
    :effect (and (running)
                 (forall (?c - cup)
                   (when (cupAt ?c dishwasher)
                     (and (clean ?c) (not (used ?c)))))))

  (:action wait
    :parameters ()
    :precondition ()
    :effect ()))
