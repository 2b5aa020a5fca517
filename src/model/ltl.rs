//! Linear temporal logic over numbered atomic propositions, and its reference semantics on
//! ultimately periodic words.
//!
//! A formula speaks of at most 64 propositions, numbered `0..64`, so that a *letter* (what
//! holds in one state of a run) is a `u64`: bit `p` set means proposition `p` is true. A
//! proposition numbered 64 or more is false in every letter (no bit can set it). A word is
//! a lasso `prefix · cycle^ω`, the shape every counterexample of a finite model has, so the
//! semantics here ([`Ltl::holds_on_lasso`]) is exact and is the oracle the Büchi
//! translation (`check::buchi`) is tested against.

/// An LTL formula. The derived operators (`->`, `<->`, `W`, `[]`, `<>`, `~>`) are built
/// by the associated functions of the same names out of these, so every consumer (the
/// semantics, the negation normal form, the automaton translation) has only these to know.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Ltl {
    /// Holds everywhere.
    True,
    /// Holds nowhere.
    False,
    /// Atomic proposition `p`: holds where bit `p` of the letter is set.
    Prop(u32),
    /// Negation.
    Not(Box<Ltl>),
    /// Conjunction.
    And(Box<Ltl>, Box<Ltl>),
    /// Disjunction.
    Or(Box<Ltl>, Box<Ltl>),
    /// `X f`: `f` holds at the next position.
    Next(Box<Ltl>),
    /// `a U b`: `b` holds at some position, and `a` at every position before it.
    Until(Box<Ltl>, Box<Ltl>),
    /// `a R b`: `b` holds up to and including the first position where `a` holds, or
    /// forever if `a` never does (the dual of `U`: `a R b = !(!a U !b)`).
    Release(Box<Ltl>, Box<Ltl>),
}

impl Ltl {
    /// `!f`, with `!true`, `!false` and `!!f` folded.
    // A constructor beside `and` and `or`, taking its operand by value like them, rather
    // than `std::ops::Not` on a formula.
    #[allow(clippy::should_implement_trait)]
    pub fn not(f: Ltl) -> Ltl {
        match f {
            Ltl::True => Ltl::False,
            Ltl::False => Ltl::True,
            Ltl::Not(g) => *g,
            f => Ltl::Not(Box::new(f)),
        }
    }

    /// `a & b`, with the constants folded.
    pub fn and(a: Ltl, b: Ltl) -> Ltl {
        match (a, b) {
            (Ltl::False, _) | (_, Ltl::False) => Ltl::False,
            (Ltl::True, f) | (f, Ltl::True) => f,
            (a, b) => Ltl::And(Box::new(a), Box::new(b)),
        }
    }

    /// `a | b`, with the constants folded.
    pub fn or(a: Ltl, b: Ltl) -> Ltl {
        match (a, b) {
            (Ltl::True, _) | (_, Ltl::True) => Ltl::True,
            (Ltl::False, f) | (f, Ltl::False) => f,
            (a, b) => Ltl::Or(Box::new(a), Box::new(b)),
        }
    }

    /// `a -> b`, that is `!a | b`.
    pub fn implies(a: Ltl, b: Ltl) -> Ltl {
        Ltl::or(Ltl::not(a), b)
    }

    /// `a <-> b`, as `(a & b) | (!a & !b)`: each side once positive and once negated, which
    /// keeps the negation normal form no bigger than two copies.
    pub fn iff(a: Ltl, b: Ltl) -> Ltl {
        Ltl::or(
            Ltl::and(a.clone(), b.clone()),
            Ltl::and(Ltl::not(a), Ltl::not(b)),
        )
    }

    /// `X f`, with `X true = true` and `X false = false` (every position has a successor).
    pub fn next(f: Ltl) -> Ltl {
        match f {
            Ltl::True | Ltl::False => f,
            f => Ltl::Next(Box::new(f)),
        }
    }

    /// `a U b`, with `a U true = true`, `a U false = false` and `false U b = b`.
    pub fn until(a: Ltl, b: Ltl) -> Ltl {
        match (a, b) {
            (_, b @ (Ltl::True | Ltl::False)) => b,
            (Ltl::False, b) => b,
            (a, b) => Ltl::Until(Box::new(a), Box::new(b)),
        }
    }

