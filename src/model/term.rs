//! Terms of the model: Jason's atoms, variables, numbers, strings, literals and lists.
//!
//! Terms are immutable and cheap to clone: names are `Arc<str>` and compound terms sit
//! behind an `Arc`, so a clone is a reference-count increment and terms can be shared
//! between the threads of the search. Each compound term caches whether it is ground, so
//! substitution and occurs checks skip ground subterms in constant time.
//!
//! Canonical forms keep structural equality equal to Jason's equality:
//!
//! * a literal with no arguments, no `~` and no annotations is always a [`Term::Atom`], never
//!   a [`Term::Struct`];
//! * annotations are kept sorted (by [`Ord`], Jason's term order) and without duplicates, as
//!   Jason's `Pred.addAnnot` does; this is also the order in which they print;
//! * numbers are `f64` (Jason's `NumberTermImpl`), so `3` and `3.0` are the same term, and
//!   `-0.0` is stored as `0.0`;
//! * lists are cons cells ending in [`Term::Nil`] or, for a partial list `[a|T]`, in a
//!   variable.
//!
//! [`Ord`] follows Jason's `compareTo`, which decides the order of annotations and the
//! result of sorting: numbers < strings < lists < literals < variables; literals by functor
//! (compared as Java compares strings, by UTF-16 code units), then positive before `~`,
//! then arguments left to right, then arity, then annotations; strings as Jason compares
//! their printed forms. Jason's own order is not consistent between strings and lists; this
//! one is a total order that agrees with it wherever Jason's is consistent.

use std::cmp::Ordering;
use std::collections::HashSet;
use std::sync::Arc;

/// The generations of the variables of a message's content start here, apart from every
/// plan's, subgoal's and rule's (see `semantics::messages`).
pub const MESSAGE_GENERATION: u32 = 3_000_000;

/// A variable.
///
/// Its identity is its name, whether it is anonymous, and its generation: variables as
/// written in the source are generation 0; [`Term::rename_apart`] moves a term's variables
/// to a new generation so that two uses of one plan or rule never share variables.
/// Anonymous variables (each `_` of the source) are named `_1`, `_2`, ... and flagged as
/// anonymous, so they never collide with a variable the programmer named `_1` (which Jason
/// reads as one named variable).
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Var {
    name: Arc<str>,
    /// 0 for a named variable, `n` for the anonymous variable `_n`.
    anon: u32,
    gen: u32,
}

impl Var {
    /// The named variable `name` (`X`, `_Name`, `_12`), generation 0.
    pub fn named(name: &str) -> Var {
        Var {
            name: name.into(),
            anon: 0,
            gen: 0,
        }
    }

    /// The anonymous variable number `n` (printed `_n`), generation 0.
    ///
    /// # Panics
    /// If `n` is 0 (0 marks named variables).
    pub fn anonymous(n: u32) -> Var {
        assert!(n > 0, "anonymous variables are numbered from 1");
        Var {
            name: format!("_{n}").into(),
            anon: n,
            gen: 0,
        }
    }

    /// The name as written (`X`), or `_n` for an anonymous variable; without the generation.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether this variable stands for one `_` of the source.
    pub fn is_anonymous(&self) -> bool {
        self.anon != 0
    }

    /// The generation: 0 as written, another number after [`Term::rename_apart`].
    pub fn generation(&self) -> u32 {
        self.gen
    }

    /// The same variable in generation `gen`.
    pub fn with_generation(&self, gen: u32) -> Var {
        Var {
            gen,
            ..self.clone()
        }
    }
}

impl Ord for Var {
    /// Named before anonymous (as Jason orders `VarTerm` before `UnnamedVar`); named ones by
    /// name, anonymous ones by number; then by generation.
    fn cmp(&self, other: &Var) -> Ordering {
        (self.anon != 0)
            .cmp(&(other.anon != 0))
            .then(self.anon.cmp(&other.anon))
            .then_with(|| java_str_cmp(&self.name, &other.name))
            .then(self.gen.cmp(&other.gen))
    }
}

