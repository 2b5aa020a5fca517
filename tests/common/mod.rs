//! What the CLI test targets share.

use std::process::{Command, Output};

/// Runs the `bdi-check` binary from the crate root, as a user in a checkout would.
pub fn bdi_check(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bdi-check"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("bdi-check runs")
}
