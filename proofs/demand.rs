//! Algorithm 1 (`demand_over`): on every bounded observed sequence, an explanation is due
//! exactly at the actions whose pair with the previous observation is novel at that point
//! (matches no initial pattern and was not learned before), and `N` grows by exactly those
//! pairs.
//!
//! Observations: the requests `!r(a)`, `!r(b)` and the actions `go(a)`, `go(b)`, `stay`.
//! Initial `N`: any subset of four patterns with shared and free variables. Sequences of up
//! to [`MAX_LEN`] observations. The reference matches patterns on this vocabulary's own
//! description, not with the crate's unification.

use crate::explain::{ExpectedSuccessors, Observation, Pair};
use crate::model::Term;

/// Longest sequence.
pub const MAX_LEN: usize = 6;
/// Observation codes.
pub const OBSERVATIONS: u8 = 5;
/// Initial patterns to choose from.
pub const PATTERNS: usize = 4;

/// An argument of a small observation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Arg {
    None,
    Const(u8),
    Var(u8),
}

/// A small observation: request?, functor, argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Obs {
    request: bool,
    functor: &'static str,
    arg: Arg,
}

const CONSTS: [&str; 2] = ["a", "b"];
const VARS: [&str; 2] = ["C", "L"];

const fn obs(request: bool, functor: &'static str, arg: Arg) -> Obs {
    Obs {
        request,
        functor,
        arg,
    }
}

/// The observed vocabulary, by code.
const SEEN: [Obs; OBSERVATIONS as usize] = [
    obs(true, "r", Arg::Const(0)),
    obs(true, "r", Arg::Const(1)),
    obs(false, "go", Arg::Const(0)),
    obs(false, "go", Arg::Const(1)),
    obs(false, "stay", Arg::None),
];

/// The patterns: `(!r(C), go(C))`, `(go(L), stay)`, `(go(a), go(b))`, `(stay, go(C))`.
const PATTERN: [(Obs, Obs); PATTERNS] = [
    (obs(true, "r", Arg::Var(0)), obs(false, "go", Arg::Var(0))),
    (obs(false, "go", Arg::Var(1)), obs(false, "stay", Arg::None)),
    (
        obs(false, "go", Arg::Const(0)),
        obs(false, "go", Arg::Const(1)),
    ),
    (obs(false, "stay", Arg::None), obs(false, "go", Arg::Var(0))),
];

fn term_of(o: &Obs) -> Term {
    match o.arg {
        Arg::None => Term::atom(o.functor),
        Arg::Const(c) => Term::structure(o.functor, vec![Term::atom(CONSTS[c as usize])]),
        Arg::Var(v) => Term::structure(o.functor, vec![Term::var(VARS[v as usize])]),
    }
}

fn observation(o: &Obs) -> Observation {
    if o.request {
        Observation::Request(term_of(o))
    } else {
        Observation::Action(term_of(o))
    }
}

/// Reference matching of a pattern side against a ground observation, extending `binding`.
fn side_matches(p: &Obs, o: &Obs, binding: &mut [Option<u8>; 2]) -> bool {
    if p.request != o.request || p.functor != o.functor {
        return false;
    }
    match (p.arg, o.arg) {
        (Arg::None, Arg::None) => true,
        (Arg::Const(c), Arg::Const(d)) => c == d,
        (Arg::Var(v), Arg::Const(d)) => match binding[v as usize] {
            Some(b) => b == d,
            None => {
                binding[v as usize] = Some(d);
                true
            }
        },
        _ => false,
    }
}

/// An observed sequence (codes) and the chosen initial patterns (a bitmask).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallRun {
    len: u8,
    seq: [u8; MAX_LEN],
    patterns: u8,
}

impl SmallRun {
    /// The run these codes spell, if canonical: in range, codes past `len` all 0.
    pub fn new(len: u8, seq: [u8; MAX_LEN], patterns: u8) -> Option<SmallRun> {
        let ok = usize::from(len) <= MAX_LEN
            && patterns < 1 << PATTERNS
            && seq.iter().enumerate().all(|(i, &c)| {
                if i < usize::from(len) {
                    c < OBSERVATIONS
                } else {
                    c == 0
                }
            });
        ok.then_some(SmallRun { len, seq, patterns })
    }

    fn seq(&self) -> &[u8] {
        &self.seq[..usize::from(self.len)]
    }

    /// The initial relation `N_0`.
    pub fn initial(&self) -> ExpectedSuccessors {
        ExpectedSuccessors::new(
            (0..PATTERNS)
                .filter(|k| self.patterns >> k & 1 == 1)
                .map(|k| Pair::new(observation(&PATTERN[k].0), observation(&PATTERN[k].1))),
        )
    }

