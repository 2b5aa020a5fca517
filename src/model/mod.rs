//! The formal model.
