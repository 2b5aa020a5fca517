//! The front end never panics, whatever the input.
//!
//! Random bytes, random soups of AgentSpeak tokens, and mutations of valid programs go to
//! `parse_agent`, `parse_expr`, `parse_step` and `parse_trigger`; each must return, with every
//! diagnostic pointing inside the text. What `parse_agent` recovers must also print and
//! re-parse to itself (the items it keeps are whole, valid items). Deeply nested input runs
//! in a thread with the default 2 MiB stack, to check that the nesting bound holds where it
//! matters. Runs are deterministic: proptest uses a fixed seed.

use bdi_check::syntax::ast::ClearSpans;
use bdi_check::syntax::parser::{parse_step, parse_trigger};
use bdi_check::syntax::printer::print_agent;
use bdi_check::syntax::{parse_agent, parse_expr, Diagnostic, FileId};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// A fixed seed keeps runs reproducible; `PROPTEST_RNG_SEED` and `PROPTEST_CASES` still
/// override it, to explore further by hand.
fn config(cases: u32) -> Config {
    let mut c = Config::default();
    if matches!(c.rng_seed, RngSeed::Random) {
        c.rng_seed = RngSeed::Fixed(0x05ee_d0a5);
    }
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    c.failure_persistence = None;
    c
}

// ----- the checks ----------------------------------------------------------------------------

fn check_spans(text: &str, diags: &[Diagnostic], what: &str) {
    for d in diags {
        if let Some(s) = d.span {
            let (start, end) = (s.start as usize, s.end as usize);
            assert!(
                start <= end
                    && end <= text.len()
                    && text.is_char_boundary(start)
                    && text.is_char_boundary(end),
                "{what}: diagnostic span {start}..{end} outside the text (length {}): {d:?}\ninput: {text:?}",
                text.len()
            );
        }
    }
}

/// Runs every entry point on `text` and checks what comes back.
fn check(text: &str) {
    let (ast, diags) = parse_agent(FileId(0), text);
    check_spans(text, &diags, "parse_agent");
    if let Err(d) = parse_expr(FileId(0), text) {
        check_spans(text, &d, "parse_expr");
    }
    if let Err(d) = parse_step(FileId(0), text) {
        check_spans(text, &d, "parse_step");
    }
    if let Err(d) = parse_trigger(FileId(0), text) {
        check_spans(text, &d, "parse_trigger");
    }
    // The items that survived error recovery are valid on their own.
    let printed = print_agent(&ast);
    let (back, diags) = parse_agent(FileId(0), &printed);
    assert!(
        diags.is_empty(),
        "the recovered tree prints as invalid text:\n{printed}\n{diags:?}\ninput: {text:?}"
    );
    let (mut a, mut b) = (ast, back);
    a.clear_spans();
    b.clear_spans();
    assert!(
        a == b,
        "the recovered tree does not re-parse to itself:\n{printed}\ninput: {text:?}"
    );
}

// ----- inputs --------------------------------------------------------------------------------

/// A program that uses most of the syntax, for mutation when no corpus is around.
const SAMPLE: &str = r#"// A sample agent.
{ include("lib.asl") }
{ begin namespace(kitchen, local) }
cup(c1)[source(self)].
~dirty(c2).
kitchen::at(table, 1.5e-3).
clean(C) :- washed(C) & not (wet(C) | .count(drop(_), N) & N > 2).
{ end }
!start.
/* block
   comment */
@p1[atomic] +!start : at(table, X) & X >= -1 <: done
   <- .print("hi\n\t\"there\"", 'quoted atom', [1, 2.5 | T]);
      !!go(X ** 2 mod 3 div 1);
      ?at(Y, Z) & Y \== Z;
      +b; +>b(1); ++c; -d; -+e(2); --f;
      X = -(-5) + +3 * (Y - 1);
      L =.. [p, [a], "s"];
      if (X < 3) { a } elif (X == 3) { b; c } else { d };
      while (n(N) & N > 0) { -+n(N - 1) };
      for (.member(M, [1, 2])) { .print(M) };
      (a; b) |&| !c ||| (d |&| e);
      +{ @l[x] +!h(V) : c(V) <- act(V) };
      -{ +!h(_) };
      .add_plan({ p :- q }, self, begin);
      Steps = { a; b };
      Empty = {};
      V::lit(::cur, ns::~x[a | T]).
