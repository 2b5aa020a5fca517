// Two items of its own. Nobody asks it to restock: it never holds a tool.
item(a).
item(b).
+!restock <- +tool(a).
