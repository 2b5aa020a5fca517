; expect: 5:3 unclosed `(`: expected `)` before the end of the file
(define (domain d) (:predicates (p))
  (:action a :effect (p))

  (:action b :parameters (?x)
    :effect (and (p) (not (p)))