impl PartialOrd for Var {
    fn partial_cmp(&self, other: &Var) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A number: an `f64` as in Jason, never NaN, with `-0.0` stored as `0.0` so that equality,
/// hashing and ordering agree.
#[derive(Clone, Copy)]
pub struct Num(f64);

impl Num {
    /// `v` as a number, or `None` if it is NaN (which no term may hold: it is not equal to
    /// itself).
    pub fn new(v: f64) -> Option<Num> {
        if v.is_nan() {
            None
        } else {
            // `-0.0 + 0.0` is `+0.0`; every other value is unchanged.
            Some(Num(v + 0.0))
        }
    }

    /// The value.
    pub fn value(self) -> f64 {
        self.0
    }

    /// The value as an integer, if it is integral and within `i64`.
    pub fn as_i64(self) -> Option<i64> {
        // 2^63 is exactly representable; `i64::MAX` is not, so compare with `<`.
        const LIMIT: f64 = 9_223_372_036_854_775_808.0;
        let v = self.0;
        (v.fract() == 0.0 && (-LIMIT..LIMIT).contains(&v)).then_some(v as i64)
    }
}

impl PartialEq for Num {
    fn eq(&self, other: &Num) -> bool {
        self.0 == other.0
    }
}

impl Eq for Num {}

impl std::hash::Hash for Num {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        // Sound because `-0.0` never occurs and NaN is excluded: equal values, equal bits.
        self.0.to_bits().hash(state);
    }
}

impl Ord for Num {
    fn cmp(&self, other: &Num) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

impl PartialOrd for Num {
    fn partial_cmp(&self, other: &Num) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A literal with arguments, strong negation or annotations: `~f(a,X)[source(self)]`.
///
/// Built only through [`Term::literal`] and friends, which keep the canonical form (see the
/// module documentation); read it through the accessors.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Struct {
    functor: Arc<str>,
    negated: bool,
    args: Vec<Term>,
    annots: Vec<Term>,
    ground: bool,
}

impl Struct {
    /// The functor, as written (`cupAt`, `.print`, `'quoted'` with its quotes).
    pub fn functor(&self) -> &str {
        &self.functor
    }

    /// Whether the literal is strongly negated (`~p`).
    pub fn negated(&self) -> bool {
        self.negated
    }

    /// The arguments.
    pub fn args(&self) -> &[Term] {
        &self.args
    }

    /// The annotations, sorted and without duplicates.
    pub fn annots(&self) -> &[Term] {
        &self.annots
    }
}

/// A list cell `[head|tail]`.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Cons {
    head: Term,
    tail: Term,
    ground: bool,
}

impl Cons {
    /// The first element.
    pub fn head(&self) -> &Term {
        &self.head
    }

    /// The rest of the list: [`Term::Nil`], another cell, or (in a partial list) a variable.
    pub fn tail(&self) -> &Term {
        &self.tail
    }
}

/// A Jason term. See the module documentation for the canonical forms.
///
/// `Debug` prints the Jason form, like `Display`, so that test failures read as Jason.
#[derive(Clone, PartialEq, Eq, Hash)]
pub enum Term {
    /// A variable.
    Var(Var),
    /// A number.
    Num(Num),
    /// A string (the text, without quotes or escapes).
    Str(Arc<str>),
    /// An atom: a literal with no arguments, no `~` and no annotations (`table`, `true`).
    Atom(Arc<str>),
    /// Any other literal.
    Struct(Arc<Struct>),
    /// The empty list `[]`.
    Nil,
    /// A list cell.
    Cons(Arc<Cons>),
}

/// The parts of a literal, atoms included: functor, negation, arguments, annotations.
pub(crate) type LitView<'a> = (&'a str, bool, &'a [Term], &'a [Term]);

impl Term {
    /// The atom `name`.
    pub fn atom(name: &str) -> Term {
        Term::Atom(name.into())
    }

    /// The named variable `name`, generation 0 (see [`Var::named`]).
    pub fn var(name: &str) -> Term {
        Term::Var(Var::named(name))
    }

    /// The integer `n` (a number; beyond 2^53 it is rounded, as in Jason).
    pub fn int(n: i64) -> Term {
        Term::Num(Num(n as f64))
    }

    /// The number `v`.
    ///
    /// # Panics
    /// If `v` is NaN; use [`Num::new`] to handle that case.
    pub fn num(v: f64) -> Term {
        Term::Num(Num::new(v).expect("NaN is not a term"))
    }

    /// The string `s` (its text, unquoted).
    pub fn string(s: &str) -> Term {
        Term::Str(s.into())
    }

