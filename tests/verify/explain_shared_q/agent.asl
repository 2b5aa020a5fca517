// The same plan, notes and intentions in two initial states that differ in `q` alone: with
// `q`, `a` deletes `p`, so the explanation of `b` gives a context that is no longer believed
// (content-truthful) and the explanation of `a` ends where the context changes; without
// `q`, nothing changes and the explanation of `a` stops short of the body's end
// (content-concise). A search that shares what a user sees across states must still tell
// the two apart (tests/suite/explain_verify.rs, tests/suite/compiled.rs).
+!g : p <- a; b.
