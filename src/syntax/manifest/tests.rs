//! Unit tests of the manifest reader: decoding TOML strings byte for byte, and formula spans
//! that point into the TOML text.

use super::spans::decode_raw;
use super::validate::Cx;
use crate::syntax::ast::ExprKind;
use crate::syntax::source::SourceMap;

#[test]
fn decode_maps_escapes_to_their_raw_bytes() {
    let (s, map, end) = decode_raw(r#""a\"b\u00e9c""#).unwrap();
    assert_eq!(s, "a\"béc");
    assert_eq!(map[0], (1, 2));
    assert_eq!(map[1], (2, 4)); // `\"`
    assert_eq!(map[2], (4, 5));
    assert_eq!(map[3], (5, 11)); // both bytes of é come from `\u00e9`
    assert_eq!(map[4], (5, 11));
    assert_eq!(map[5], (11, 12));
    assert_eq!(end, 12);
}

#[test]
fn decode_handles_multiline_and_literal_strings() {
    let (s, map, _) = decode_raw("\"\"\"\nab \\\n   c\"\"\"").unwrap();
    assert_eq!(s, "ab c");
    assert_eq!(map[3], (12, 13));
    let (s, _, _) = decode_raw("'a\\b'").unwrap();
    assert_eq!(s, "a\\b");
    let (s, _, _) = decode_raw("bare_key").unwrap();
    assert_eq!(s, "bare_key");
}

#[test]
fn formula_spans_point_into_the_toml_text_even_with_escapes() {
    let text = "[invariants]\nx = \"p(\\\"s\\\") & q(Y)\"\n";
    let mut map = SourceMap::new();
    let id = map.add("m.toml", "m.toml", text.to_string());
    let mut cx = Cx::new(id, text);
    let root = cx.parse_root().unwrap();
    let inv = cx.invariants(&root);
    assert!(cx.errors.is_empty(), "{:?}", cx.errors);
    let ExprKind::And(_, q) = &inv[0].formula.expr.kind else {
        panic!()
    };
    assert_eq!(map.slice(q.span), "q(Y)");
    assert_eq!(map.slice(inv[0].formula.expr.span), "p(\\\"s\\\") & q(Y)");
}
