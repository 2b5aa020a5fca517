// Borrowing the drill takes it out of the rack for three steps, and an inspection needs
// it in the rack. `[atomic]` keeps the three steps together: once the borrowing starts, no
// other intention runs until the drill is back, so every inspection finds it there.
@borrow[atomic]
+!borrow <- take(drill); use(drill); putBack(drill).

+!inspect <- inspect(drill).
