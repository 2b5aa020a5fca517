//! Writes an AST back as Jason text.