    /// `functor(args)`, or the atom `functor` when `args` is empty.
    pub fn structure(functor: &str, args: Vec<Term>) -> Term {
        Term::literal(functor, false, args, Vec::new())
    }

    /// The literal `[~]functor(args)[annots]` in canonical form: an atom when it can be,
    /// annotations sorted and deduplicated.
    pub fn literal(functor: &str, negated: bool, args: Vec<Term>, annots: Vec<Term>) -> Term {
        Term::make_literal(functor.into(), negated, args, annots)
    }

    /// [`Term::literal`] with a shared functor, so rebuilding a literal does not copy it.
    pub(crate) fn make_literal(
        functor: Arc<str>,
        negated: bool,
        args: Vec<Term>,
        mut annots: Vec<Term>,
    ) -> Term {
        if args.is_empty() && !negated && annots.is_empty() {
            return Term::Atom(functor);
        }
        annots.sort();
        annots.dedup();
        let ground = args.iter().all(Term::is_ground) && annots.iter().all(Term::is_ground);
        Term::Struct(Arc::new(Struct {
            functor,
            negated,
            args,
            annots,
            ground,
        }))
    }

    /// The empty list `[]`.
    pub fn nil() -> Term {
        Term::Nil
    }

    /// The list cell `[head|tail]`.
    pub fn cons(head: Term, tail: Term) -> Term {
        let ground = head.is_ground() && tail.is_ground();
        Term::Cons(Arc::new(Cons { head, tail, ground }))
    }

    /// The proper list `[e1,...,en]`.
    pub fn list(elems: Vec<Term>) -> Term {
        Term::list_with_tail(elems, Term::Nil)
    }

    /// The list `[e1,...,en|tail]` (`tail` is usually a variable or a list).
    pub fn list_with_tail(elems: Vec<Term>, tail: Term) -> Term {
        elems
            .into_iter()
            .rev()
            .fold(tail, |acc, e| Term::cons(e, acc))
    }

    /// Whether the term has no variable. Constant time: compound terms cache it.
    pub fn is_ground(&self) -> bool {
        match self {
            Term::Var(_) => false,
            Term::Num(_) | Term::Str(_) | Term::Atom(_) | Term::Nil => true,
            Term::Struct(s) => s.ground,
            Term::Cons(c) => c.ground,
        }
    }

    /// Whether the term is a variable.
    pub fn is_var(&self) -> bool {
        matches!(self, Term::Var(_))
    }

    /// The variable, if the term is one.
    pub fn as_var(&self) -> Option<&Var> {
        match self {
            Term::Var(v) => Some(v),
            _ => None,
        }
    }

