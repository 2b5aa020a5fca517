(define (domain d)
  (:predicates (p ?x))
  (:action a :parameters (?x) :effect (q ?x)))
