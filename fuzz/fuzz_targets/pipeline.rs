//! The whole pipeline under small bounds: any agent, in the kitchen's world (its PDDL
//! domain and manifest), is loaded, grounded and explored with every dynamic check, and
//! never brings bdi-check down, whatever it says. Seeded with the test corpora's agents.
#![no_main]

use bdi_check::check::explore::Limits;
use bdi_check::check::{verify_with, VerifyOptions};
use bdi_check::model::project::load_project;
use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

/// A project folder with the kitchen's domain and manifest; the agent is the input.
fn project_dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let kitchen = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../specs/kitchen");
        let dir = std::env::temp_dir().join(format!("bdi-check-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        std::fs::copy(kitchen.join("kitchen.pddl"), dir.join("kitchen.pddl")).expect("the domain");
        let manifest =
            std::fs::read_to_string(kitchen.join("bdi-check.toml")).expect("the manifest");
        std::fs::write(
            dir.join("bdi-check.toml"),
            manifest.replace("kitchen.asl", "agent.asl"),
        )
        .expect("the manifest");
        dir
    })
}

fuzz_target!(|agent: &str| {
    let dir = project_dir();
    if std::fs::write(dir.join("agent.asl"), agent).is_err() {
        return;
    }
    let Ok(project) = load_project(dir) else {
        return;
    };
    let limits = Limits {
        max_states: 500,
        max_depth: 40,
        timeout: Some(2.0),
    };
    let opts = VerifyOptions {
        threads: 1,
        ..VerifyOptions::default()
    };
    let _ = verify_with(&project, limits, &opts, |_, _, _| {}, &[]);
});