    /// `a R b`, with `a R true = true`, `a R false = false` and `true R b = b`.
    pub fn release(a: Ltl, b: Ltl) -> Ltl {
        match (a, b) {
            (_, b @ (Ltl::True | Ltl::False)) => b,
            (Ltl::True, b) => b,
            (a, b) => Ltl::Release(Box::new(a), Box::new(b)),
        }
    }

    /// `a W b` (weak until: `a U b`, or `a` forever), as `b R (a | b)`, which names each
    /// side once.
    pub fn weak_until(a: Ltl, b: Ltl) -> Ltl {
        Ltl::release(b.clone(), Ltl::or(a, b))
    }

    /// `[] f` (always), as `false R f`.
    pub fn always(f: Ltl) -> Ltl {
        Ltl::release(Ltl::False, f)
    }

    /// `<> f` (eventually), as `true U f`.
    pub fn eventually(f: Ltl) -> Ltl {
        Ltl::until(Ltl::True, f)
    }

    /// `a ~> b` (leads to: every `a` is followed, now or later, by a `b`), as
    /// `[](a -> <> b)`.
    pub fn leads_to(a: Ltl, b: Ltl) -> Ltl {
        Ltl::always(Ltl::implies(a, Ltl::eventually(b)))
    }

    /// The same formula in negation normal form: `Not` only directly on `Prop`, pushed
    /// through the other operators by De Morgan and the dualities `!X f = X !f`,
    /// `!(a U b) = !a R !b`, `!(a R b) = !a U !b`. The tableau translation needs it.
    pub fn nnf(&self) -> Ltl {
        self.nnf_signed(true)
    }

    /// The negation normal form of `self` (`positive`) or of `!self`.
    fn nnf_signed(&self, positive: bool) -> Ltl {
        let b = |f: &Ltl, pos: bool| Box::new(f.nnf_signed(pos));
        match (self, positive) {
            (Ltl::True, true) | (Ltl::False, false) => Ltl::True,
            (Ltl::True, false) | (Ltl::False, true) => Ltl::False,
            (Ltl::Prop(p), true) => Ltl::Prop(*p),
            (Ltl::Prop(p), false) => Ltl::Not(Box::new(Ltl::Prop(*p))),
            (Ltl::Not(f), _) => f.nnf_signed(!positive),
            (Ltl::And(x, y), true) | (Ltl::Or(x, y), false) => {
                Ltl::And(b(x, positive), b(y, positive))
            }
            (Ltl::Or(x, y), true) | (Ltl::And(x, y), false) => {
                Ltl::Or(b(x, positive), b(y, positive))
            }
            (Ltl::Next(f), _) => Ltl::Next(b(f, positive)),
            (Ltl::Until(x, y), true) | (Ltl::Release(x, y), false) => {
                Ltl::Until(b(x, positive), b(y, positive))
            }
            (Ltl::Release(x, y), true) | (Ltl::Until(x, y), false) => {
                Ltl::Release(b(x, positive), b(y, positive))
            }
        }
    }

    /// One more than the highest proposition the formula names (0 if it names none): the
    /// number of propositions a caller must give a value in each letter.
    pub fn props(&self) -> u32 {
        match self {
            Ltl::True | Ltl::False => 0,
            Ltl::Prop(p) => p.saturating_add(1),
            Ltl::Not(f) | Ltl::Next(f) => f.props(),
            Ltl::And(a, b) | Ltl::Or(a, b) | Ltl::Until(a, b) | Ltl::Release(a, b) => {
                a.props().max(b.props())
            }
        }
    }

