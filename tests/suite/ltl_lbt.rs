//! `Buchi::from_ltl` checked against an independent translation: `lbt` (Debian package
//! `lbt`), another implementation of the same tableau (Gerth, Peled, Vardi, Wolper) by other
//! authors, which writes a generalized Büchi automaton.
//!
//! Formulas are generated with every operator, written once with the crate's constructors
//! and once in lbt's prefix syntax with lbt's own operators (`F`, `G`, `i`, `e`; `W` and
//! `~>` spelled out), so the derived operators are checked too. On random lassos, lbt's
//! automaton, the crate's and the reference semantics (`Ltl::holds_on_lasso`) must agree.
//! Everything is seeded: a failure is reproducible. Without `lbt` installed the test fails
//! and says so, unless `BDI_CHECK_NO_LBT` is set (then it says so on stderr and passes).

use bdi_check::check::buchi::Buchi;
use bdi_check::model::ltl::Ltl;
use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::process::{Command, Stdio};

/// About 2 s in all. With 300 formulas a degeneralization that never carried its counter
/// over (a real mistake to make) still passed; with 1000 it fails.
const FORMULAS: usize = 1000;
const LASSOS_PER_FORMULA: usize = 40;
/// lbt, unoptimized, takes seconds to a minute on some formulas with more temporal
/// operators (automata of thousands of states): those are drawn again.
const MAX_TEMPORAL: usize = 6;

/// The temporal operators of a formula in lbt's syntax.
fn temporal_operators(text: &str) -> usize {
    text.split_whitespace()
        .filter(|t| matches!(*t, "X" | "F" | "G" | "U" | "V"))
        .count()
}

/// xorshift64*: a tiny deterministic generator, enough to draw formulas and words.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 32) % n
    }
}

/// A formula over `p0..p2` of depth at most `depth`: the crate's and lbt's spelling.
fn formula(rng: &mut Rng, depth: u32) -> (Ltl, String) {
    if depth == 0 || rng.below(6) == 0 {
        return match rng.below(8) {
            0 => (Ltl::True, "t".into()),
            1 => (Ltl::False, "f".into()),
            _ => {
                let p = rng.below(3) as u32;
                (Ltl::Prop(p), format!("p{p}"))
            }
        };
    }
    let (a, sa) = formula(rng, depth - 1);
    match rng.below(12) {
        0 => (Ltl::not(a), format!("! {sa}")),
        1 => (Ltl::next(a), format!("X {sa}")),
        2 => (Ltl::eventually(a), format!("F {sa}")),
        3 => (Ltl::always(a), format!("G {sa}")),
        op => {
            let (b, sb) = formula(rng, depth - 1);
            match op {
                4 => (Ltl::and(a, b), format!("& {sa} {sb}")),
                5 => (Ltl::or(a, b), format!("| {sa} {sb}")),
                6 => (Ltl::implies(a, b), format!("i {sa} {sb}")),
                7 => (Ltl::iff(a, b), format!("e {sa} {sb}")),
                8 => (Ltl::until(a, b), format!("U {sa} {sb}")),
                9 => (Ltl::release(a, b), format!("V {sa} {sb}")),
                10 => (Ltl::weak_until(a, b), format!("| U {sa} {sb} G {sa}")),
                _ => (Ltl::leads_to(a, b), format!("G i {sa} F {sb}")),
            }
        }
    }
}

/// An edge condition of lbt's output.
#[derive(Debug)]
enum Gate {
    True,
    False,
    Prop(u32),
    Not(Box<Gate>),
    And(Box<Gate>, Box<Gate>),
    Or(Box<Gate>, Box<Gate>),
}

impl Gate {
    fn holds(&self, letter: u64) -> bool {
        match self {
            Gate::True => true,
            Gate::False => false,
            Gate::Prop(p) => *p < 64 && (letter >> p) & 1 == 1,
            Gate::Not(g) => !g.holds(letter),
            Gate::And(a, b) => a.holds(letter) && b.holds(letter),
            Gate::Or(a, b) => a.holds(letter) || b.holds(letter),
        }
    }
}

/// lbt's generalized Büchi automaton: states by index, each with the acceptance sets it is
/// in (numbered `0..sets`) and its edges.
#[derive(Debug)]
struct Gba {
    sets: usize,
    initial: usize,
    accepting: Vec<BTreeSet<usize>>,
    edges: Vec<Vec<(Gate, usize)>>,
}

