//! Substitutions and unification.
//!
//! A [`Substitution`] maps variables to terms. It is kept triangular (a binding may mention
//! variables bound elsewhere in it), which makes binding cheap; [`Substitution::apply`]
//! follows bindings to the end. Bindings live in a `BTreeMap`, so iteration, printing,
//! equality and hashing are deterministic: substitutions are part of the states the model
//! checker stores.
//!
//! [`unify`] is Jason's unification with two deliberate properties:
//!
//! * **Annotations are asymmetric**, as in Jason (`Unifier.unifyTerms` with
//!   `Pred.hasSubsetAnnot`): `unify(p[a1..an], p[b1..bm])` needs every annotation `ai` of
//!   the *first* term to unify with a *distinct* annotation `bj` of the *second* (the first
//!   term's annotations are a subset of the second's), so `p[a]` unifies with `p[a,b]` but
//!   not the other way round, and `p` (no annotations) unifies with any `p[...]`. The rule
//!   applies at every depth, in the same direction. Jason searches greedily; we search with
//!   backtracking over the choice of `bj`, so we also find matches the greedy scan misses,
//!   and commit to the first match found (ordered by the annotations' sorted order), as
//!   Jason does. Without annotations unification is symmetric.
//! * **We perform the occurs check**, which Jason does not: `X = f(X)` fails. The model
//!   checker must never build a cyclic term, since resolving it would loop forever; with
//!   the check, bindings form an acyclic graph, so [`Substitution::apply`] always
//!   terminates. The cost is negligible on the small terms of plan libraries.
//!
//! A failed unification leaves the substitution exactly as it was (bindings made on the way
//! are undone from a trail).

use super::term::{Term, Var};
use std::collections::BTreeMap;
use std::fmt;

/// Variable bindings. See the module documentation.
///
/// Equality and hashing compare the bindings as stored (triangular form); compare
/// [`Substitution::resolved`] forms to compare meanings.
#[derive(Clone, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Substitution {
    map: BTreeMap<Var, Term>,
}

impl Substitution {
    /// The empty substitution.
    pub fn new() -> Substitution {
        Substitution::default()
    }

    /// Whether nothing is bound.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// The number of bound variables.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// The term `v` is bound to, as stored (not resolved).
    pub fn get(&self, v: &Var) -> Option<&Term> {
        self.map.get(v)
    }

    /// The bindings as stored, in variable order.
    pub fn iter(&self) -> impl Iterator<Item = (&Var, &Term)> {
        self.map.iter()
    }

    /// `t` with bound variables followed at the top only: the first term of the binding
    /// chain that is not a bound variable.
    pub fn deref<'a>(&'a self, mut t: &'a Term) -> &'a Term {
        while let Term::Var(v) = t {
            match self.map.get(v) {
                Some(b) => t = b,
                None => break,
            }
        }
        t
    }

    /// `t` with every bound variable replaced, recursively, by its value: the result has no
    /// bound variable. Terminates because bindings are acyclic (see [`Substitution::bind`]).
    pub fn apply(&self, t: &Term) -> Term {
        if self.map.is_empty() {
            return t.clone();
        }
        t.map_vars(&mut |v| match self.map.get(v) {
            Some(b) => self.apply(b),
            None => Term::Var(v.clone()),
        })
    }

    /// The value of `v`, fully resolved (`v` itself if unbound).
    pub fn resolve(&self, v: &Var) -> Term {
        self.apply(&Term::Var(v.clone()))
    }

    /// Binds `v` to `t`, if `v` is unbound and does not occur in `t` (bindings followed).
    /// Returns whether it did; the check keeps bindings acyclic.
    pub fn bind(&mut self, v: Var, t: Term) -> bool {
        if self.map.contains_key(&v) || self.occurs(&v, &t) {
            return false;
        }
        self.map.insert(v, t);
        true
    }

    /// Whether `v` occurs in `t` once bindings are followed (`v` itself counts).
    pub fn occurs(&self, v: &Var, t: &Term) -> bool {
        let t = self.deref(t);
        match t {
            _ if t.is_ground() => false,
            Term::Var(w) => w == v,
            Term::Struct(s) => s.args().iter().chain(s.annots()).any(|a| self.occurs(v, a)),
            Term::Cons(c) => self.occurs(v, c.head()) || self.occurs(v, c.tail()),
            _ => false,
        }
    }

    /// The same bindings in idempotent form: every value fully resolved. Two substitutions
    /// with the same meaning have equal resolved forms.
    pub fn resolved(&self) -> Substitution {
        Substitution {
            map: self
                .map
                .iter()
                .map(|(v, t)| (v.clone(), self.apply(t)))
                .collect(),
        }
    }

