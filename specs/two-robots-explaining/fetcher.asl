// The fetcher of specs/two-robots with the paper's explanation mechanism written in it, as
// specs/kitchen-explaining's robot has it: the owner's expected successors are beliefs
// over observation tokens, the last observation is a belief, and before every environment
// action the fetcher checks the pair; when it is novel it explains itself with
// `explain(Action, Context, Steps)` and learns the pair. The owner watches the fetcher
// only: the loader's actions are no observations of theirs, so the fetcher's own
// bookkeeping is enough, whatever the loader does meanwhile.
//
// Each plan passes its context down to its subgoals (`Ctx`), so an explanation's context is
// the plan's own literals and everything above it (`not p` written `neg(p)`), and the steps
// run up to the one that changes that context.

/* Observation tokens. */

reqToken(cup1, req_clear_cup1).
reqToken(cup2, req_clear_cup2).
pickToken(cup1, pick_cup1).
pickToken(cup2, pick_cup2).
putToken(cup1, put_cup1).
putToken(cup2, put_cup2).

/* What the owner expects (the pairs of the owner in bdi-check.toml, for each cup). */

last(start).
expected(req_clear_cup1, nav_table).
expected(req_clear_cup2, nav_table).
expected(nav_table, pick_cup1).
expected(nav_table, pick_cup2).

/* Clearing a cup from the table: to the counter, where the loader takes it. */

@clearFromTable
+!clear(C) : not cupAt(C, counter)
   <- ?reqToken(C, R);
      -+last(R);
      !fetch(C, [neg(cupAt(C, counter))]);
      !bring(C, [neg(cupAt(C, counter))]);
      .send(loader, achieve, load(C)).

@clearNothing
+!clear(C) : cupAt(C, counter)
   <- ?reqToken(C, R);
      -+last(R).

@fetch
+!fetch(C, Ctx) : cupAt(C, table)
   <- ?pickToken(C, K);
      if (last(P1) & not expected(P1, nav_table)) {
         explain(move(fetcher, table), [cupAt(C, table) | Ctx], [move(fetcher, table), pick(fetcher, C)]);
         +expected(P1, nav_table)
      };
      -+last(nav_table);
      move(fetcher, table);
      if (last(P2) & not expected(P2, K)) {
         explain(pick(fetcher, C), [cupAt(C, table) | Ctx], [pick(fetcher, C)]);
         +expected(P2, K)
      };
      -+last(K);
      pick(fetcher, C).

@bring
+!bring(C, Ctx) : holding(fetcher, C)
   <- ?putToken(C, K);
      if (last(P1) & not expected(P1, nav_counter)) {
         explain(move(fetcher, counter), [holding(fetcher, C) | Ctx], [move(fetcher, counter), put(fetcher, C)]);
         +expected(P1, nav_counter)
      };
      -+last(nav_counter);
      move(fetcher, counter);
      if (last(P2) & not expected(P2, K)) {
         explain(put(fetcher, C), [holding(fetcher, C) | Ctx], [put(fetcher, C)]);
         +expected(P2, K)
      };
      -+last(K);
      put(fetcher, C).