    /// The number's value, if the term is a number.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Term::Num(n) => Some(n.value()),
            _ => None,
        }
    }

    /// The string's text, if the term is a string.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Term::Str(s) => Some(s),
            _ => None,
        }
    }

    /// Whether the term is a literal (an atom or a [`Struct`]).
    pub fn is_literal(&self) -> bool {
        matches!(self, Term::Atom(_) | Term::Struct(_))
    }

    /// Whether the term is a list (`[]` or a cell; partial lists included).
    pub fn is_list(&self) -> bool {
        matches!(self, Term::Nil | Term::Cons(_))
    }

    /// The functor of a literal (an atom's name); `None` for other terms.
    pub fn functor(&self) -> Option<&str> {
        self.lit_view().map(|l| l.0)
    }

    /// The arguments of a literal; empty for atoms and for terms that are not literals.
    pub fn args(&self) -> &[Term] {
        self.lit_view().map_or(&[], |l| l.2)
    }

    /// The annotations of a literal, sorted; empty otherwise.
    pub fn annots(&self) -> &[Term] {
        self.lit_view().map_or(&[], |l| l.3)
    }

    /// Whether the term is a strongly negated literal (`~p`).
    pub fn is_negated(&self) -> bool {
        self.lit_view().is_some_and(|l| l.1)
    }

    /// The number of arguments of a literal (0 for other terms).
    pub fn arity(&self) -> usize {
        self.args().len()
    }

    /// The parts of a literal, atoms included.
    pub(crate) fn lit_view(&self) -> Option<LitView<'_>> {
        match self {
            Term::Atom(a) => Some((a, false, &[], &[])),
            Term::Struct(s) => Some((&s.functor, s.negated, &s.args, &s.annots)),
            _ => None,
        }
    }

    /// The elements of a list and its tail when that is not `[]` (a partial list's
    /// variable); `None` if the term is not a list.
    pub fn list_elements(&self) -> Option<(Vec<Term>, Option<Term>)> {
        if !self.is_list() {
            return None;
        }
        let mut elems = Vec::new();
        let mut t = self;
        while let Term::Cons(c) = t {
            elems.push(c.head.clone());
            t = &c.tail;
        }
        let tail = (*t != Term::Nil).then(|| t.clone());
        Some((elems, tail))
    }

    /// The literal with `extra` annotations added (kept sorted, without duplicates), as when
    /// Jason adds `source(self)`; `None` if the term is not a literal.
    pub fn add_annots(&self, extra: impl IntoIterator<Item = Term>) -> Option<Term> {
        let (f, neg, args, annots) = self.lit_view()?;
        let mut all = annots.to_vec();
        all.extend(extra);
        Some(Term::literal(f, neg, args.to_vec(), all))
    }

    /// The literal without its annotations (the term itself if it is not a literal).
    pub fn without_annots(&self) -> Term {
        match self {
            Term::Struct(s) if !s.annots.is_empty() => {
                Term::make_literal(s.functor.clone(), s.negated, s.args.clone(), Vec::new())
            }
            _ => self.clone(),
        }
    }

    /// The distinct variables of the term, in order of first occurrence (left to right,
    /// arguments before annotations), so that anything built from them is deterministic.
    pub fn vars(&self) -> Vec<Var> {
        let mut out = Vec::new();
        let mut seen = HashSet::new();
        self.collect_vars(&mut out, &mut seen);
        out
    }

    fn collect_vars(&self, out: &mut Vec<Var>, seen: &mut HashSet<Var>) {
        if self.is_ground() {
            return;
        }
        match self {
            Term::Var(v) if seen.insert(v.clone()) => out.push(v.clone()),
            Term::Struct(s) => {
                for t in s.args.iter().chain(&s.annots) {
                    t.collect_vars(out, seen);
                }
            }
            Term::Cons(c) => {
                c.head.collect_vars(out, seen);
                c.tail.collect_vars(out, seen);
            }
            _ => {}
        }
    }

    /// Whether `v` occurs in the term (bindings not followed; see the substitution for
    /// that).
    pub fn contains_var(&self, v: &Var) -> bool {
        match self {
            _ if self.is_ground() => false,
            Term::Var(w) => w == v,
            Term::Struct(s) => s.args.iter().chain(&s.annots).any(|t| t.contains_var(v)),
            Term::Cons(c) => c.head.contains_var(v) || c.tail.contains_var(v),
            _ => false,
        }
    }

    /// The term with every variable `v` replaced by `f(v)`. Ground subterms are shared, not
    /// copied; literals are rebuilt in canonical form (replacing variables may reorder or
    /// merge annotations).
    pub fn map_vars(&self, f: &mut impl FnMut(&Var) -> Term) -> Term {
        if self.is_ground() {
            return self.clone();
        }
        match self {
            Term::Var(v) => f(v),
            Term::Struct(s) => {
                let args = s.args.iter().map(|t| t.map_vars(f)).collect();
                let annots = s.annots.iter().map(|t| t.map_vars(f)).collect();
                Term::make_literal(s.functor.clone(), s.negated, args, annots)
            }
            Term::Cons(c) => {
                let head = c.head.map_vars(f);
                Term::cons(head, c.tail.map_vars(f))
            }
            _ => self.clone(),
        }
    }

    /// The term with every variable moved to generation `gen`, to instantiate a plan or a
    /// rule with variables of its own: give every use a new `gen` (from a counter) and
    /// rename all parts of the plan (trigger, context, body) with the same one, so that they
    /// still share their variables.
    ///
    /// The renaming is one-to-one when the term's variables all have one generation, as
    /// every term converted from the source does (generation 0).
    pub fn rename_apart(&self, gen: u32) -> Term {
        self.map_vars(&mut |v| Term::Var(v.with_generation(gen)))
    }

    /// The rank of the term's kind in Jason's order.
    fn kind_rank(&self) -> u8 {
        match self {
            Term::Num(_) => 0,
            Term::Str(_) => 1,
            Term::Nil | Term::Cons(_) => 2,
            Term::Atom(_) | Term::Struct(_) => 3,
            Term::Var(_) => 4,
        }
    }
}

