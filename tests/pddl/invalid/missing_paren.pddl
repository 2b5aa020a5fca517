; expect: 5:3 unclosed `(`: expected `)` before the next section `(:action`
(define (domain d)
  (:predicates (clean ?x))
  ; the effect's `(and` is not closed
  (:action wash :parameters (?x)
    :effect (and (clean ?x))
  (:action dry :parameters (?x) :effect (not (clean ?x))))
