// As explain_shared_q, with `a` deleting `p` when `q` does not hold: the two initial states
// come in the other order, so a search that shared one state's verdict with the other would
// lose a violation in one of the two projects.
//
// `q`, `a` deletes `p`, so the explanation of `b` gives a context that is no longer believed
// (content-truthful) and the explanation of `a` ends where the context changes; without
// `q`, nothing changes and the explanation of `a` stops short of the body's end
// (content-concise). A search that shares what a user sees across states must still tell
// the two apart (tests/suite/explain_verify.rs, tests/suite/compiled.rs).
+!g : p <- a; b.
