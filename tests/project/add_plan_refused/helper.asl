// Included into a namespace by agent.asl.
+!helper <- act(b).