impl From<Var> for Term {
    fn from(v: Var) -> Term {
        Term::Var(v)
    }
}

/// Compares two strings as Java's `String.compareTo` does (UTF-16 code units), which is
/// how Jason orders functors.
pub(crate) fn java_str_cmp(a: &str, b: &str) -> Ordering {
    if a == b {
        Ordering::Equal
    } else {
        a.encode_utf16().cmp(b.encode_utf16())
    }
}

fn cmp_seq(a: &[Term], b: &[Term]) -> Ordering {
    // Element by element, then the shorter first: Jason's order for arguments and
    // annotations (and exactly `Ord` for slices).
    a.cmp(b)
}

impl Ord for Term {
    /// Jason's term order; see the module documentation.
    fn cmp(&self, other: &Term) -> Ordering {
        let rank = self.kind_rank().cmp(&other.kind_rank());
        if rank != Ordering::Equal {
            return rank;
        }
        match (self, other) {
            (Term::Num(a), Term::Num(b)) => a.cmp(b),
            (Term::Str(a), Term::Str(b)) => {
                // Jason compares the printed forms `"a"` and `"b"`, quotes included.
                let q = std::iter::once(u16::from(b'"'));
                q.clone()
                    .chain(a.encode_utf16())
                    .chain(q.clone())
                    .cmp(q.clone().chain(b.encode_utf16()).chain(q))
            }
            (Term::Var(a), Term::Var(b)) => a.cmp(b),
            (Term::Nil, Term::Nil) => Ordering::Equal,
            (Term::Nil, Term::Cons(_)) => Ordering::Less,
            (Term::Cons(_), Term::Nil) => Ordering::Greater,
            (Term::Cons(_), Term::Cons(_)) => {
                // Cell by cell, iteratively along the spine.
                let (mut a, mut b) = (self, other);
                loop {
                    match (a, b) {
                        (Term::Cons(x), Term::Cons(y)) => {
                            let c = x.head.cmp(&y.head);
                            if c != Ordering::Equal {
                                return c;
                            }
                            a = &x.tail;
                            b = &y.tail;
                        }
                        _ => return a.cmp(b),
                    }
                }
            }
            _ => {
                let (fa, na, aa, ta) = self.lit_view().expect("a literal");
                let (fb, nb, ab, tb) = other.lit_view().expect("a literal");
                java_str_cmp(fa, fb)
                    .then(na.cmp(&nb))
                    .then_with(|| cmp_seq(aa, ab))
                    .then_with(|| cmp_seq(ta, tb))
            }
        }
    }
}

impl PartialOrd for Term {
    fn partial_cmp(&self, other: &Term) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(s: &str) -> Term {
        Term::atom(s)
    }

    #[test]
    fn terms_are_send_and_sync() {
        // The search shares terms between threads.
        fn check<T: Send + Sync>() {}
        check::<Term>();
        check::<crate::model::Substitution>();
    }

    #[test]
    fn atoms_are_canonical() {
        assert_eq!(Term::structure("p", vec![]), a("p"));
        assert_eq!(Term::literal("p", false, vec![], vec![]), a("p"));
        assert!(matches!(
            Term::literal("p", true, vec![], vec![]),
            Term::Struct(_)
        ));
        assert!(matches!(
            Term::literal("p", false, vec![], vec![a("x")]),
            Term::Struct(_)
        ));
    }

    #[test]
    fn numbers_compare_by_value() {
        assert_eq!(Term::int(3), Term::num(3.0));
        assert_eq!(Term::num(-0.0), Term::num(0.0));
        assert_eq!(Term::num(-0.0).cmp(&Term::int(0)), Ordering::Equal);
        assert!(Term::int(-2) < Term::num(1.5));
        assert!(Num::new(f64::NAN).is_none());
        assert_eq!(Num::new(-7.0).unwrap().as_i64(), Some(-7));
        assert_eq!(Num::new(0.5).unwrap().as_i64(), None);
    }

    #[test]
    fn hash_agrees_with_eq() {
        let set: HashSet<Term> = [Term::num(-0.0), Term::int(0), Term::num(0.0)].into();
        assert_eq!(set.len(), 1);
    }

