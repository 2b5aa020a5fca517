// Case 47 (point 13): `{ include("common.asl") }` found through the source path
// (`source_path = ["lib"]` in the manifest, Jason's aslSourcePath); the included file brings
// an initial belief and a plan. Decided by jason.asSyntax.directives.Include.process
// (SourcePath.fixPath over the agent's folder and the aslSourcePath entries).

{ include("common.asl") }

+!go <- !helper(a); ?target(T); act(T).
