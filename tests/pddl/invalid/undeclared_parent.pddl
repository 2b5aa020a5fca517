; expect: 4:17 undefined type `dish`
(define (domain d)
  (:requirements :typing)
  (:types cup - dish))
