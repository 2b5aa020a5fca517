// Strong negation: refused on an environment predicate, allowed on a mental note.
+!go : ~robotAt(table) & ~tired <- navigateTo(table); +~tired.
