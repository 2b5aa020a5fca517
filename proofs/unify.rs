//! Unification (`crate::model::unifier`): a unifier it returns makes both terms equal and is
//! most general; it returns none only when no unifier exists.
//!
//! Terms are built over the constants `a`, `b`, the variables `X`, `Y`, and the functors
//! `f/1`, `g/2`, to depth 2: a term is a heap-ordered tree of [`NODES`] codes (node `i` has
//! children `2i+1` and `2i+2`). "No unifier exists" is checked against every ground
//! substitution `θ` of `X` and `Y` by ground terms of depth at most 2 (the Kani harness
//! leaves `θ` symbolic); the same `θ`s check that the returned `σ` is most general
//! (`θ(σ(v)) = θ(v)` for every unifier `θ`).

use crate::model::{Substitution, Term};

/// Nodes of a term of depth at most 2.
pub const NODES: usize = 7;
/// Node codes: `a`, `b`, `X`, `Y`, `f(_)`, `g(_,_)`.
pub const CODES: u8 = 6;
const A: u8 = 0;
const B: u8 = 1;
const X: u8 = 2;
const Y: u8 = 3;
const F: u8 = 4;
const G: u8 = 5;

/// A term of depth at most 2, as node codes; unused nodes are 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallTerm {
    nodes: [u8; NODES],
}

impl SmallTerm {
    /// The term these codes spell, if they are canonical: codes in range, compound nodes
    /// above depth 2 only, unused nodes 0.
    pub fn new(nodes: [u8; NODES]) -> Option<SmallTerm> {
        let used = used_nodes(&nodes);
        for i in 0..NODES {
            let c = nodes[i];
            let ok = if used[i] {
                c < CODES && (i < 3 || c < F)
            } else {
                c == 0
            };
            if !ok {
                return None;
            }
        }
        Some(SmallTerm { nodes })
    }

    /// Whether the term has no variable.
    pub fn is_ground(&self) -> bool {
        let used = used_nodes(&self.nodes);
        (0..NODES).all(|i| !used[i] || (self.nodes[i] != X && self.nodes[i] != Y))
    }

    /// The depth (0 for a constant or a variable).
    pub fn depth(&self) -> usize {
        match self.nodes[0] {
            F | G => {
                let deep = (1..3).any(|i| matches!(self.nodes[i], F | G));
                1 + usize::from(deep)
            }
            _ => 0,
        }
    }

    /// The crate's term.
    pub fn term(&self) -> Term {
        self.term_at(0)
    }

    fn term_at(&self, i: usize) -> Term {
        match self.nodes[i] {
            A => Term::atom("a"),
            B => Term::atom("b"),
            X => Term::var("X"),
            Y => Term::var("Y"),
            F => Term::structure("f", vec![self.term_at(2 * i + 1)]),
            _ => Term::structure("g", vec![self.term_at(2 * i + 1), self.term_at(2 * i + 2)]),
        }
    }
}

/// Which nodes a tree of codes uses (the root, and the children of used compound nodes).
fn used_nodes(nodes: &[u8; NODES]) -> [bool; NODES] {
    let mut used = [false; NODES];
    used[0] = true;
    for i in 0..3 {
        if used[i] {
            if nodes[i] == F || nodes[i] == G {
                used[2 * i + 1] = true;
            }
            if nodes[i] == G {
                used[2 * i + 2] = true;
            }
        }
    }
    used
}

/// Every canonical term of depth at most `depth` (at most 2), ground ones only if `ground`.
pub fn all_terms(depth: usize, ground: bool) -> Vec<SmallTerm> {
    let leaves: &[u8] = if ground { &[A, B] } else { &[A, B, X, Y] };
    let mut out: Vec<[u8; NODES]> = Vec::new();
    fn fill(at: usize, depth: usize, leaves: &[u8], acc: Vec<[u8; NODES]>) -> Vec<[u8; NODES]> {
        let mut out = Vec::new();
        for t in acc {
            for &c in leaves {
                let mut n = t;
                n[at] = c;
                out.push(n);
            }
            if depth > 0 {
                let mut n = t;
                n[at] = F;
                out.extend(fill(2 * at + 1, depth - 1, leaves, vec![n]));
                let mut n = t;
                n[at] = G;
                for m in fill(2 * at + 1, depth - 1, leaves, vec![n]) {
                    out.extend(fill(2 * at + 2, depth - 1, leaves, vec![m]));
                }
            }
        }
        out
    }
    out.extend(fill(0, depth.min(2), leaves, vec![[0; NODES]]));
    out.into_iter()
        .map(|n| SmallTerm::new(n).expect("the enumeration builds canonical terms"))
        .collect()
}

/// A ground substitution of `X` (first) and `Y` (second).
pub type Theta = [SmallTerm; 2];

/// Every `θ` with values among `values`.
pub fn all_thetas(values: &[SmallTerm]) -> Vec<Theta> {
    values
        .iter()
        .flat_map(|x| values.iter().map(move |y| [*x, *y]))
        .collect()
}

/// Node `i` of `t` with `θ` applied at the top: a variable's value, at its root.
fn resolve<'a>(t: &'a SmallTerm, i: usize, theta: &'a Theta) -> (&'a SmallTerm, usize) {
    match t.nodes[i] {
        X => (&theta[0], 0),
        Y => (&theta[1], 0),
        _ => (t, i),
    }
}