+!go(_) <- true. { +!sub <- act. @s2 -!sub. }
-?q(A) : A > 0.
^!g[state(S)] <- .print(S).
"#;

/// The `.asl` files under `dir`, recursively (valid and invalid alike: both are good seeds).
fn asl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            asl_files(&path, out);
        } else if path.extension().is_some_and(|x| x == "asl") {
            out.push(path);
        }
    }
}

/// The programs to mutate: the sample, the corpus under `tests/`, and each of them as the
/// printer writes it (a different layout with the same meaning).
fn seeds() -> &'static [String] {
    static SEEDS: OnceLock<Vec<String>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let mut files = Vec::new();
        asl_files(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests"),
            &mut files,
        );
        files.sort();
        let mut texts = vec![SAMPLE.to_string()];
        texts.extend(files.iter().filter_map(|p| std::fs::read_to_string(p).ok()));
        let printed: Vec<String> = texts
            .iter()
            .map(|t| print_agent(&parse_agent(FileId(0), t).0))
            .collect();
        texts.extend(printed);
        texts
    })
}

/// Tokens, keywords and punctuation of AgentSpeak, and a few near misses.
const TOKENS: &[&str] = &[
    "a",
    "p",
    "cup",
    ".print",
    "math.abs",
    "'q a'",
    "X",
    "_",
    "_Y",
    "1",
    "2.5",
    ".5",
    "1e3",
    "\"s\"",
    "\"\\n\"",
    "true",
    "false",
    "not",
    "div",
    "mod",
    "begin",
    "end",
    "if",
    "else",
    "elif",
    "for",
    "while",
    "include",
    "namespace",
    "@",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ".",
    ";",
    ":",
    "+",
    "-",
    "*",
    "/",
    "**",
    "^",
    "!",
    "!!",
    "?",
    "~",
    "<",
    "<=",
    ">",
    ">=",
    "==",
    "\\==",
    "=",
    "=..",
    "|",
    "&",
    "|&|",
    "|||",
    "<-",
    "<:",
    ":-",
    "::",
    "+<",
    "+>",
    "++",
    "-+",
    "--",
    "\n",
    " ",
    "//c\n",
    "/*c*/",
    "'",
    "\"",
    "#",
    "\\",
    "é",
    "\u{0}",
];

fn token_soup() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(prop::sample::select(TOKENS), 0..80),
        prop::bool::ANY,
    )
        .prop_map(|(toks, spaced)| toks.join(if spaced { " " } else { "" }))
}

