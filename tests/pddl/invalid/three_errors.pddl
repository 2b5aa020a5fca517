; expect: 7:51 expected a predicate name or a connective such as `and`, found `(clean`
; expect: 10:36 undefined predicate `dirty`
; expect: 11:31 undefined variable `?d`
; Three independent errors: a syntax error in one action, an undefined predicate in
; another, a free variable in a third. All are reported in one run.
(define (domain d) (:predicates (clean ?x))
  (:action broken :parameters (?x) :precondition ((clean ?x)))
  (:action wash
    :parameters (?x)
    :precondition (and (clean ?x) (dirty ?x)))
  (:action dry :effect (clean ?d)))