    #[test]
    fn annotations_sorted_and_deduplicated() {
        let t = Term::literal(
            "p",
            false,
            vec![],
            vec![a("x"), Term::structure("source", vec![a("self")]), a("x")],
        );
        assert_eq!(
            t.annots(),
            &[Term::structure("source", vec![a("self")]), a("x")]
        );
    }

    #[test]
    fn jason_order() {
        // numbers < strings < lists < literals < variables
        let mut v = vec![
            Term::var("X"),
            a("b"),
            Term::list(vec![a("a")]),
            Term::string("s"),
            Term::int(10),
            Term::nil(),
            Term::structure("a", vec![a("z")]),
            a("a"),
            Term::Var(Var::anonymous(1)),
            Term::literal("a", true, vec![], vec![]),
        ];
        v.sort();
        let printed: Vec<String> = v.iter().map(|t| t.to_string()).collect();
        assert_eq!(
            printed,
            ["10", "\"s\"", "[]", "[a]", "a", "a(z)", "~a", "b", "X", "_1"]
        );
    }

    #[test]
    fn string_order_is_on_printed_form() {
        // `"ab"` vs `"ab c"`: the closing quote (0x22) sorts after the space (0x20).
        assert!(Term::string("ab c") < Term::string("ab"));
        assert!(Term::string("ab") < Term::string("abc"));
    }

    #[test]
    fn ground_and_vars() {
        let t = Term::literal(
            "f",
            false,
            vec![
                Term::var("X"),
                Term::list_with_tail(vec![a("a")], Term::var("T")),
            ],
            vec![Term::var("X"), Term::structure("s", vec![Term::var("Y")])],
        );
        assert!(!t.is_ground());
        // annotations sort `s(Y)` (a literal) before `X` (a variable).
        assert_eq!(
            t.vars(),
            vec![Var::named("X"), Var::named("T"), Var::named("Y")]
        );
        assert!(t.contains_var(&Var::named("T")));
        assert!(!t.contains_var(&Var::named("Z")));
        assert!(Term::structure("f", vec![a("a"), Term::list(vec![Term::int(1)])]).is_ground());
    }

    #[test]
    fn anonymous_variables_differ_from_named_ones() {
        assert_ne!(Var::anonymous(1), Var::named("_1"));
        assert_eq!(Var::anonymous(1).name(), "_1");
        assert!(Var::anonymous(1).is_anonymous());
    }

    #[test]
    fn rename_apart_moves_generation() {
        let t = Term::structure("f", vec![Term::var("X"), Term::Var(Var::anonymous(2))]);
        let r = t.rename_apart(7);
        assert_eq!(
            r.vars(),
            vec![
                Var::named("X").with_generation(7),
                Var::anonymous(2).with_generation(7)
            ]
        );
        assert_ne!(r, t);
        assert_eq!(r.rename_apart(0), t);
    }

    #[test]
    fn list_elements() {
        let l = Term::list_with_tail(vec![a("a"), a("b")], Term::var("T"));
        assert_eq!(
            l.list_elements(),
            Some((vec![a("a"), a("b")], Some(Term::var("T"))))
        );
        assert_eq!(Term::nil().list_elements(), Some((vec![], None)));
        assert_eq!(a("a").list_elements(), None);
    }

    #[test]
    fn annotation_helpers() {
        let p = Term::structure("p", vec![a("a")]);
        let src = Term::structure("source", vec![a("self")]);
        let q = p.add_annots([src.clone()]).unwrap();
        assert_eq!(q.annots(), &[src]);
        assert_eq!(q.without_annots(), p);
        assert_eq!(a("x").add_annots([]), Some(a("x")));
        assert_eq!(Term::int(1).add_annots([]), None);
    }

    #[test]
    fn accessors() {
        let t = Term::literal("p", true, vec![a("a")], vec![]);
        assert_eq!(t.functor(), Some("p"));
        assert!(t.is_negated());
        assert_eq!(t.arity(), 1);
        assert_eq!(a("q").args(), &[] as &[Term]);
        assert_eq!(Term::string("s").as_str(), Some("s"));
        assert_eq!(Term::int(2).as_f64(), Some(2.0));
        assert!(Term::var("X").is_var());
        assert!(Term::nil().is_list() && !Term::nil().is_literal());
    }
}