/// Reads lbt's output format (its documentation, `/usr/share/doc/lbt/index.html`): the
/// number of states and of acceptance sets, then per state its id, whether it is initial,
/// its sets up to `-1`, its transitions (target id, gate in prefix notation) up to `-1`.
/// With no acceptance set, every state is accepting.
fn parse_gba(text: &str) -> Result<Gba, String> {
    let mut tokens = text.split_whitespace();
    let mut next = || tokens.next().ok_or("unexpected end of lbt's output");
    let number = |t: &str| t.parse::<u64>().map_err(|e| format!("{t:?}: {e}"));
    let n = number(next()?)? as usize;
    let declared_sets = number(next()?)? as usize;
    let mut ids = BTreeMap::new();
    let mut set_ids = BTreeMap::new();
    let mut initial = None;
    let mut accepting = Vec::new();
    let mut raw_edges = Vec::new();
    for index in 0..n {
        ids.insert(number(next()?)?, index);
        if number(next()?)? == 1 {
            initial = Some(index);
        }
        let mut sets = BTreeSet::new();
        loop {
            match next()? {
                "-1" => break,
                t => {
                    let fresh = set_ids.len();
                    sets.insert(*set_ids.entry(number(t)?).or_insert(fresh));
                }
            }
        }
        accepting.push(sets);
        let mut edges = Vec::new();
        loop {
            match next()? {
                "-1" => break,
                t => edges.push((number(t)?, parse_gate(&mut next)?)),
            }
        }
        raw_edges.push(edges);
    }
    // Sets declared but never used are empty: then nothing is accepted, which `sets`
    // larger than every used index says.
    let sets = declared_sets.max(set_ids.len());
    let edges = raw_edges
        .into_iter()
        .map(|es| {
            es.into_iter()
                .map(|(t, g)| ids.get(&t).map(|&i| (g, i)).ok_or(format!("no state {t}")))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Gba {
        sets,
        initial: if n == 0 {
            0
        } else {
            initial.ok_or("no initial state")?
        },
        accepting,
        edges,
    })
}

fn parse_gate<'a>(
    next: &mut impl FnMut() -> Result<&'a str, &'static str>,
) -> Result<Gate, String> {
    Ok(match next()? {
        "t" => Gate::True,
        "f" => Gate::False,
        "!" => Gate::Not(Box::new(parse_gate(next)?)),
        "&" => Gate::And(Box::new(parse_gate(next)?), Box::new(parse_gate(next)?)),
        "|" => Gate::Or(Box::new(parse_gate(next)?), Box::new(parse_gate(next)?)),
        t => match t.strip_prefix('p').map(str::parse::<u32>) {
            Some(Ok(p)) => Gate::Prop(p),
            _ => return Err(format!("unexpected gate token {t:?}")),
        },
    })
}

impl Gba {
    /// Whether some run on `prefix · cycle^ω` visits every acceptance set infinitely often:
    /// a reachable strongly connected component of the product (positions × states) with
    /// an edge inside it whose states cover every set.
    fn accepts_lasso(&self, prefix: &[u64], cycle: &[u64]) -> bool {
        let s = self.edges.len();
        if s == 0 {
            return false;
        }
        let word: Vec<u64> = prefix.iter().chain(cycle).copied().collect();
        let succ = |i: usize| {
            if i + 1 < word.len() {
                i + 1
            } else {
                prefix.len()
            }
        };
        let adj: Vec<Vec<usize>> = (0..word.len() * s)
            .map(|v| {
                let (i, q) = (v / s, v % s);
                self.edges[q]
                    .iter()
                    .filter(|(g, _)| g.holds(word[i]))
                    .map(|&(_, t)| succ(i) * s + t)
                    .collect()
            })
            .collect();
        let start = self.initial;
        let mut reached = vec![false; adj.len()];
        let mut stack = vec![start];
        reached[start] = true;
        while let Some(v) = stack.pop() {
            for &w in &adj[v] {
                if !reached[w] {
                    reached[w] = true;
                    stack.push(w);
                }
            }
        }
        let comp = tarjan(&adj);
        let mut covered: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
        let mut cyclic = BTreeSet::new();
        for v in (0..adj.len()).filter(|&v| reached[v]) {
            covered
                .entry(comp[v])
                .or_default()
                .extend(&self.accepting[v % s]);
            if adj[v].iter().any(|&w| comp[w] == comp[v]) {
                cyclic.insert(comp[v]);
            }
        }
        cyclic.iter().any(|c| covered[c].len() == self.sets)
    }
}

