; expect: 5:3 section `(:action` is outside `(define ...)`
; expect: 7:1 unexpected `)`: it closes no `(`
(define (domain d) (:predicates (p))
  (:action a :effect (p)))
  (:action b :effect (not (p)))
  ; the extra `)` above closed the domain; `b` is still read
)
