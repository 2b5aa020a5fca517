// Case 78: .intend and .desire see achievement goals only: a plan for the belief event
// +marked(X) does not make marked(X) intended, and the +marked events still queued are
// not desires. Decided by stdlib intend/desire (allIntentions / allDesires over `+!` IMs
// and events, TEType.achieve).

+!go <- markAll; ping.
+marked(X) <- if (.intend(marked(X))) { act(a) } else { act(b) };
              if (.desire(marked(_))) { .print("desire") } else { .print("none") }.
+!marked(X) <- ping.   // never posted: makes marked/1 a goal the queries may ask about
