// included-only: a correct library that the invalid agents may include.
shelf(top).
