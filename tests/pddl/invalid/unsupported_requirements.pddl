; expect: 5:26 requirement `:numeric-fluents` is not supported
; expect: 5:43 requirement `:durative-actions` is not supported
; expect: 6:18 unknown requirement `:magic`
(define (domain d)
  (:requirements :strips :numeric-fluents :durative-actions
                 :magic :typing))