/// Whether `θ(s at i) = θ(t at j)`, without building terms.
fn equal_under(s: &SmallTerm, i: usize, t: &SmallTerm, j: usize, theta: &Theta) -> bool {
    let (s, i) = resolve(s, i, theta);
    let (t, j) = resolve(t, j, theta);
    let c = s.nodes[i];
    if c != t.nodes[j] {
        return false;
    }
    match c {
        F => equal_under(s, 2 * i + 1, t, 2 * j + 1, theta),
        G => {
            equal_under(s, 2 * i + 1, t, 2 * j + 1, theta)
                && equal_under(s, 2 * i + 2, t, 2 * j + 2, theta)
        }
        _ => true,
    }
}

/// Whether `θ(term) = g at j`, for a crate term over `a`, `b`, `X`, `Y`, `f`, `g` and a
/// ground small term `g`.
fn term_equal_under(term: &Term, theta: &Theta, g: &SmallTerm, j: usize) -> bool {
    match term {
        Term::Var(v) if v.name() == "X" && v.generation() == 0 => {
            equal_under(&theta[0], 0, g, j, theta)
        }
        Term::Var(v) if v.name() == "Y" && v.generation() == 0 => {
            equal_under(&theta[1], 0, g, j, theta)
        }
        Term::Atom(n) if &**n == "a" => g.nodes[j] == A,
        Term::Atom(n) if &**n == "b" => g.nodes[j] == B,
        Term::Struct(_) => {
            let args = term.args();
            match (term.functor(), args.len(), g.nodes[j]) {
                (Some("f"), 1, F) => term_equal_under(&args[0], theta, g, 2 * j + 1),
                (Some("g"), 2, G) => {
                    term_equal_under(&args[0], theta, g, 2 * j + 1)
                        && term_equal_under(&args[1], theta, g, 2 * j + 2)
                }
                _ => false,
            }
        }
        _ => false,
    }
}

/// What the kernel answered, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// It returned a unifier.
    Unified,
    /// It returned none.
    NotUnifiable,
}

/// The property: with `unifier` the kernel (`crate::model::unifier`),
///
/// * if it returns `σ`, then `σ(a) = σ(b)`, and every `θ` of `thetas` that unifies `a` and
///   `b` is an instance of `σ` (`θ(σ(X)) = θ(X)`, `θ(σ(Y)) = θ(Y)`): `σ` is most general;
/// * if it returns none, no `θ` of `thetas` unifies `a` and `b`.
///
/// The `θ`s must be ground.
pub fn unify_is_sound_and_most_general(
    a: &SmallTerm,
    b: &SmallTerm,
    unifier: impl Fn(&Term, &Term) -> Option<Substitution>,
    thetas: impl IntoIterator<Item = Theta>,
) -> Result<Verdict, String> {
    let (ta, tb) = (a.term(), b.term());
    let answer = unifier(&ta, &tb);
    if let Some(s) = &answer {
        let (sa, sb) = (s.apply(&ta), s.apply(&tb));
        if sa != sb {
            return Err(format!(
                "{ta} and {tb}: the unifier {s} gives {sa} and {sb}"
            ));
        }
    }
    let images = answer
        .as_ref()
        .map(|s| [s.apply(&Term::var("X")), s.apply(&Term::var("Y"))]);
    for theta in thetas {
        if !theta[0].is_ground() || !theta[1].is_ground() {
            return Err("θ must be ground".into());
        }
        if !equal_under(a, 0, b, 0, &theta) {
            continue;
        }
        let shown = || format!("{{X -> {}, Y -> {}}}", theta[0].term(), theta[1].term());
        match &images {
            None => {
                return Err(format!(
                    "{ta} and {tb}: no unifier returned, but {} unifies them",
                    shown()
                ))
            }
            Some([sx, sy]) => {
                if !term_equal_under(sx, &theta, &theta[0], 0)
                    || !term_equal_under(sy, &theta, &theta[1], 0)
                {
                    return Err(format!(
                        "{ta} and {tb}: the unifier {} is not most general: {} unifies them and is not an instance of it",
                        answer.as_ref().map(|s| s.to_string()).unwrap_or_default(),
                        shown()
                    ));
                }
            }
        }
    }
    Ok(if answer.is_some() {
        Verdict::Unified
    } else {
        Verdict::NotUnifiable
    })
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    fn any_term() -> SmallTerm {
        let t = SmallTerm::new(kani::any());
        kani::assume(t.is_some());
        t.unwrap()
    }

    fn any_ground() -> SmallTerm {
        let t = any_term();
        kani::assume(t.is_ground());
        t
    }

    /// Terms of depth ≤ 2 over a, b, X, Y, f/1, g/2; θ any ground substitution of depth ≤ 2.
    #[kani::proof]
    #[kani::unwind(8)]
    fn unification_is_sound_complete_and_most_general() {
        let a = any_term();
        let b = any_term();
        let theta = [any_ground(), any_ground()];
        let verdict = unify_is_sound_and_most_general(&a, &b, crate::model::unifier, [theta]);
        kani::cover!(verdict == Ok(Verdict::Unified), "a unifier is returned");
        kani::cover!(
            verdict == Ok(Verdict::NotUnifiable),
            "no unifier is returned"
        );
        kani::cover!(a.depth() == 2 && b.depth() == 2, "two terms of depth 2");
        assert!(verdict.is_ok());
    }
}