    /// The resolved bindings of `vars` only (those bound), e.g. to keep the answer of a
    /// query in terms of the query's variables.
    pub fn restrict(&self, vars: &[Var]) -> Substitution {
        Substitution {
            map: vars
                .iter()
                .filter(|v| self.map.contains_key(v))
                .map(|v| (v.clone(), self.resolve(v)))
                .collect(),
        }
    }
}

impl fmt::Display for Substitution {
    /// `{X -> a, Y -> f(Z)}`, bindings as stored, in variable order.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("{")?;
        for (i, (v, t)) in self.map.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{v} -> {t}")?;
        }
        f.write_str("}")
    }
}

impl fmt::Debug for Substitution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

/// Unifies `a` with `b`, extending `s`; returns whether it succeeded. On failure `s` is left
/// unchanged. Annotations of `a` must be a subset of those of `b` (see the module
/// documentation); the occurs check is performed.
pub fn unify(a: &Term, b: &Term, s: &mut Substitution) -> bool {
    let mut u = Unifier {
        s,
        trail: Vec::new(),
        frozen: &[],
    };
    let ok = u.unify(a, b);
    if !ok {
        u.undo_to(0);
    }
    ok
}

/// A substitution that unifies `a` with `b` from scratch, if there is one.
pub fn unifier(a: &Term, b: &Term) -> Option<Substitution> {
    let mut s = Substitution::new();
    unify(a, b, &mut s).then_some(s)
}

/// One-way matching: extends `s` so that `pattern` becomes `target` (up to the annotation
/// subset rule: the pattern's annotations must be found in the target's), binding only the
/// pattern's variables; the target's variables are treated as constants. On failure `s` is
/// unchanged. For a ground target this is exactly [`unify`]. The target's variables should
/// not be bound in `s`.
pub fn match_pattern(pattern: &Term, target: &Term, s: &mut Substitution) -> bool {
    let frozen = target.vars();
    let mut u = Unifier {
        s,
        trail: Vec::new(),
        frozen: &frozen,
    };
    let ok = u.unify(pattern, target);
    if !ok {
        u.undo_to(0);
    }
    ok
}

/// One unification run: the bindings it made (to undo them) and the variables it may not
/// bind.
struct Unifier<'a> {
    s: &'a mut Substitution,
    trail: Vec<Var>,
    frozen: &'a [Var],
}

