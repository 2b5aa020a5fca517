// Case 50: strong negation in beliefs and contexts: ~happy is a belief of its own, distinct
// from `not happy`; -~happy removes it, +happy adds the positive one, and `not ~p` holds once
// ~p is gone. Decided by Literal (a negated literal, LiteralImpl with type ~) and
// DefaultBeliefBase (~p and p have different predicate indicators).

~happy.
~cold(a).

+!go : ~happy <- act(a); -~happy; +happy; !check.
+!go <- ping.

+!check : happy & not ~happy <- act(b).
+!check <- ping.

+!neg(X) : ~cold(X) <- act(X).
+!neg(X) : not ~cold(X) <- mark(X).
