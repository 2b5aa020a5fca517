//! The manifest and scenario loaders: any TOML (or not) is read or refused, never a panic.
#![no_main]

use bdi_check::syntax::manifest::{parse_manifest, parse_scenario};
use bdi_check::syntax::FileId;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|text: &str| {
    let _ = parse_manifest(FileId(0), text, Path::new("fuzz/bdi-check.toml"));
    let _ = parse_scenario(FileId(0), text, Path::new("fuzz/scenario.toml"));
});
