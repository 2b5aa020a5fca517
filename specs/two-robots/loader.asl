// The loader takes cups from the counter into the dishwasher, one at a time: its plan for
// a cup the fetcher asks for is atomic, so while it loads one cup it starts no other (a
// request that comes meanwhile waits in its queue of events, Jason's atomic intention),
// and between requests it is idle.
//
// Three earlier versions failed verify: `.wait({-busy})` in the plan for a second request
// waited forever in the run where the `-busy` event came before the wait began (a
// deadlock), a `not busy` context let two intentions both pass the test before either set
// `busy` (an action failure), and a worker that looked for requests every 500 ms never
// became idle (a livelock).

@load[atomic]
+!load(C)[source(fetcher)]
   <- move(loader, dishwasher);
      openDoor(loader);
      move(loader, counter);
      pick(loader, C);
      move(loader, dishwasher);
      put(loader, C);
      closeDoor(loader);
      move(loader, counter).
