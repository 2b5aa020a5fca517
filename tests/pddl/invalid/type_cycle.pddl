; expect: 5:5 type `cup` is its own ancestor
(define (domain d)
  (:requirements :typing)
  (:types
    cup - dish
    dish - item
    item - cup
    location))
