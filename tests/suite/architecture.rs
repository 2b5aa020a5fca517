//! Data flows one way: each stage of `src/` may use only the stages before it.
//!
//! Reads every `.rs` file under `src/`, finds each path into another stage
//! (`crate::stage`, or `bdi_check::stage` in `main.rs`) outside comments, and fails on any
//! that points up the order. Stages on one floor (`smt` and `semantics`, both built on the
//! model) may not use each other either, so no two stages import each other in a circle.

use std::path::{Path, PathBuf};

/// The floors, lowest first. A stage may use the stages of lower floors only.
const FLOORS: &[&[&str]] = &[
    &["syntax"],
    &["model"],
    &["findings"],
    &["smt", "semantics"],
    &["explain"],
    &["check"],
    &["report"],
    &["commands"],
    &["main"],
];

fn floor(stage: &str) -> Option<usize> {
    FLOORS.iter().position(|f| f.contains(&stage))
}

/// The stage a file of `src/` belongs to (`None` for `lib.rs`, which declares them all).
fn stage_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_string_lossy();
    match first.as_ref() {
        "lib.rs" => None,
        "main.rs" => Some("main".into()),
        f => Some(f.trim_end_matches(".rs").to_string()),
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("src/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every stage named after `crate::` (or `bdi_check::`) in the code of `text`, with its
/// line number; comments are left out.
fn uses(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        for prefix in ["crate::", "bdi_check::"] {
            let mut rest = code;
            while let Some(i) = rest.find(prefix) {
                let after = &rest[i + prefix.len()..];
                let name: String = after
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    out.push((n + 1, name));
                }
                rest = &rest[i + prefix.len()..];
            }
        }
    }
    out
}

fn upward_imports(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut bad = Vec::new();
    for f in &files {
        let Some(stage) = stage_of(src, f) else {
            continue;
        };
        let here = floor(&stage)
            .unwrap_or_else(|| panic!("{}: stage `{stage}` is not in FLOORS", f.display()));
        let text = std::fs::read_to_string(f).expect("a source file is readable");
        for (line, used) in uses(&text) {
            if used == stage {
                continue;
            }
            match floor(&used) {
                Some(there) if there < here => {}
                Some(_) => bad.push(format!(
                    "{}:{line}: `{stage}` uses `{used}`, which is not below it",
                    f.display()
                )),
                // Not a stage (e.g. a macro path): nothing to check.
                None => {}
            }
        }
    }
    bad
}

#[test]
fn no_stage_uses_a_stage_above_it_or_beside_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let bad = upward_imports(&src);
    assert!(
        bad.is_empty(),
        "imports against the data flow:\n{}",
        bad.join("\n")
    );
}

#[test]
fn every_stage_folder_is_on_a_floor() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    for f in &files {
        if let Some(stage) = stage_of(&src, f) {
            assert!(
                floor(&stage).is_some(),
                "{}: `{stage}` has no floor",
                f.display()
            );
        }
    }
}

#[test]
fn the_check_sees_an_upward_import() {
    // The checker itself: an import from `model` into `check` must be found.
    // Where tests/common's `temp_dir` puts its folders (and sweeps them once they end).
    let dir = std::env::temp_dir()
        .join("bdi-check-tests")
        .join(std::process::id().to_string())
        .join("arch");
    let model = dir.join("model");
    std::fs::create_dir_all(&model).expect("temp dir");
    std::fs::write(
        model.join("plans.rs"),
        "// crate::check in a comment is fine\nuse crate::syntax::Span;\nuse crate::check::verify;\n",
    )
    .expect("writable");
    std::fs::write(dir.join("lib.rs"), "pub mod report;\n").expect("writable");
    let bad = upward_imports(&dir);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(
        bad[0].ends_with(":3: `model` uses `check`, which is not below it"),
        "{bad:?}"
    );
}