/// One edit of a text, positions taken modulo its length (in chars).
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Insert(usize, &'static str),
    Swap(usize, usize),
    Duplicate(usize, usize),
    Move(usize, usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let pos = any::<usize>();
    prop_oneof![
        (pos, 1usize..8).prop_map(|(p, n)| Edit::Delete(p, n)),
        (pos, prop::sample::select(TOKENS)).prop_map(|(p, t)| Edit::Insert(p, t)),
        (pos, pos).prop_map(|(a, b)| Edit::Swap(a, b)),
        (pos, 1usize..40).prop_map(|(p, n)| Edit::Duplicate(p, n)),
        (pos, 1usize..40, pos).prop_map(|(p, n, q)| Edit::Move(p, n, q)),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut cs: Vec<char> = text.chars().collect();
    for e in edits {
        let len = cs.len().max(1);
        match *e {
            Edit::Delete(p, n) => {
                let p = p % len;
                let end = (p + n).min(cs.len());
                cs.drain(p.min(cs.len())..end);
            }
            Edit::Insert(p, t) => {
                let p = p % (cs.len() + 1);
                cs.splice(p..p, t.chars());
            }
            Edit::Swap(a, b) => {
                let n = cs.len();
                if n > 0 {
                    cs.swap(a % n, b % n);
                }
            }
            Edit::Duplicate(p, n) => {
                let p = p % len;
                let end = (p + n).min(cs.len());
                if p < end {
                    let slice: Vec<char> = cs[p..end].to_vec();
                    cs.splice(end..end, slice);
                }
            }
            Edit::Move(p, n, q) => {
                let p = p % len;
                let end = (p + n).min(cs.len());
                if p < end {
                    let slice: Vec<char> = cs.drain(p..end).collect();
                    let q = q % (cs.len() + 1);
                    cs.splice(q..q, slice);
                }
            }
        }
    }
    cs.into_iter().collect()
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_ascii(text in "[ -~\n]{0,200}") {
        check(&text);
    }

    #[test]
    fn token_soups(text in token_soup()) {
        check(&text);
    }

    #[test]
    fn mutated_programs(
        seed in any::<prop::sample::Index>(),
        edits in prop::collection::vec(edit(), 1..6),
    ) {
        let seeds = seeds();
        let text = apply(&seeds[seed.index(seeds.len())], &edits);
        check(&text);
    }
}

// ----- deep nesting ----------------------------------------------------------------------------

/// Parses `text` with every entry point in a thread with the default 2 MiB stack, and
/// fails if that takes more than `limit` (hostile input must not be slow either).
fn check_in_small_stack(name: &str, text: String, limit: Duration) {
    let started = Instant::now();
    let handle = std::thread::Builder::new()
        .name(name.to_string())
        .stack_size(2 << 20)
        .spawn(move || check(&text))
        .expect("spawn a parser thread");
    if let Err(e) = handle.join() {
        std::panic::resume_unwind(e);
    }
    let took = started.elapsed();
    assert!(took < limit, "{name}: parsing took {took:?}");
}

#[test]
fn deep_nesting_is_refused_not_fatal() {
    const N: usize = 100_000;
    let rep = |s: &str| s.repeat(N);
    let cases: Vec<(&str, String)> = vec![
        ("parens", rep("(")),
        ("brackets", rep("[")),
        ("braces", rep("{")),
        ("balanced parens", format!("p({}a{}).", rep("("), rep(")"))),
        ("balanced lists", format!("p({}{}).", rep("["), rep("]"))),
        ("mixed", rep("p([{(")),
        ("arguments", format!("{}a", rep("p("))),
        ("annotations", format!("{}a", rep("p["))),
        ("plan terms", format!("p({}).", rep("{ +!g <- "))),
        ("groups in a body", format!("+!g <- {}a.", rep("("))),
        ("groups and plan terms", format!("+!g <- {}a.", rep("({"))),
        ("if statements", format!("+!g <- {}a.", rep("if (c) { "))),
        ("while statements", format!("+!g <- {}a.", rep("while ("))),
        ("blocks", rep("{ begin a } ")),
        ("sub-plans", rep("+!g. { ")),
        ("powers", format!("p({}1).", rep("1 ** "))),
        ("conjunctions", format!("r :- {}a.", rep("a & "))),
        ("disjunctions", format!("r :- {}a.", rep("a | "))),
        ("relations", format!("r :- {}a.", rep("a = "))),
        ("nots", format!("r :- {}a.", rep("not "))),
        ("signs", format!("p({}1).", rep("-"))),
        ("negations", format!("p({}a).", rep("~"))),
        ("namespaces", format!("p({}a).", rep("ns::"))),
        ("forks", format!("+!g <- {}a.", rep("a |&| "))),
        ("sequences", format!("+!g <- {}a.", rep("a; "))),
        ("list tails", format!("p({}X).", rep("[a|"))),
        ("labels", rep("@l[")),
    ];
    for (name, text) in cases {
        check_in_small_stack(name, text, Duration::from_secs(20));
    }
}

/// `+ - * / div mod` are read by loops, not recursion, so their chains escape the nesting
/// bound and build a tree as deep as the chain is long; code that walks the tree recursively
/// then overflows the stack (a derived `Clone` at about 4,000 terms, `Drop` at about 40,000).
#[test]
fn long_operator_chains_are_bounded() {
    const N: usize = 100_000;
    let cases = [
        ("sums", format!("p({}1).", "1 + ".repeat(N))),
        ("products", format!("p({}1).", "X * ".repeat(N))),
        (
            "differences in a list",
            format!("p([{}1]).", "1 - ".repeat(N)),
        ),
    ];
    for (name, text) in cases {
        check_in_small_stack(name, text, Duration::from_secs(20));
    }
}

/// `body_formula` reads `(` by first trying a logical expression, then a group; nested
/// `( ... { ... ( ...` make that backtracking exponential, bounded only by the nesting limit.
/// A few lines of 50 bytes each should not take seconds.
#[test]
fn backtracking_stays_cheap() {
    let line = format!("+!g <- {}a.\n", "((({".repeat(10));
    let text = line.repeat(10);
    check_in_small_stack("backtracking", text, Duration::from_millis(500));
}
