//! The PDDL parser: any text parses or is refused with diagnostics inside the text.
#![no_main]

use bdi_check::syntax::pddl::parse_domain;
use bdi_check::syntax::FileId;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let (_, diags) = parse_domain(FileId(0), text);
    for d in &diags {
        if let Some(s) = d.span {
            assert!(s.start <= s.end && s.end as usize <= text.len());
        }
    }
});
