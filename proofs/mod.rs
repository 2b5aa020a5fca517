//! Proofs of the pure kernels: one property per kernel, written once, checked three ways.
//!
//! Each module holds a kernel's property as a plain function over small, array-backed
//! inputs (codes in fixed-size arrays, decoded into the crate's real types inside the
//! property), the kernel under test passed in as a parameter. Three drivers call it:
//!
//! * a Kani harness (`#[cfg(kani)]`, `cargo kani`), with every input `kani::any()`;
//! * an exhaustive small-scope enumeration in the `proofs` test target;
//! * proptest, with a fixed seed, in the same target.
//!
//! The test target also passes deliberately broken kernels and asserts that the property
//! reports a violation, so no property holds vacuously.
//!
//! The modules name the crate's items as `crate::model`, `crate::explain`, ...: compiled into
//! the library (under `cfg(kani)`) that is the library itself; compiled into
//! `tests/proofs.rs`, that file re-exports `bdi_check`'s modules at its root.

pub mod cond;
pub mod content;
pub mod demand;
pub mod effects;
pub mod store;
pub mod symmetry;
pub mod unify;
