//! The report reader: `merge` and `replay` take any file as a report without a panic
//! (refusing what is not one of bdi-check's reports).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(v) = serde_json::from_str::<serde_json::Value>(text) {
        let _ = bdi_check::commands::merge::merge(&[v.clone()]);
        let _ = bdi_check::commands::merge::merge(&[v.clone(), v]);
    }
    let file =
        std::env::temp_dir().join(format!("bdi-check-fuzz-report-{}.json", std::process::id()));
    if std::fs::write(&file, text).is_ok() {
        let _ = bdi_check::commands::replay::replay(&file, None);
    }
});
