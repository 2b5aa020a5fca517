// Plans added and removed at run time (`.add_plan`, `.remove_plan`): lint judges a plan by
// the libraries it may be in. @s2 and @late are hidden by @s1, which is always there and
// before them; @h2 is not hidden by @h1, which `!setup` removes, nor @early by anything (it
// goes first); `!g` has a gap whatever is added; whether `!h` has one depends on the runs.

@s1 +!k <- act(a).
@s2 +!k : ready(b) <- act(b).
@h1 +!h <- act(a).
@h2 +!h : ready(a) <- act(b).
+!g : ready(a) <- act(a).

+!setup <- .add_plan({ @quick +!g : marked(a) <- act(b) }, self, begin);
           .add_plan({ @late +!k <- act(c) });
           .add_plan({ @early +!k : marked(b) <- act(c) }, self, begin);
           .add_plan({ @never +!k : marked(c) & not marked(c) <- act(c) });
           .remove_plan(h1).