    /// The reference: for each observation, why it is due or not. It is due when it is an
    /// action whose pair with its predecessor matches no chosen pattern and no earlier due
    /// pair.
    pub fn reference(&self) -> Vec<Why> {
        let mut learned: Vec<(Option<u8>, u8)> = Vec::new();
        let mut prev: Option<u8> = None;
        let mut out = Vec::new();
        for &o in self.seq() {
            let next = &SEEN[o as usize];
            let by_pattern = (0..PATTERNS).any(|k| {
                let Some(p) = prev else { return false };
                let mut binding = [None; 2];
                self.patterns >> k & 1 == 1
                    && side_matches(&PATTERN[k].0, &SEEN[p as usize], &mut binding)
                    && side_matches(&PATTERN[k].1, next, &mut binding)
            });
            let why = if next.request {
                Why::Request
            } else if by_pattern {
                Why::Pattern
            } else if learned.contains(&(prev, o)) {
                Why::Learned
            } else {
                learned.push((prev, o));
                Why::Due
            };
            out.push(why);
            prev = Some(o);
        }
        out
    }
}

/// Why an observation is due or not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Why {
    /// Due: a novel pair.
    Due,
    /// A request: never due.
    Request,
    /// An initial pattern matches its pair.
    Pattern,
    /// Its pair was learned earlier in the run.
    Learned,
}

/// Every canonical run of at most `max_len` observations, with every choice of patterns.
pub fn all_runs(max_len: usize) -> Vec<SmallRun> {
    let mut out = Vec::new();
    let mut seqs: Vec<Vec<u8>> = vec![Vec::new()];
    let mut all = seqs.clone();
    for _ in 0..max_len.min(MAX_LEN) {
        seqs = seqs
            .iter()
            .flat_map(|s| {
                (0..OBSERVATIONS).map(move |o| {
                    let mut s = s.clone();
                    s.push(o);
                    s
                })
            })
            .collect();
        all.extend(seqs.iter().cloned());
    }
    for s in &all {
        let mut seq = [0; MAX_LEN];
        seq[..s.len()].copy_from_slice(s);
        for patterns in 0..1 << PATTERNS {
            out.push(SmallRun::new(s.len() as u8, seq, patterns).expect("canonical"));
        }
    }
    out
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// Some action was due.
    pub due: bool,
    /// Some action was not due because a pattern matched it.
    pub by_pattern: bool,
    /// Some action was not due because its pair had been learned earlier in the run.
    pub by_learning: bool,
}

/// The property, with `demand` the kernel (`demand_over`): its verdicts are the
/// reference's; afterwards `N` has its initial patterns unchanged and has learned exactly
/// the pairs `(o_{j-1}, o_j)` (`(start, o_0)` for `j = 0`) of the due `j`s.
pub fn demand_fires_exactly_at_novel_pairs(
    run: &SmallRun,
    demand: impl Fn(&mut ExpectedSuccessors, &[Observation]) -> Vec<bool>,
) -> Result<Seen, String> {
    let seq: Vec<Observation> = run
        .seq()
        .iter()
        .map(|&o| observation(&SEEN[o as usize]))
        .collect();
    let mut n = run.initial();
    let initial = n.initial().to_vec();
    let got = demand(&mut n, &seq);
    let why = run.reference();
    let want: Vec<bool> = why.iter().map(|w| *w == Why::Due).collect();
    let shown = || {
        let s: Vec<String> = seq.iter().map(|o| o.to_string()).collect();
        let p: Vec<String> = initial.iter().map(|p| p.to_string()).collect();
        format!("sequence [{}] with N0 = [{}]", s.join(", "), p.join(", "))
    };
    if got != want {
        return Err(format!(
            "{}: demand gives {got:?}, novelty {want:?}",
            shown()
        ));
    }
    if n.initial() != initial.as_slice() {
        return Err(format!("{}: the initial patterns changed", shown()));
    }
    let mut grown: Vec<Pair> = (0..seq.len())
        .filter(|&j| want[j])
        .map(|j| Pair {
            prev: j.checked_sub(1).map(|i| seq[i].clone()),
            next: seq[j].clone(),
        })
        .collect();
    grown.sort();
    let mut learned = n.learned().to_vec();
    learned.sort();
    if learned != grown {
        let l: Vec<String> = learned.iter().map(|p| p.to_string()).collect();
        let g: Vec<String> = grown.iter().map(|p| p.to_string()).collect();
        return Err(format!(
            "{}: N learned [{}], the due pairs are [{}]",
            shown(),
            l.join(", "),
            g.join(", ")
        ));
    }
    Ok(Seen {
        due: why.contains(&Why::Due),
        by_pattern: why.contains(&Why::Pattern),
        by_learning: why.contains(&Why::Learned),
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// Sequences of up to 6 observations over 5, any subset of 4 initial patterns.
    #[kani::proof]
    #[kani::unwind(8)]
    fn demand_fires_exactly_at_the_novel_pairs() {
        let run = SmallRun::new(kani::any(), kani::any(), kani::any());
        kani::assume(run.is_some());
        let run = run.unwrap();
        let seen = demand_fires_exactly_at_novel_pairs(&run, crate::explain::demand_over);
        kani::cover!(seen.as_ref().is_ok_and(|s| s.due), "an explanation is due");
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.by_learning),
            "a pair learned earlier in the run"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.by_pattern),
            "an action expected by a pattern"
        );
        assert!(seen.is_ok());
    }
}
