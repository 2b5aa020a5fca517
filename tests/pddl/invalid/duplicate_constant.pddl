; expect: 5:26 constant `table` is declared twice
(define (domain d)
  (:requirements :typing)
  (:types location)
  (:constants table sink table - location))
