// Covers the include directive: `{ include("file.asl") }` resolved next to
// this file, an include from a subfolder that itself includes a file relative
// to its own folder, and the two-argument form `{ include("file.asl", ns) }`
// that puts the included items into namespace `ns`.

{ include("lib.asl") }
{ include("parts/drying.asl", dryer) }

!tidyKitchen.

+!tidyKitchen <- !storeCup(c1); !dryer::dryAll.
