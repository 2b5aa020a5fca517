// Case 46 (point 13): `{ include("lib/common.asl") }` resolved relative to the folder of the
// including file; the included plan takes the place of the directive in the plan library.
// Decided by jason.asSyntax.directives.Include.process (SourcePath.addParentInPath of the
// outer source, then fixPath).

{ include("lib/common.asl") }

+!go <- !helper(a); act(b).