impl Unifier<'_> {
    fn undo_to(&mut self, mark: usize) {
        for v in self.trail.drain(mark..) {
            self.s.map.remove(&v);
        }
    }

    fn bind(&mut self, v: &Var, t: &Term) -> bool {
        if self.frozen.contains(v) || self.s.occurs(v, t) {
            return false;
        }
        self.s.map.insert(v.clone(), t.clone());
        self.trail.push(v.clone());
        true
    }

    /// Unifies without undoing on failure: the caller undoes to its own mark.
    fn unify(&mut self, a: &Term, b: &Term) -> bool {
        // Clones are reference-count increments; they free `self.s` for binding.
        let a = self.s.deref(a).clone();
        let b = self.s.deref(b).clone();
        match (&a, &b) {
            (Term::Var(x), Term::Var(y)) if x == y => true,
            (Term::Var(x), Term::Var(y)) => {
                // Bind the one that may be bound (a frozen variable is a constant).
                if self.frozen.contains(x) {
                    self.bind(y, &a)
                } else {
                    self.bind(x, &b)
                }
            }
            (Term::Var(x), t) | (t, Term::Var(x)) => self.bind(x, t),
            (Term::Num(x), Term::Num(y)) => x == y,
            (Term::Str(x), Term::Str(y)) => x == y,
            (Term::Nil, Term::Nil) => true,
            (Term::Cons(x), Term::Cons(y)) => {
                self.unify(x.head(), y.head()) && self.unify(x.tail(), y.tail())
            }
            _ => {
                let (Some((fa, na, aa, ta)), Some((fb, nb, ab, tb))) = (a.lit_view(), b.lit_view())
                else {
                    return false;
                };
                fa == fb
                    && na == nb
                    && aa.len() == ab.len()
                    && aa.iter().zip(ab).all(|(x, y)| self.unify(x, y))
                    && self.annots_subset(ta, tb)
            }
        }
    }

    /// Whether every annotation in `xs` unifies with a distinct one in `ys`.
    fn annots_subset(&mut self, xs: &[Term], ys: &[Term]) -> bool {
        if xs.is_empty() {
            return true;
        }
        if xs.len() > ys.len() {
            return false;
        }
        if xs.iter().chain(ys).all(Term::is_ground) {
            // Both sorted by the same total order: a merge decides inclusion.
            let mut ys = ys.iter();
            return xs.iter().all(|x| ys.any(|y| y == x));
        }
        let mut used = vec![false; ys.len()];
        self.annots_search(xs, ys, &mut used)
    }

    /// Backtracking search for an injective match of `xs` into `ys`; on success the
    /// bindings of the first match found are kept.
    fn annots_search(&mut self, xs: &[Term], ys: &[Term], used: &mut [bool]) -> bool {
        let Some((x, rest)) = xs.split_first() else {
            return true;
        };
        for (j, y) in ys.iter().enumerate() {
            if used[j] {
                continue;
            }
            let mark = self.trail.len();
            if self.unify(x, y) {
                used[j] = true;
                if self.annots_search(rest, ys, used) {
                    return true;
                }
                used[j] = false;
            }
            self.undo_to(mark);
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(s: &str) -> Term {
        Term::atom(s)
    }
    fn v(s: &str) -> Term {
        Term::var(s)
    }
    fn f(name: &str, args: Vec<Term>) -> Term {
        Term::structure(name, args)
    }
    fn ann(name: &str, args: Vec<Term>, annots: Vec<Term>) -> Term {
        Term::literal(name, false, args, annots)
    }

    #[test]
    fn binds_variables() {
        let mut s = Substitution::new();
        assert!(unify(
            &f("cupAt", vec![v("C"), a("table")]),
            &f("cupAt", vec![a("cup1"), v("L")]),
            &mut s
        ));
        assert_eq!(s.resolve(&Var::named("C")), a("cup1"));
        assert_eq!(s.resolve(&Var::named("L")), a("table"));
        assert_eq!(s.to_string(), "{C -> cup1, L -> table}");
    }

    #[test]
    fn clashes_fail_and_leave_substitution_unchanged() {
        let mut s = Substitution::new();
        assert!(unify(&v("Z"), &a("z"), &mut s));
        let before = s.clone();
        // X gets bound to a before the second argument clashes.
        assert!(!unify(
            &f("p", vec![v("X"), a("b")]),
            &f("p", vec![a("a"), a("c")]),
            &mut s
        ));
        assert_eq!(s, before);
        assert!(!unify(&a("p"), &f("p", vec![a("a")]), &mut s));
        assert!(!unify(
            &Term::literal("p", true, vec![], vec![]),
            &a("p"),
            &mut s
        ));
        assert!(!unify(&Term::int(1), &Term::string("1"), &mut s));
        assert!(!unify(&Term::nil(), &a("[]"), &mut s));
        assert_eq!(s, before);
    }

    #[test]
    fn numbers_unify_by_value() {
        assert!(unifier(&Term::int(2), &Term::num(2.0)).is_some());
        assert!(unifier(&Term::int(2), &Term::num(2.5)).is_none());
    }

    #[test]
    fn occurs_check() {
        assert!(unifier(&v("X"), &f("f", vec![v("X")])).is_none());
        assert!(unifier(&f("f", vec![v("X")]), &v("X")).is_none());
        // Through a chain: X = Y, then Y = f(X).
        let mut s = Substitution::new();
        assert!(unify(&v("X"), &v("Y"), &mut s));
        assert!(!unify(&v("Y"), &f("f", vec![v("X")]), &mut s));
        assert!(!s.bind(Var::named("Y"), f("g", vec![v("X")])));
        // In a list tail: T = [a|T].
        assert!(unifier(&v("T"), &Term::list_with_tail(vec![a("a")], v("T"))).is_none());
        assert!(unifier(&v("X"), &v("X")).is_some_and(|s| s.is_empty()));
    }

    #[test]
    fn lists_unify_head_and_tail() {
        let s = unifier(
            &Term::list_with_tail(vec![v("H")], v("T")),
            &Term::list(vec![a("a"), a("b"), a("c")]),
        )
        .unwrap();
        assert_eq!(s.resolve(&Var::named("H")), a("a"));
        assert_eq!(s.resolve(&Var::named("T")).to_string(), "[b,c]");
        assert!(unifier(&Term::list(vec![v("X")]), &Term::list(vec![])).is_none());
        assert!(unifier(
            &Term::list_with_tail(vec![a("a")], v("T")),
            &Term::list_with_tail(vec![v("X"), a("b")], v("U"))
        )
        .is_some());
    }

    #[test]
    fn annotations_subset_direction() {
        let src = f("source", vec![a("self")]);
        let p = a("p");
        let p_src = ann("p", vec![], vec![src.clone()]);
        let p_src_x = ann("p", vec![], vec![src.clone(), a("x")]);
        assert!(unifier(&p, &p_src).is_some());
        assert!(unifier(&p_src, &p).is_none());
        assert!(unifier(&p_src, &p_src_x).is_some());
        assert!(unifier(&p_src_x, &p_src).is_none());
        // With a variable: `p[source(A)]` against `p[x,source(self)]`.
        let s = unifier(&ann("p", vec![], vec![f("source", vec![v("A")])]), &p_src_x).unwrap();
        assert_eq!(s.resolve(&Var::named("A")), a("self"));
        // Nested, same direction.
        assert!(unifier(&f("q", vec![p.clone()]), &f("q", vec![p_src.clone()])).is_some());
        assert!(unifier(&f("q", vec![p_src.clone()]), &f("q", vec![p.clone()])).is_none());
    }

    #[test]
    fn annotations_need_distinct_members() {
        // Two annotations cannot both match the single `a`.
        let two_vars = ann("p", vec![], vec![v("X"), v("Y")]);
        assert!(unifier(&two_vars, &ann("p", vec![], vec![a("a")])).is_none());
        let s = unifier(&two_vars, &ann("p", vec![], vec![a("a"), a("b")])).unwrap();
        assert_eq!(s.to_string(), "{X -> a, Y -> b}");
    }

    #[test]
    fn annotation_search_backtracks() {
        // `f(X)` first tries `f(a)`, then `g(X)` fails on `g(b)`: it must retry `f(b)`.
        // (Sorted: `f(X)` < `g(X)`, and `f(a)` < `f(b)` < `g(b)`.)
        let first = ann(
            "p",
            vec![],
            vec![f("f", vec![v("X")]), f("g", vec![v("X")])],
        );
        let second = ann(
            "p",
            vec![],
            vec![
                f("f", vec![a("a")]),
                f("f", vec![a("b")]),
                f("g", vec![a("b")]),
            ],
        );
        let s = unifier(&first, &second).unwrap();
        assert_eq!(s.resolve(&Var::named("X")), a("b"));
    }

    #[test]
    fn apply_resolves_chains_and_resorts_annotations() {
        let mut s = Substitution::new();
        assert!(unify(&v("X"), &v("Y"), &mut s));
        assert!(unify(&v("Y"), &f("f", vec![v("Z")]), &mut s));
        assert!(unify(&v("Z"), &a("c"), &mut s));
        assert_eq!(s.apply(&v("X")).to_string(), "f(c)");
        assert_eq!(s.resolved().to_string(), "{X -> f(c), Y -> f(c), Z -> c}");
        assert_eq!(
            s.restrict(&[Var::named("Z"), Var::named("W")]).to_string(),
            "{Z -> c}"
        );
        // `p[W,b]` with W = a becomes `p[a,b]`; with W = b it becomes `p[b]`.
        let t = ann("p", vec![], vec![v("W"), a("b")]);
        let mut s1 = Substitution::new();
        assert!(s1.bind(Var::named("W"), a("a")));
        assert_eq!(s1.apply(&t).to_string(), "p[a,b]");
        let mut s2 = Substitution::new();
        assert!(s2.bind(Var::named("W"), a("b")));
        assert_eq!(s2.apply(&t).to_string(), "p[b]");
    }

    #[test]
    fn bind_refuses_rebinding() {
        let mut s = Substitution::new();
        assert!(s.bind(Var::named("X"), a("a")));
        assert!(!s.bind(Var::named("X"), a("b")));
        assert_eq!(s.len(), 1);
    }

    #[test]
    fn matching_binds_only_the_pattern() {
        let mut s = Substitution::new();
        assert!(match_pattern(
            &f("p", vec![v("X")]),
            &f("p", vec![a("a")]),
            &mut s
        ));
        assert_eq!(s.resolve(&Var::named("X")), a("a"));
        // The target's variable is a constant: it matches a pattern variable, not `a`.
        let mut s = Substitution::new();
        assert!(!match_pattern(
            &f("p", vec![a("a")]),
            &f("p", vec![v("Y")]),
            &mut s
        ));
        assert!(s.is_empty());
        assert!(match_pattern(
            &f("p", vec![v("X")]),
            &f("p", vec![v("Y")]),
            &mut s
        ));
        assert_eq!(s.resolve(&Var::named("X")), v("Y"));
        // Repeated pattern variable against distinct target variables.
        let mut s = Substitution::new();
        assert!(!match_pattern(
            &f("p", vec![v("X"), v("X")]),
            &f("p", vec![v("Y"), v("Z")]),
            &mut s
        ));
        assert!(s.is_empty());
    }

    #[test]
    fn renamed_variables_are_distinct() {
        let t = f("p", vec![v("X")]);
        let s = unifier(&t, &f("p", vec![t.rename_apart(1)])).unwrap();
        assert_eq!(s.apply(&v("X")).to_string(), "p(_1X)");
    }
}