/// Strongly connected components (Tarjan's algorithm, recursive: the products here are
/// small), a component number per node.
fn tarjan(adj: &[Vec<usize>]) -> Vec<usize> {
    struct T<'a> {
        adj: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        comp: Vec<usize>,
        next_index: usize,
        next_comp: usize,
    }
    fn visit(t: &mut T, v: usize) {
        t.index[v] = Some(t.next_index);
        t.low[v] = t.next_index;
        t.next_index += 1;
        t.stack.push(v);
        t.on_stack[v] = true;
        for &w in &t.adj[v] {
            match t.index[w] {
                None => {
                    visit(t, w);
                    t.low[v] = t.low[v].min(t.low[w]);
                }
                Some(iw) if t.on_stack[w] => t.low[v] = t.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(t.low[v]) == t.index[v] {
            while let Some(w) = t.stack.pop() {
                t.on_stack[w] = false;
                t.comp[w] = t.next_comp;
                if w == v {
                    break;
                }
            }
            t.next_comp += 1;
        }
    }
    let n = adj.len();
    let mut t = T {
        adj,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        comp: vec![0; n],
        next_index: 0,
        next_comp: 0,
    };
    for v in 0..n {
        if t.index[v].is_none() {
            visit(&mut t, v);
        }
    }
    t.comp
}

/// lbt's automaton for a formula in its prefix syntax, or `None` when lbt is not installed.
fn lbt(formula: &str) -> Option<String> {
    let mut child = match Command::new("lbt")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return None,
        Err(e) => panic!("cannot run lbt: {e}"),
    };
    child
        .stdin
        .take()
        .expect("lbt's stdin is piped")
        .write_all(format!("{formula}\n").as_bytes())
        .expect("lbt reads its formula");
    let out = child.wait_with_output().expect("lbt runs");
    assert!(
        out.status.success(),
        "lbt failed on {formula:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(String::from_utf8(out.stdout).expect("lbt writes ASCII"))
}

#[test]
fn buchi_agrees_with_lbt() {
    let mut rng = Rng(0x1b7_5eed_c0ff_ee01);
    let mut verdicts = [0usize; 2];
    let mut largest = (0, String::new());
    let mut drawn = 0;
    for _ in 0..FORMULAS {
        let (f, text) = loop {
            drawn += 1;
            let (f, text) = formula(&mut rng, 4);
            if temporal_operators(&text) <= MAX_TEMPORAL {
                break (f, text);
            }
        };
        let Some(out) = lbt(&text) else {
            // As the browser test does without chromium: a missing peer fails, unless the
            // machine says on purpose that it has none.
            assert!(
                std::env::var_os("BDI_CHECK_NO_LBT").is_some(),
                "lbt is not installed (Debian package `lbt`: apt-get install -y lbt); BDI_CHECK_NO_LBT=1 skips this cross-check"
            );
            eprintln!("lbt is not installed (Debian package `lbt`): cross-check skipped");
            return;
        };
        let theirs = parse_gba(&out).unwrap_or_else(|e| panic!("{text}: {e}\n{out}"));
        let ours = Buchi::from_ltl(&f);
        if ours.len() > largest.0 {
            largest = (ours.len(), text.clone());
        }
        for _ in 0..LASSOS_PER_FORMULA {
            let (m, n) = (rng_len(&mut rng, 0), rng_len(&mut rng, 1));
            let prefix: Vec<u64> = (0..m).map(|_| rng.below(8)).collect();
            let cycle: Vec<u64> = (0..n).map(|_| rng.below(8)).collect();
            let holds = f.holds_on_lasso(&prefix, &cycle);
            let word = format!("{prefix:?} ({cycle:?})^w");
            assert_eq!(
                theirs.accepts_lasso(&prefix, &cycle),
                holds,
                "lbt's automaton and the semantics disagree on {text} ({f:?}), {word}:\n{out}"
            );
            assert_eq!(
                ours.accepts_lasso(&prefix, &cycle),
                holds,
                "Buchi::from_ltl and lbt disagree on {text} ({f:?}), {word}:\n{ours:?}\n{out}"
            );
            verdicts[usize::from(holds)] += 1;
        }
    }
    let (accepted, rejected) = (verdicts[1], verdicts[0]);
    eprintln!(
        "{FORMULAS} formulas (of {drawn} drawn), {accepted} lassos accepted, {rejected} rejected"
    );
    eprintln!("largest automaton: {} states ({})", largest.0, largest.1);
    // Generated formulas that were all valid or all unsatisfiable would test little.
    assert!(verdicts
        .iter()
        .all(|&v| v > FORMULAS * LASSOS_PER_FORMULA / 10));
}

/// A length in `min..4`.
fn rng_len(rng: &mut Rng, min: u64) -> u64 {
    min + rng.below(4 - min)
}