    /// The propositions the formula names, each once, sorted.
    pub fn named_props(&self) -> Vec<u32> {
        fn walk(f: &Ltl, out: &mut Vec<u32>) {
            match f {
                Ltl::True | Ltl::False => {}
                Ltl::Prop(p) => out.push(*p),
                Ltl::Not(a) | Ltl::Next(a) => walk(a, out),
                Ltl::And(a, b) | Ltl::Or(a, b) | Ltl::Until(a, b) | Ltl::Release(a, b) => {
                    walk(a, out);
                    walk(b, out);
                }
            }
        }
        let mut out = Vec::new();
        walk(self, &mut out);
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Its truth at a position whose propositions are `letter`'s, when it has no temporal
    /// operator (`None` when it has one: its truth depends on the positions after).
    pub fn at_letter(&self, letter: u64) -> Option<bool> {
        Some(match self {
            Ltl::True => true,
            Ltl::False => false,
            Ltl::Prop(p) => letter_has(letter, *p),
            Ltl::Not(f) => !f.at_letter(letter)?,
            Ltl::And(a, b) => a.at_letter(letter)? & b.at_letter(letter)?,
            Ltl::Or(a, b) => a.at_letter(letter)? | b.at_letter(letter)?,
            Ltl::Next(_) | Ltl::Until(..) | Ltl::Release(..) => return None,
        })
    }

    /// Whether the formula holds on the word `prefix · cycle^ω` (at its first position).
    ///
    /// The word has the positions `0..prefix.len() + cycle.len()`, each followed by the next
    /// one, the last by position `prefix.len()` (the start of the cycle). Each subformula is
    /// evaluated at every position, bottom-up; `U` is the least and `R` the greatest
    /// fixpoint of its one-step unfolding, iterated until stable. This is the reference
    /// semantics: written to be obviously right, not fast.
    ///
    /// `cycle` must not be empty (an empty cycle is no infinite word): in a debug build
    /// that panics, in a release build the answer is `false`.
    pub fn holds_on_lasso(&self, prefix: &[u64], cycle: &[u64]) -> bool {
        debug_assert!(!cycle.is_empty(), "a lasso's cycle is not empty");
        if cycle.is_empty() {
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
        self.eval(&word, &succ)[0]
    }

    /// The truth value of `self` at each position of `word`, whose successor function is
    /// `succ`.
    fn eval(&self, word: &[u64], succ: &dyn Fn(usize) -> usize) -> Vec<bool> {
        let n = word.len();
        match self {
            Ltl::True => vec![true; n],
            Ltl::False => vec![false; n],
            Ltl::Prop(p) => word.iter().map(|&l| letter_has(l, *p)).collect(),
            Ltl::Not(f) => f.eval(word, succ).into_iter().map(|v| !v).collect(),
            Ltl::And(a, b) => zip(a.eval(word, succ), b.eval(word, succ), |x, y| x && y),
            Ltl::Or(a, b) => zip(a.eval(word, succ), b.eval(word, succ), |x, y| x || y),
            Ltl::Next(f) => {
                let v = f.eval(word, succ);
                (0..n).map(|i| v[succ(i)]).collect()
            }
            Ltl::Until(a, b) => {
                let (a, b) = (a.eval(word, succ), b.eval(word, succ));
                fixpoint(vec![false; n], |v, i| b[i] || (a[i] && v[succ(i)]))
            }
            Ltl::Release(a, b) => {
                let (a, b) = (a.eval(word, succ), b.eval(word, succ));
                fixpoint(vec![true; n], |v, i| b[i] && (a[i] || v[succ(i)]))
            }
        }
    }
}

/// Whether proposition `p` holds in `letter` (never, for `p >= 64`).
fn letter_has(letter: u64, p: u32) -> bool {
    p < 64 && (letter >> p) & 1 == 1
}

fn zip(a: Vec<bool>, b: Vec<bool>, f: impl Fn(bool, bool) -> bool) -> Vec<bool> {
    a.into_iter().zip(b).map(|(x, y)| f(x, y)).collect()
}

/// Applies `step` at every position until no value changes. Started from all `false` this
/// is the least fixpoint, from all `true` the greatest (`step` is monotone in `v`).
fn fixpoint(mut v: Vec<bool>, step: impl Fn(&[bool], usize) -> bool) -> Vec<bool> {
    loop {
        let mut changed = false;
        for i in 0..v.len() {
            let x = step(&v, i);
            changed |= x != v[i];
            v[i] = x;
        }
        if !changed {
            return v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Ltl;

    const P: u64 = 1;
    const Q: u64 = 2;

    fn p() -> Ltl {
        Ltl::Prop(0)
    }
    fn q() -> Ltl {
        Ltl::Prop(1)
    }

    /// Checks `f` on each `(prefix, cycle, expected)`, and its negation normal form too.
    fn check(f: &Ltl, cases: &[(&[u64], &[u64], bool)]) {
        for &(prefix, cycle, expected) in cases {
            assert_eq!(
                f.holds_on_lasso(prefix, cycle),
                expected,
                "{f:?} on {prefix:?} ({cycle:?})^w"
            );
            assert_eq!(
                f.nnf().holds_on_lasso(prefix, cycle),
                expected,
                "nnf of {f:?} on {prefix:?} ({cycle:?})^w"
            );
            assert_eq!(
                Ltl::not(f.clone()).holds_on_lasso(prefix, cycle),
                !expected,
                "!{f:?} on {prefix:?} ({cycle:?})^w"
            );
        }
    }

    #[test]
    fn constants_and_propositions() {
        check(&Ltl::True, &[(&[], &[0], true)]);
        check(&Ltl::False, &[(&[], &[P], false)]);
        check(
            &p(),
            &[
                (&[P], &[0], true),
                (&[0], &[P], false),
                (&[], &[P, 0], true),
            ],
        );
        // A proposition beyond the 64 bits of a letter is false, not a panic.
        check(&Ltl::Prop(64), &[(&[], &[u64::MAX], false)]);
    }

    #[test]
    fn boolean_connectives() {
        check(
            &Ltl::and(p(), q()),
            &[(&[P | Q], &[0], true), (&[P], &[Q], false)],
        );
        check(
            &Ltl::or(p(), q()),
            &[(&[Q], &[0], true), (&[0], &[P | Q], false)],
        );
        check(
            &Ltl::implies(p(), q()),
            &[
                (&[0], &[0], true),
                (&[P], &[Q], false),
                (&[P | Q], &[0], true),
            ],
        );
        check(
            &Ltl::iff(p(), q()),
            &[
                (&[0], &[P], true),
                (&[P | Q], &[0], true),
                (&[Q], &[0], false),
            ],
        );
    }

    #[test]
    fn next_reads_across_the_loop_back() {
        let f = Ltl::next(p());
        check(&f, &[(&[0, P], &[0], true), (&[0], &[0], false)]);
        // Position 0 is the cycle's last position: its successor is the cycle's first.
        check(&f, &[(&[], &[P], true), (&[], &[0, 0, P], false)]);
        // From the last position of the cycle (X X X on a 2-prefix, 2-cycle word).
        let x4 = Ltl::next(Ltl::next(Ltl::next(Ltl::next(p()))));
        check(&x4, &[(&[0, 0], &[P, 0], true), (&[0, 0], &[0, P], false)]);
    }

    #[test]
    fn until_whose_right_side_holds_only_in_the_cycle() {
        let f = Ltl::until(p(), q());
        check(
            &f,
            &[
                (&[P, P], &[P, Q], true),
                (&[P, 0], &[Q], false),
                (&[], &[P], false),
                (&[Q], &[0], true),
                (&[P], &[P, P, Q], true),
            ],
        );
    }

    #[test]
    fn release_holds_forever_or_until_released() {
        let f = Ltl::release(p(), q());
        check(
            &f,
            &[
                (&[], &[Q], true),
                (&[Q, Q], &[P | Q], true),
                (&[Q, P], &[Q], false),
                (&[Q], &[Q, 0], false),
                (&[0], &[Q], false),
            ],
        );
    }

    #[test]
    fn weak_until_with_a_right_side_that_never_holds() {
        let f = Ltl::weak_until(p(), q());
        check(
            &f,
            &[
                (&[P], &[P], true),
                (&[P], &[P, 0], false),
                (&[P, P], &[Q], true),
                (&[0], &[Q], false),
            ],
        );
        // The same with a right side that is literally false: `[] p`.
        check(
            &Ltl::weak_until(p(), Ltl::False),
            &[(&[], &[P], true), (&[P], &[0], false)],
        );
    }

    #[test]
    fn always_and_eventually() {
        check(
            &Ltl::always(p()),
            &[(&[P], &[P, P], true), (&[P], &[P, 0], false)],
        );
        check(
            &Ltl::eventually(p()),
            &[(&[0], &[0, P], true), (&[0], &[0], false)],
        );
        let infinitely_often = Ltl::always(Ltl::eventually(p()));
        check(
            &infinitely_often,
            &[(&[], &[0, P], true), (&[P, P], &[0], false)],
        );
        let finally_forever = Ltl::eventually(Ltl::always(p()));
        check(
            &finally_forever,
            &[(&[0, 0], &[P], true), (&[], &[0, P], false)],
        );
    }

    #[test]
    fn a_formula_without_temporal_operators_is_read_on_one_letter() {
        let props = [
            Ltl::True,
            Ltl::False,
            p(),
            Ltl::not(q()),
            Ltl::and(p(), q()),
            Ltl::or(Ltl::not(p()), q()),
            Ltl::implies(p(), q()),
            Ltl::iff(p(), Ltl::not(q())),
        ];
        for f in &props {
            for letter in [0, P, Q, P | Q] {
                // On a word whose every position is `letter`, as on any other.
                let lasso = f.holds_on_lasso(&[letter], &[letter ^ P]);
                assert_eq!(f.at_letter(letter), Some(lasso), "{f:?} on {letter}");
            }
        }
        let temporal = [
            Ltl::next(p()),
            Ltl::always(p()),
            Ltl::and(p(), Ltl::eventually(q())),
            Ltl::not(Ltl::until(p(), q())),
        ];
        for f in &temporal {
            assert_eq!(f.at_letter(P), None, "{f:?}");
        }
    }

    #[test]
    fn leads_to() {
        let f = Ltl::leads_to(p(), q());
        check(
            &f,
            &[
                (&[], &[0], true),
                (&[P, 0], &[Q], true),
                (&[P | Q], &[0], true),
                (&[], &[P, 0, Q], true),
                (&[Q], &[P], false),
                (&[P, Q, P], &[0], false),
            ],
        );
    }

    #[test]
    fn constructors_fold_constants() {
        assert_eq!(Ltl::and(Ltl::True, p()), p());
        assert_eq!(Ltl::or(p(), Ltl::True), Ltl::True);
        assert_eq!(Ltl::not(Ltl::not(p())), p());
        assert_eq!(Ltl::until(p(), Ltl::False), Ltl::False);
        assert_eq!(Ltl::release(Ltl::True, q()), q());
        assert_eq!(Ltl::always(Ltl::True), Ltl::True);
        assert_eq!(Ltl::eventually(Ltl::False), Ltl::False);
    }

    #[test]
    fn nnf_has_negations_only_on_propositions() {
        fn only_on_props(f: &Ltl) -> bool {
            match f {
                Ltl::Not(g) => matches!(**g, Ltl::Prop(_)),
                Ltl::True | Ltl::False | Ltl::Prop(_) => true,
                Ltl::Next(g) => only_on_props(g),
                Ltl::And(a, b) | Ltl::Or(a, b) | Ltl::Until(a, b) | Ltl::Release(a, b) => {
                    only_on_props(a) && only_on_props(b)
                }
            }
        }
        let f = Ltl::Not(Box::new(Ltl::leads_to(
            Ltl::Not(Box::new(p())),
            Ltl::Next(Box::new(Ltl::Not(Box::new(Ltl::True)))),
        )));
        assert!(only_on_props(&f.nnf()));
        assert_eq!(Ltl::Not(Box::new(Ltl::True)).nnf(), Ltl::False);
    }

    #[test]
    fn props_counts_up_to_the_highest() {
        assert_eq!(Ltl::True.props(), 0);
        assert_eq!(Ltl::until(p(), Ltl::Prop(5)).props(), 6);
        assert_eq!(Ltl::not(Ltl::Prop(u32::MAX)).props(), u32::MAX);
    }
}
