; expect: 5:5 expected `:parameters`, `:precondition` or `:effect`, found keyword `:vars`
; expect: 7:21 expected a value after `:effect`, found `)`
(define (domain d) (:predicates (p))
  (:action a
    :vars (?x)
    :effect (p))
  (:action b :effect))
