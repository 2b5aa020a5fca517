; expect: 6:17 type `cup` is declared twice
; The second `cup` is reported, pointing back at the first.
(define (domain d)
  (:requirements :typing)
  (:types cup - object
          plate cup))
