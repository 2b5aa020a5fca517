// included-only: loaded by main.asl, not on its own.
// A plan library for storing cups; it includes a file from a subfolder.

{ include("parts/washing.asl") }

+!storeCup(C) : used(C) <- !wash(C); navigateTo(cupboard); putDown(C).
+!storeCup(_).
