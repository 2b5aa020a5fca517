// Knows the answer.
q(low).
