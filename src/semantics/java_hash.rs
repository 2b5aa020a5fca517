//! Java's hash codes of Jason literals and `java.util.HashSet`'s iteration order: the order in
//! which Jason's belief update function (`Agent.buf`) queues percept events.
//!
//! `Agent.buf` copies the percepts into a `HashSet<StructureWrapperForLiteral>` and queues the
//! `+p` events in that set's iteration order; the `-p` events follow the iteration order of
//! `DefaultBeliefBase.percepts`, a `HashSet<Literal>` that lives as long as the agent. Both
//! orders depend on `hashCode()` of the literals and on `HashMap`'s bucket layout, reproduced
//! here: [`literal_hash`], [`hash_set_order`], [`JavaHashSet`].
//!
//! Annotations never enter a literal's hash (`Pred` does not override `calcHashCode`), so
//! `p`, `p[source(percept)]` and the wrapper `StructureWrapperForLiteral(p)` (whose
//! `hashCode` is `l.hashCode()`) all hash alike: [`literal_hash`] is also the hash of the
//! literal as stored in the belief base's `percepts` set.

/// A ground argument of a literal, as Jason builds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JArg<'a> {
    /// An atom (`Atom` or 0-ary `LiteralImpl`, same hash) in the default namespace.
    Atom(&'a str),
    /// A number as Jason's parser reads it from text (`ASSyntax.parseLiteral`, the lab's
    /// driver): a negative value is written `-N` and parsed as the unevaluated unary
    /// `ArithExpr(minus, N)` (as2j.arithm_expr_simple), which hashes as the structure `-(N)`.
    Num(f64),
    /// A `NumberTermImpl` with exactly this value (`ASSyntax.createNumber`, an environment
    /// written in Java): no `ArithExpr`, also for negative values.
    NumTerm(f64),
    /// A string (`StringTermImpl`).
    Str(&'a str),
    /// A positive compound term (`Structure`/`LiteralImpl`) in the default namespace.
    Struct(&'a str, &'a [JArg<'a>]),
}

/// `java.lang.String.hashCode`: `s[0]*31^(n-1) + … + s[n-1]` over UTF-16 code units, `int`
/// arithmetic (wrapping).
pub fn string_hash(s: &str) -> i32 {
    s.encode_utf16()
        .fold(0i32, |h, c| h.wrapping_mul(31).wrapping_add(i32::from(c)))
}

/// `Literal.DefaultNameSpace.calcHashCode`: `"default".hashCode()` (no namespace of its own).
fn default_ns_hash() -> i32 {
    string_hash("default")
}

/// `NumberTermImpl.calcHashCode`: `37 * (int) value`; Java's `(int)` of a double truncates
/// toward zero, saturates and maps NaN to 0, as Rust's `as i32` does.
fn number_hash(value: f64) -> i32 {
    37i32.wrapping_mul(value as i32)
}

/// `hashCode()` of one argument term.
pub fn arg_hash(arg: &JArg) -> i32 {
    match *arg {
        JArg::Atom(name) => structure_hash(name, &[]),
        JArg::Num(v) if v < 0.0 => structure_hash_with("-", &[number_hash(-v)]),
        JArg::Num(v) | JArg::NumTerm(v) => number_hash(v),
        // StringTermImpl.calcHashCode: value.hashCode()
        JArg::Str(s) => string_hash(s),
        JArg::Struct(functor, args) => structure_hash(functor, args),
    }
}

/// `Structure.calcHashCode` over `Atom.calcHashCode` (`functor.hashCode() + getNS().hashCode()`),
/// adding `(i+7) * arg_i.hashCode()`.
fn structure_hash_with(functor: &str, arg_hashes: &[i32]) -> i32 {
    let atom = string_hash(functor).wrapping_add(default_ns_hash());
    arg_hashes.iter().enumerate().fold(atom, |h, (i, &a)| {
        h.wrapping_add((i as i32).wrapping_add(7).wrapping_mul(a))
    })
}

fn structure_hash(functor: &str, args: &[JArg]) -> i32 {
    let hashes: Vec<i32> = args.iter().map(arg_hash).collect();
    structure_hash_with(functor, &hashes)
}

/// `hashCode()` of the positive literal `functor(args…)` in the default namespace, with or
/// without annotations (they do not enter it); also the hash of its
/// `StructureWrapperForLiteral` (`StructureWrapperForLiteral.hashCode`).
pub fn literal_hash(functor: &str, args: &[JArg]) -> i32 {
    structure_hash(functor, args)
}

/// `hashCode()` of the strongly negated literal `~functor(args…)`: `LiteralImpl.calcHashCode`
/// adds 3271 when negated.
pub fn negated_literal_hash(functor: &str, args: &[JArg]) -> i32 {
    literal_hash(functor, args).wrapping_add(3271)
}

/// `HashMap.hash`: the high half is xored into the low half before the bucket is taken.
fn spread(h: i32) -> u32 {
    let h = h as u32;
    h ^ (h >> 16)
}

/// `HashMap.DEFAULT_INITIAL_CAPACITY`: the table `resize()` allocates at the first insertion.
const INITIAL_CAPACITY: u32 = 16;
/// `HashMap.TREEIFY_THRESHOLD`: a bin that already holds this many nodes when one more is
/// appended is treeified (`putVal`: `binCount >= TREEIFY_THRESHOLD - 1`).
const TREEIFY_THRESHOLD: usize = 8;
/// `HashMap.MIN_TREEIFY_CAPACITY`: below it `treeifyBin` resizes instead.
const MIN_TREEIFY_CAPACITY: u32 = 64;

/// A `java.util.HashSet` (a `HashMap` with the default capacity 16 and load factor 0.75) of
/// elements known by an id and their `hashCode()`: which capacity its table has and in which
/// order it iterates, through any sequence of insertions, removals and clears.
///
/// No table is kept: within a bin the chain is always in insertion order (`putVal` appends at
/// the tail, `resize` splits a bin into lo/hi lists that keep their order, `removeNode`
/// unlinks), and the elements of one new bin all come from one old bin, so iteration (bins by
/// index, `HashIterator`) is the stable sort of the elements, in insertion order, by bin index.
/// Once a bin is treeified (9+ nodes in a table of 64+) its order depends on `TreeNode`'s
/// red-black tree (`moveRootToFront`, `compareTo` or `System.identityHashCode`): [`Self::order`]
/// then answers `None` until [`Self::clear`]. `MAXIMUM_CAPACITY` (2^30) is not modelled.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct JavaHashSet {
    /// Table length; 0 before the first insertion (`HashMap` allocates lazily).
    capacity: u32,
    /// (spread hash, id), in insertion order.
    entries: Vec<(u32, usize)>,
    /// Some bin was treeified: the order is no longer known.
    treeified: bool,
}

impl JavaHashSet {
    /// An empty set, as `new HashSet<>()`.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the set has no elements.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The table's length (0 before the first insertion); it never shrinks.
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Whether the element `id` is in the set.
    pub fn contains(&self, id: usize) -> bool {
        self.entries.iter().any(|&(_, e)| e == id)
    }

    fn bin(&self, spread_hash: u32) -> u32 {
        spread_hash & (self.capacity - 1)
    }

    /// `HashSet.add`: inserts the element `id` whose `hashCode()` is `hash`; false (and nothing
    /// changes) if `id` is already in. `id` equality stands for Java's `equals`.
    pub fn insert(&mut self, hash: i32, id: usize) -> bool {
        if self.contains(id) {
            return false;
        }
        if self.capacity == 0 {
            self.capacity = INITIAL_CAPACITY;
        }
        let h = spread(hash);
        let bin = self.bin(h);
        let before = self
            .entries
            .iter()
            .filter(|&&(e, _)| self.bin(e) == bin)
            .count();
        self.entries.push((h, id));
        // putVal -> treeifyBin, which resizes a small table instead
        if before >= TREEIFY_THRESHOLD {
            if self.capacity < MIN_TREEIFY_CAPACITY {
                self.capacity *= 2;
            } else {
                self.treeified = true;
            }
        }
        // putVal: `if (++size > threshold) resize()`, threshold = 0.75 * capacity
        if self.entries.len() > (self.capacity as usize / 4) * 3 {
            self.capacity *= 2;
        }
        true
    }

    /// `HashSet.remove` (also through an iterator): removes the element `id`; false if it was
    /// not in. The others keep their order and the capacity stays.
    pub fn remove(&mut self, id: usize) -> bool {
        match self.entries.iter().position(|&(_, e)| e == id) {
            Some(i) => {
                self.entries.remove(i);
                true
            }
            None => false,
        }
    }

    /// `HashSet.clear`: empties the set; the table keeps its length (`HashMap.clear`).
    pub fn clear(&mut self) {
        self.entries.clear();
        self.treeified = false;
    }

    /// The ids in the set's iteration order, or `None` if a bin was treeified.
    pub fn order(&self) -> Option<Vec<usize>> {
        if self.treeified {
            return None;
        }
        let mut entries = self.entries.clone();
        entries.sort_by_key(|&(h, _)| self.bin(h)); // stable: insertion order within a bin
        Some(entries.into_iter().map(|(_, id)| id).collect())
    }
}

/// Iteration order (indices into `hashes`) of a `new HashSet<>()` after adding elements with
/// these hash codes in this order, all distinct as elements (equal hashes are fine); `None` if
/// a bin was treeified (see [`JavaHashSet`]). Removing elements later (as `Agent.buf` does
/// with `perW.remove`) leaves the others in this order.
pub fn hash_set_order(hashes: &[i32]) -> Option<Vec<usize>> {
    let mut set = JavaHashSet::new();
    for (i, &h) in hashes.iter().enumerate() {
        set.insert(h, i);
    }
    set.order()
}

#[cfg(test)]
mod tests {
    //! Expected values printed by real Jason 3 (build/jason.jar of the lab, Java 17) with a
    //! throwaway program outside this repository: `hashCode()` of `ASSyntax.parseLiteral(..)`,
    //! of its `StructureWrapperForLiteral`, with `[source(percept)]` (all equal), and
    //! iteration orders of `HashSet<StructureWrapperForLiteral>` and of `Agent.buf`.
    use super::JArg::{Atom, Num, NumTerm, Str, Struct};
    use super::*;

    #[test]
    fn literal_hashes_match_jason() {
        assert_eq!(literal_hash("robotAt", &[Atom("table")]), 1612305639);
        assert_eq!(literal_hash("done", &[]), 1547893187);
        assert_eq!(
            literal_hash("cupAt", &[Atom("cup1"), Atom("table")]),
            -55534218
        );
        assert_eq!(literal_hash("count", &[Num(3.0)]), 1639656025);
        assert_eq!(literal_hash("count", &[Num(-2.0)]), -431615364);
        assert_eq!(literal_hash("v", &[Num(2.5)]), 1544804541);
        assert_eq!(literal_hash("v", &[Num(-2.5)]), -526466589);
        assert_eq!(literal_hash("n", &[Num(3e9)]), -602679892);
        assert_eq!(literal_hash("n", &[Num(-3e9)]), 1621011612);
        assert_eq!(literal_hash("name", &[Str("abc")]), 1548852090);
        assert_eq!(literal_hash("name", &[Str("é€😀")]), 1665441654);
        assert_eq!(literal_hash("name", &[Str("")]), 1548177612);
        assert_eq!(
            negated_literal_hash("robotAt", &[Atom("table")]),
            1612308910
        );
        let g = [Atom("a")];
        let h = [Atom("b"), Num(1.0)];
        assert_eq!(
            literal_hash("f", &[Struct("g", &g), Struct("h", &h)]),
            -2057274255
        );
        let ten = ["a", "b", "c", "d", "e", "f", "g", "h", "i", "j"].map(Atom);
        assert_eq!(literal_hash("p", &ten), -1191361585);
        assert_eq!(literal_hash("at", &[Atom("r1"), Atom("room2")]), -183326732);
        assert_eq!(literal_hash("holding", &[Atom("cup1")]), 586748080);
        // createNumber(3) is the parsed 3; a NumberTermImpl(-2) is 37 * -2
        assert_eq!(literal_hash("count", &[NumTerm(3.0)]), 1639656025);
        assert_eq!(
            literal_hash("count", &[NumTerm(-2.0)]),
            literal_hash("count", &[]).wrapping_add(7 * -74)
        );
    }

    fn at(i: usize, room: usize) -> i32 {
        literal_hash(
            "at",
            &[Atom(&format!("r{i}")), Atom(&format!("room{room}"))],
        )
    }
    fn count(i: usize) -> i32 {
        literal_hash("count", &[Num(i as f64)])
    }

    /// The order and final capacity Java printed for these hashes.
    fn check(hashes: &[i32], capacity: u32, expected: Option<&[usize]>) {
        let mut set = JavaHashSet::new();
        for (i, &h) in hashes.iter().enumerate() {
            assert!(set.insert(h, i));
        }
        assert_eq!(set.capacity(), capacity);
        assert_eq!(set.order().as_deref(), expected);
        assert_eq!(hash_set_order(hashes).as_deref(), expected);
    }

    #[test]
    fn small_sets_match_java() {
        let five = [
            literal_hash("robotAt", &[Atom("table")]),
            literal_hash("cupAt", &[Atom("cup1"), Atom("table")]),
            literal_hash("done", &[]),
            literal_hash("count", &[Num(3.0)]),
            literal_hash("name", &[Str("abc")]),
        ];
        check(&five, 16, Some(&[2, 3, 1, 4, 0]));
        let thirteen: Vec<i32> = (0..13).map(|i| at(i, i)).collect();
        check(
            &thirteen,
            32,
            Some(&[6, 10, 8, 12, 2, 4, 0, 7, 9, 11, 3, 5, 1]),
        );
        let mut thirty = Vec::new();
        for i in 0..10 {
            thirty.push(literal_hash(
                "cupAt",
                &[Atom(&format!("cup{i}")), Atom("table")],
            ));
            thirty.push(count(i));
            thirty.push(literal_hash("name", &[Str(&format!("n{i}"))]));
        }
        check(
            &thirty,
            64,
            Some(&[
                20, 3, 23, 6, 21, 28, 25, 26, 24, 19, 2, 22, 27, 29, 0, 10, 15, 16, 5, 13, 4, 11,
                18, 1, 7, 8, 14, 9, 17, 12,
            ]),
        );
    }

    #[test]
    fn hundred_numbers_match_java() {
        let hashes: Vec<i32> = (0..100).map(count).collect();
        #[rustfmt::skip]
        let expected = [
            35, 37, 36, 33, 32, 34, 30, 31, 27, 29, 28, 25, 24, 26, 22, 23, 19, 21, 20, 17, 16,
            18, 57, 56, 58, 54, 55, 51, 53, 52, 49, 48, 50, 46, 47, 43, 45, 44, 41, 40, 42, 38,
            39, 78, 79, 75, 77, 76, 73, 72, 74, 70, 71, 67, 69, 68, 65, 64, 66, 62, 63, 59, 61,
            60, 14, 99, 15, 97, 11, 96, 13, 98, 12, 9, 94, 8, 10, 95, 6, 91, 93, 7, 92, 89, 3,
            88, 5, 90, 4, 1, 86, 0, 2, 87, 83, 85, 84, 81, 80, 82,
        ];
        check(&hashes, 256, Some(&expected));
    }

    #[test]
    fn long_chains_match_java() {
        // 11 numbers in one bin of the 16-table: the 9th makes treeifyBin resize to 32
        let coll16: Vec<i32> = (0..11).map(|k| count(16 * k)).collect();
        check(&coll16, 32, Some(&[0, 2, 4, 6, 8, 10, 1, 3, 5, 7, 9]));
        // 30 others, then 8, 9, 10 numbers in one bin of the 64-table: treeified from 9 on
        let same_bin = [0, 128, 301, 429, 514, 642, 727, 855, 1068, 1196];
        let with = |k: usize| -> Vec<i32> {
            (0..30)
                .map(|i| at(i, 1))
                .chain(same_bin[..k].iter().map(|&i| count(i)))
                .collect()
        };
        #[rustfmt::skip]
        let eight = [
            24, 7, 17, 23, 16, 8, 22, 4, 15, 21, 14, 5, 29, 6, 20, 2, 13, 28, 12, 3, 27, 30, 31,
            32, 33, 34, 35, 36, 37, 11, 26, 10, 9, 0, 19, 25, 18, 1,
        ];
        check(&with(8), 64, Some(&eight));
        check(&with(9), 64, None);
        check(&with(10), 64, None);
    }

    #[test]
    fn the_table_doubles_when_its_size_passes_three_quarters_of_its_capacity() {
        // HashMap.putVal: `if (++size > threshold) resize()`, threshold = 0.75 * capacity.
        let mut set = JavaHashSet::new();
        let mut at_size = Vec::new();
        for i in 0..25 {
            set.insert(i as i32, i);
            at_size.push((set.len(), set.capacity()));
        }
        assert_eq!(at_size[11], (12, 16));
        assert_eq!(at_size[12], (13, 32));
        assert_eq!(at_size[23], (24, 32));
        assert_eq!(at_size[24], (25, 64));
    }

    #[test]
    fn removals_and_reinsertions_match_java() {
        let hashes: Vec<i32> = (0..20).map(|i| at(i, 1)).collect();
        let mut set = JavaHashSet::new();
        for (i, &h) in hashes.iter().enumerate().take(10) {
            set.insert(h, i);
        }
        for i in [0, 3, 4, 9] {
            assert!(set.remove(i));
        }
        assert!(!set.remove(9));
        for i in [9, 0, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 3] {
            assert!(set.insert(hashes[i], i));
        }
        assert!(!set.insert(hashes[3], 3));
        assert_eq!(set.capacity(), 32);
        let expected = [
            2, 13, 7, 17, 12, 3, 16, 8, 11, 15, 10, 9, 0, 19, 14, 5, 18, 6, 1,
        ];
        assert_eq!(set.order().unwrap(), expected);
        assert_eq!(set.len(), expected.len());
        assert!(!set.is_empty());
        set.clear();
        assert_eq!((set.len(), set.capacity()), (0, 32));
        assert!(set.is_empty());
    }

    /// `Agent.buf` over three cycles of percepts, with `DefaultBeliefBase.percepts` as a
    /// [`JavaHashSet`]: the events it queues and the `percepts` set's order afterwards.
    #[test]
    fn agent_buf_matches_jason() {
        let p = |text: &'static str, hash: i32| (text, hash);
        let robot = |place: &'static str, text| p(text, literal_hash("robotAt", &[Atom(place)]));
        let cycles = [
            vec![
                robot("table", "robotAt(table)"),
                p(
                    "cupAt(cup1,table)",
                    literal_hash("cupAt", &[Atom("cup1"), Atom("table")]),
                ),
                p(
                    "cupAt(cup2,shelf)",
                    literal_hash("cupAt", &[Atom("cup2"), Atom("shelf")]),
                ),
                p("holding(none)", literal_hash("holding", &[Atom("none")])),
                p("count(3)", count(3)),
                p("name(\"abc\")", literal_hash("name", &[Str("abc")])),
                p("door(open)", literal_hash("door", &[Atom("open")])),
            ],
            vec![
                robot("shelf", "robotAt(shelf)"),
                p(
                    "cupAt(cup1,table)",
                    literal_hash("cupAt", &[Atom("cup1"), Atom("table")]),
                ),
                p("holding(cup2)", literal_hash("holding", &[Atom("cup2")])),
                p("count(4)", count(4)),
                p("name(\"abc\")", literal_hash("name", &[Str("abc")])),
                p("door(open)", literal_hash("door", &[Atom("open")])),
                p("battery(80)", literal_hash("battery", &[Num(80.0)])),
            ],
            vec![
                robot("table", "robotAt(table)"),
                p(
                    "cupAt(cup1,table)",
                    literal_hash("cupAt", &[Atom("cup1"), Atom("table")]),
                ),
                p(
                    "cupAt(cup2,shelf)",
                    literal_hash("cupAt", &[Atom("cup2"), Atom("shelf")]),
                ),
                p("holding(none)", literal_hash("holding", &[Atom("none")])),
                p("count(3)", count(3)),
                p("door(closed)", literal_hash("door", &[Atom("closed")])),
            ],
        ];
        let expected = [
            (
                "+count(3) +cupAt(cup2,shelf) +cupAt(cup1,table) +door(open) +holding(none) \
                 +name(\"abc\") +robotAt(table)",
                "count(3) cupAt(cup2,shelf) cupAt(cup1,table) door(open) holding(none) \
                 name(\"abc\") robotAt(table)",
            ),
            (
                "-count(3) -cupAt(cup2,shelf) -holding(none) -robotAt(table) +robotAt(shelf) \
                 +count(4) +battery(80) +holding(cup2)",
                "cupAt(cup1,table) door(open) robotAt(shelf) count(4) name(\"abc\") battery(80) \
                 holding(cup2)",
            ),
            (
                "-door(open) -robotAt(shelf) -count(4) -name(\"abc\") -battery(80) \
                 -holding(cup2) +count(3) +cupAt(cup2,shelf) +holding(none) +door(closed) \
                 +robotAt(table)",
                "count(3) cupAt(cup2,shelf) cupAt(cup1,table) holding(none) door(closed) \
                 robotAt(table)",
            ),
        ];
        let mut names: Vec<&str> = Vec::new(); // id -> text
        let mut bb = JavaHashSet::new();
        for (percepts, (events, in_bb)) in cycles.iter().zip(expected) {
            let hashes: Vec<i32> = percepts.iter().map(|&(_, h)| h).collect();
            let per_w = hash_set_order(&hashes).unwrap();
            let mut queued = Vec::new();
            for id in bb.order().unwrap() {
                if !percepts.iter().any(|&(t, _)| t == names[id]) {
                    queued.push(format!("-{}", names[id]));
                    bb.remove(id);
                }
            }
            for i in per_w {
                let (text, hash) = percepts[i];
                let id = names.iter().position(|&n| n == text).unwrap_or_else(|| {
                    names.push(text);
                    names.len() - 1
                });
                if bb.insert(hash, id) {
                    queued.push(format!("+{text}"));
                }
            }
            assert_eq!(queued.join(" "), events);
            let order: Vec<&str> = bb
                .order()
                .unwrap()
                .into_iter()
                .map(|id| names[id])
                .collect();
            assert_eq!(order.join(" "), in_bb);
        }
    }
}
