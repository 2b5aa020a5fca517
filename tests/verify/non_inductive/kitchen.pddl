;; The kitchen of the paper's survey: a robot that clears used cups into the dishwasher,
;; runs and unloads the dishwasher, puts clean cups away in the cupboard and wipes the table.
;;
;; Jason's term navigateTo(table) is this domain's (navigateTo table).
(define (domain kitchen)
  (:requirements :strips :typing :negative-preconditions :equality
                 :existential-preconditions :universal-preconditions :conditional-effects)

  (:types location item doorstate - object
          cup nothing - item)

  (:constants table dishwasher cupboard - location
              none - nothing
              open closed - doorstate)

  (:predicates
    (robotAt ?l - location)              ; where the robot is
    (holding ?i - item)                  ; what is in its gripper (none when empty)
    (cupAt ?c - cup ?l - location)       ; where a cup stands (nowhere while held)
    (used ?c - cup)                      ; a used cup needs washing
    (dishwasherDoor ?s - doorstate)      ; open or closed
    (dirty ?l - location))               ; a surface that needs wiping

  ;; The robot moves from where it is (it always is somewhere); moving to where it already
  ;; is changes nothing.
  (:action navigateTo
    :parameters (?to - location)
    :precondition (exists (?from - location) (robotAt ?from))
    :effect (and (robotAt ?to)
                 (forall (?l - location)
                   (when (not (= ?l ?to)) (not (robotAt ?l))))))

  ;; Cups in the dishwasher can only be reached through an open door.
  (:action pickUp
    :parameters (?c - cup)
    :precondition (and (holding none)
                       (exists (?l - location) (and (robotAt ?l) (cupAt ?c ?l)))
                       (imply (cupAt ?c dishwasher) (dishwasherDoor open)))
    :effect (and (holding ?c)
                 (not (holding none))
                 (forall (?l - location) (not (cupAt ?c ?l)))))

  ;; A cup goes where the robot stands; never a used cup into the cupboard.
  (:action putDown
    :parameters (?c - cup)
    :precondition (and (holding ?c)
                       (imply (robotAt dishwasher) (dishwasherDoor open))
                       (imply (robotAt cupboard) (not (used ?c))))
    :effect (and (not (holding ?c))
                 (holding none)
                 (forall (?l - location) (when (robotAt ?l) (cupAt ?c ?l)))))

  ;; Doors need a free hand.
  (:action openDoor
    :parameters (?a - location)
    :precondition (and (= ?a dishwasher) (robotAt dishwasher) (holding none)
                       (dishwasherDoor closed))
    :effect (and (dishwasherDoor open) (not (dishwasherDoor closed))))

  (:action closeDoor
    :parameters (?a - location)
    :precondition (and (= ?a dishwasher) (robotAt dishwasher) (holding none)
                       (dishwasherDoor open))
    :effect (and (dishwasherDoor closed) (not (dishwasherDoor open))))

  ;; A wash cycle (modelled as one step) cleans every cup inside.
  (:action startDishwasher
    :parameters (?a - location)
    :precondition (and (= ?a dishwasher) (robotAt dishwasher) (dishwasherDoor closed))
    :effect (forall (?c - cup) (when (cupAt ?c dishwasher) (not (used ?c)))))

  (:action wipe
    :parameters (?l - location)
    :precondition (and (robotAt ?l) (holding none))
    :effect (not (dirty ?l))))
