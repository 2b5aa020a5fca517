; expect: 3:9 this is a PDDL problem, not a domain
; bdi-check reads domains only: objects and initial facts come from the manifest.
(define (problem p1) (:domain kitchen)
  (:objects cup1 - cup)
  (:init (robotAt table))
  (:goal (used cup1)))
