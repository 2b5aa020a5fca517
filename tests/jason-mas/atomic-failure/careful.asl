// An ordinary intention, and two atomic ones that take what the rival may take first.
!plain.
!fetch.
!rash.

+!plain
   <- .print("plain 1"); .print("plain 2"); .print("plain 3"); .print("plain 4");
      .print("plain 5"); .print("plain 6"); .print("plain 7"); .print("plain 8").

@fetch[atomic]
+!fetch <- .print("fetch 1"); take(box); .print("fetch 2"); !stow; .print("fetch 3").
-!fetch[error(E)] <- .print("fetch failed: ", E); step(s1); .print("fetch recovered").

// No plan for `shelve`: the failure goes to `-!stow`.
+!stow <- step(s2); !shelve; .print("stowed").
-!stow[error(E)] <- .print("stow failed: ", E).

// No failure plan: the intention is dropped.
@rash[atomic]
+!rash <- .print("rash 1"); take(cup); .print("rash 2").
