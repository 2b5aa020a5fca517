//! The AgentSpeak parser: any text parses without a panic, every diagnostic points inside
//! the text, and what error recovery keeps prints and re-parses to itself.
#![no_main]

use bdi_check::syntax::ast::ClearSpans;
use bdi_check::syntax::parser::{parse_step, parse_trigger};
use bdi_check::syntax::printer::print_agent;
use bdi_check::syntax::{parse_agent, parse_expr, Diagnostic, FileId};
use libfuzzer_sys::fuzz_target;

fn inside(text: &str, diags: &[Diagnostic]) {
    for d in diags {
        if let Some(s) = d.span {
            let (a, b) = (s.start as usize, s.end as usize);
            assert!(
                a <= b && b <= text.len() && text.is_char_boundary(a) && text.is_char_boundary(b)
            );
        }
    }
}

fuzz_target!(|text: &str| {
    let (ast, diags) = parse_agent(FileId(0), text);
    inside(text, &diags);
    for r in [
        parse_expr(FileId(0), text).err(),
        parse_step(FileId(0), text).err(),
        parse_trigger(FileId(0), text).err(),
    ] {
        inside(text, &r.unwrap_or_default());
    }
    let printed = print_agent(&ast);
    let (back, diags) = parse_agent(FileId(0), &printed);
    assert!(
        diags.is_empty(),
        "the recovered tree prints as invalid text:\n{printed}"
    );
    let (mut a, mut b) = (ast, back);
    a.clear_spans();
    b.clear_spans();
    assert!(
        a == b,
        "the recovered tree does not re-parse to itself:\n{printed}"
    );
});
