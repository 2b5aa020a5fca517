// agent.asl without `[atomic]`: an inspection may run while the drill is out.
@borrow
+!borrow <- take(drill); use(drill); putBack(drill).

+!inspect <- inspect(drill).
