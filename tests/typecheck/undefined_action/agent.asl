// An action nothing defines is not an error: lint reports it.
+!go <- beep(3); navigateTo(table); say("going"); honk.
