+!go <- ping.
